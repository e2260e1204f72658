"""Reports of a tooth-pair solve: the JSON summary (``fegear solve --json``), the short table
``fegear solve`` prints, and the rows, extremes and table of a mesh cycle."""

from __future__ import annotations

import math
from dataclasses import fields

from .. import quantities
from ..fe import Allowables
from ..quantities import FACTORS, HELD
from .case import HEADLINE, PairSolution, SolveCase, ToothResult
from .safety import (
    ALLOWABLE_KEYS,
    DEFAULT_ALLOWABLES,
    SAFETY,
    safety_factors,
    smallest,
    with_safety,
)

#: the product case's fields; a summary records a peer's further inputs by their names
SOLVE_FIELDS = {f.name for f in fields(SolveCase)}


def pair_summary(sol: PairSolution, estimate: dict | None = None, wall_s: float | None = None,
                 coarse_quality: str | None = None,
                 allowables: Allowables = DEFAULT_ALLOWABLES) -> dict:
    """The JSON summary: inputs, headline stresses and the safety factors at ``allowables``
    (:mod:`.safety`), per-tooth results and checks."""
    loaded = [t for t in sol.teeth if t.load_N > 0]
    peak = max(loaded, key=lambda t: t.p_max_MPa)
    out = {
        "inputs": _inputs(sol.case),
        **sol.headline(),
        **dict.fromkeys(SAFETY),           # with_safety fills them in
        "contact_peak_on_tip_round": peak.peak_on_round,
        "edge_contact": _edge_summary(loaded),
        "hertz_p0_MPa": peak.hertz_p0_MPa,
        "hertz_b_over_R": peak.b_over_R,
        "teeth_in_contact": sol.teeth_in_contact,
        "load_share": {str(t.tooth): t.load_share for t in loaded},
        "transmission_error_urad": 1e6 * (sol.rotation - sol.first_touch),
        "rotation_urad": 1e6 * sol.rotation,
        "first_touch_urad": 1e6 * sol.first_touch,
        "mesh_stiffness_Nm_per_rad": sol.mesh_stiffness,
        "tangent_stiffness_Nm_per_rad": _number(sol.tangent_stiffness),
        "error_estimate_pct": max(estimate.values()) if estimate else None,
        "error_estimate_by_stress_pct": estimate,
        "error_estimate_from": coarse_quality,
        "torque_balance_error": sol.checks.balance_error,
        "load_share_sum": sum(t.load_share for t in sol.teeth),
        "max_penetration_um": 1e3 * sol.checks.max_penetration,
        "iterations": sol.checks.iterations,
        "body_residuals": list(sol.checks.residuals),
        "dofs": sol.dofs,
        "contact_points": sol.checks.points,
        "teeth": [_tooth_row(t) for t in sol.teeth],
        "timings_s": sol.timings_s,
        "wall_s": wall_s,
    }
    return with_safety(out, allowables)


def _inputs(c: SolveCase) -> dict:
    """The summary's ``inputs``: the case's, by their summary names."""
    p = c.params
    return {"m": p.m, "z1": p.z1, "z2": p.z2, "h1": p.h1, "f1": p.f1, "shift": p.shift,
            "rotation": p.rotation, "tip_clearance": p.tip_clearance,
            "relief_um": p.relief, "relief_extent_mm": p.relief_extent,
            "relief_start_mm": p.relief_start, "relief_shape": p.relief_shape,
            "torque_Nm": c.torque,
            "position_deg": math.degrees(c.beta), "thickness_mm": c.thickness,
            "E_MPa": c.E, "nu": c.nu, "quality": c.quality,
            "tip_round_mm": c.edge_radius,
            "rim1_mm": c.rims[0], "rim2_mm": c.rims[1], "extra_pairs": c.extra_pairs,
            "deviations": c.deviations.summary(),
            # a peer's own inputs (the sector model's extra teeth and penalty factor)
            **{f.name: getattr(c, f.name) for f in fields(c) if f.name not in SOLVE_FIELDS}}


def add_tooth_estimates(summary: dict, estimates: dict[int, dict[str, float]] | None) -> None:
    """Each loaded tooth of ``summary`` with its own error estimate (%; :func:`~.estimate.
    tooth_estimates`): ``error_estimate_pct`` the largest of its stresses', and by stress
    under the summary's names; None without an estimate."""
    names = {h.attribute: h.tooth_key for h in HELD}
    for t in summary["teeth"]:
        own = (estimates or {}).get(t["tooth"])
        t["error_estimate_pct"] = max(own.values()) if own else None
        t["error_estimate_by_stress_pct"] = (None if own is None else
                                             {names[k]: v for k, v in own.items()})


def _tooth_row(t: ToothResult) -> dict:
    """One tooth's entry in the summary's ``teeth``."""
    return {"tooth": t.tooth, "clearance_um": t.clearance_um, "load_N": t.load_N,
            "load_share": t.load_share, "p_max_MPa": t.p_max_MPa,
            "half_width_mm": t.half_width_mm, "hertz_p0_MPa": t.hertz_p0_MPa,
            "hertz_b_mm": t.hertz_b_mm, "b_over_R": t.b_over_R,
            "root_stress_gear1_MPa": t.root1_MPa, "root_stress_gear2_MPa": t.root2_MPa,
            "peak_on_tip_round": t.peak_on_round,
            "flank_pressure_MPa": t.flank_p_MPa, "edge_pressure_MPa": t.edge_p_MPa,
            "edge_load_N": t.edge_load_N, "edge_contact": t.edge_contact,
            "halfplane_p_MPa": t.halfplane_p_MPa,
            "halfplane_flank_MPa": t.halfplane_flank_MPa,
            "bending_curvature": t.bending_curvature,
            "points_per_half_width": t.per_half_width, "resolved": t.resolved,
            "gear2_tooth": t.tooth2}


#: the safety factors the per-tooth and cycle tables show (S_F1, S_F2, S_H); the pair's
#: table shows every one of :data:`~fegear.quantities.FACTORS`
TABLE_SAFETY = ("safety_bending_gear1", "safety_bending_gear2", "safety_contact")


def factor_cell(s: float | None) -> str:
    """A safety factor in at most four characters, so that its column keeps its width: two
    decimals below 10, one below 100, none below 1000, ">999" above (a tooth that barely
    carries load; summary.json keeps the value); "-" where there is none (no load)."""
    if s is None:
        return "-"
    for decimals, below in ((2, 10), (1, 100), (0, 1000)):
        if round(s, decimals) < below:
            return f"{s:.{decimals}f}"
    return ">999"


def stiffness_cell(k: float) -> str:
    """A mesh stiffness (N·m/rad) in one format whatever its value: four significant digits
    and the exponent (``5.500e+05``, not ``5.5e+05`` beside ``5.676e+05``)."""
    return f"{k:.3e}"


def aligned_table(head: list[str], rows: list[list[str]], labels: int = 0) -> list[str]:
    """A markdown table whose columns stay aligned on a terminal for any value: each column
    as wide as its widest cell or header, the first ``labels`` columns left-aligned, the
    others (numbers) right-aligned."""
    widths = [max(len(c) for c in column) for column in zip(head, *rows)]

    def line(cells):
        return "| " + " | ".join(c.ljust(w) if k < labels else c.rjust(w)
                                 for k, (c, w) in enumerate(zip(cells, widths))) + " |"

    rule = "|" + "|".join("-" * (w + 2) if k < labels else "-" * (w + 1) + ":"
                          for k, w in enumerate(widths)) + "|"
    return [line(head), rule, *(line(r) for r in rows)]


def safety_table(summary: dict) -> list[str]:
    """The pair's safety factors beside the allowables and the stresses they divide, and a
    line where the tip round's pressure sets S_H or a factor is below 1."""
    i = summary["inputs"]
    allowable = {w: i[k] for w, k in ALLOWABLE_KEYS.items()}
    edge = summary["contact_peak_on_tip_round"]
    rows = []
    for k, f in FACTORS.items():
        mark = "e" if edge and k == "safety_contact" else " "
        rows.append([f"{f.label} ({f.stress.short})", factor_cell(summary[k]),
                     f"{allowable[f.stress.allowable]:.0f}",
                     f"{summary[f.stress.key]:.1f}{mark}"])
    lines = aligned_table(["safety factor [-]      ", "    S", "allowable MPa", "stress MPa"],
                          rows, labels=1)
    notes = []
    if edge:
        notes.append("e: the peak pressure, and so S_H, sits on a tip round (EDGE CONTACT "
                     "below); S_H flank is the flanks' own.")
    low = [f.label for k, f in FACTORS.items() if summary[k] is not None and summary[k] < 1.0]
    if low:
        notes.append(f"{', '.join(low)} below 1: the stress exceeds the allowable.")
    return lines + ([" ".join(notes)] if notes else [])


def _edge_summary(loaded) -> dict:
    """Which teeth press on their tip round, how hard and with how much of the load."""
    edge = [t for t in loaded if t.edge_contact]
    total = sum(t.load_N for t in loaded)
    on_rounds = sum(t.edge_load_N for t in edge)
    return {"teeth": [t.tooth for t in edge], "load_N": on_rounds,
            "load_fraction": on_rounds / total if total > 0 else 0.0,
            "max_pressure_MPa": max((t.edge_p_MPa for t in edge), default=0.0)}


def pair_table(summary: dict) -> str:
    """Short plain-text report of a summary (the `fegear solve` output)."""
    i = summary["inputs"]
    est = summary["error_estimate_by_stress_pct"] or {}
    lines = [
        f"pair m {i['m']:g}, z {i['z2']}/{i['z1']}, h1 {i['h1']:g}, f1 {i['f1']:g}, "
        f"shift {i['shift']:g}, rotation {i['rotation']:g} mm; T {i['torque_Nm']:g} N·m at "
        f"β {i['position_deg']:g}°, t {i['thickness_mm']:g} mm, quality {i['quality']}, "
        f"tip round {i['tip_round_mm']:g} mm"
        + (f", tip relief {i['relief_um']:g} µm {i['relief_shape']}"
           + (f" over {i['relief_extent_mm']:g} mm" if i["relief_extent_mm"] else
              f" from r {i['relief_start_mm']:g} mm") if i["relief_um"] else "")
        + (f"; deviations: {words}" if (words := deviations_words(i.get("deviations"))) else ""),
        "",
        *aligned_table(["headline [MPa]         ", "     FE", "err est %"],
                       [[label, f"{summary[k]:.1f}", f"{est[k]:.2f}" if k in est else "-"]
                        for k, label in HEADLINE.items()], labels=1),
        "", *safety_table(summary), "",
        *aligned_table(list(TOOTH_HEAD), [_tooth_cells(t) for t in summary["teeth"]
                                          if t["load_N"] > 0]),
    ]
    return "\n".join(lines + _notes(summary) + _checks(summary))


def _notes(summary: dict) -> list[str]:
    """The notes under the pair's table: edge contact, under-resolved contacts and what the
    columns err % and p ref mean, where they apply."""
    lines = []
    edge = summary["edge_contact"]
    if edge["teeth"]:
        lines += ["", f"EDGE CONTACT: the tip rounds of teeth {edge['teeth']} carry "
                  f"{edge['load_N']:.1f} N ({100 * edge['load_fraction']:.1f} % of the normal "
                  f"load) at up to {edge['max_pressure_MPa']:.0f} MPa, a pressure set by the "
                  "round's radius (--tip-round); the flank pressure beside it is the flank's "
                  "own. A tip relief keeps the load off the round (--relief; `fegear relief` "
                  "sizes one). e: the tooth's peak is on its round."]
    coarse = [t for t in summary["teeth"] if t["load_N"] > 0 and not t.get("resolved", True)]
    if coarse:
        lines += ["", "UNDER-RESOLVED (u): " + ", ".join(
            f"tooth {t['tooth']} has {t['points_per_half_width']:.1f}" for t in coarse)
            + " grid points or elements across its half-width (on a round, the round's), fewer "
            f"than `{summary['inputs']['quality']}` needs for a converged pressure "
            "(docs/model.md, \"Under-resolved contacts\"); a finer --quality resolves it."]
    if any(t.get("error_estimate_pct") is not None for t in summary["teeth"]):
        lines += ["", "err %: each loaded tooth's own discretisation-error estimate, the "
                  "largest of its root stresses' and pressures', from the same tooth solved "
                  f"at `{summary['error_estimate_from']}` (a lightly loaded tooth is resolved "
                  "more coarsely than the headline's)."]
    if any(t.get("halfplane_flank_MPa") for t in summary["teeth"]):
        lines += ["", "p ref: the flank pressure of two half-planes with the teeth's exact gap, "
                  "bent as the teeth bend, under the same load (Hertz without its constant "
                  "curvature and rigid teeth; docs/model.md, \"Hertz at load\")."]
    return lines


def _checks(summary: dict) -> list[str]:
    """The lines under the notes: the contact's checks, the transmission error and the mesh
    stiffness, the problem's size and the times."""
    unloaded = [t["tooth"] for t in summary["teeth"] if t["load_N"] <= 0]
    return ["",
            f"teeth in contact {summary['teeth_in_contact']} (paired but open: {unloaded}); "
            f"load shares sum to {summary['load_share_sum']:.6f}; torque balance error "
            f"{summary['torque_balance_error']:.1e}",
            f"transmission error {summary['transmission_error_urad']:.1f} µrad (rotation "
            f"{summary['rotation_urad']:.1f}, first touch {summary['first_touch_urad']:.1f}); "
            f"mesh stiffness {stiffness_cell(summary['mesh_stiffness_Nm_per_rad'])} N·m/rad"
            + _tangent(summary),
            f"DOFs {summary['dofs']}, contact points {summary['contact_points']}, "
            f"iterations {summary['iterations']}, max penetration "
            f"{summary['max_penetration_um']:.3g} µm",
            "time [s]: " + ", ".join(f"{k} {v:.2f}" for k, v in summary["timings_s"].items() if v)
            + _estimate_time(summary)
            + (f"; solve wall {summary['wall_s']:.1f}" if summary["wall_s"] else "")]


#: the per-tooth table's headers, each as wide as its column's usual values
TOOTH_HEAD = ("tooth", "clear. µm", "load N", "share", quantities.PEAK.head,
              quantities.FLANK.short, "p ref ", quantities.EDGE_PRESSURE.short,
              quantities.EDGE_LOAD.head, "b mm  ", "Hertz p0", "b/R*  ", quantities.ROOT1.short,
              quantities.ROOT2.short, *(FACTORS[k].symbol.ljust(5) for k in TABLE_SAFETY),
              "err %")


def _tooth_cells(t: dict) -> list[str]:
    """One loaded tooth's row of the per-tooth table: ``e`` after a peak on the tip round,
    ``u`` after an under-resolved half-width, "-" where a value does not apply."""
    ref = t.get("halfplane_flank_MPa")
    return [str(t["tooth"]), f"{t['clearance_um']:z.2f}", f"{t['load_N']:.0f}",
            f"{t['load_share']:.3f}",
            f"{t['p_max_MPa']:.1f}" + ("e" if t["peak_on_tip_round"] else " "),
            f"{t['flank_pressure_MPa']:.1f}", f"{ref:.0f}" if ref else "-",
            f"{t['edge_pressure_MPa']:.0f}" if t["edge_contact"] else "-",
            f"{t['edge_load_N']:.1f}" if t["edge_contact"] else "-",
            f"{t['half_width_mm']:.3f}" + (" " if t.get("resolved", True) else "u"),
            f"{t['hertz_p0_MPa']:.1f}" if t["hertz_p0_MPa"] else "-",
            f"{t['b_over_R']:.4f}" if t["b_over_R"] else "-",
            f"{t['root_stress_gear1_MPa']:.0f}", f"{t['root_stress_gear2_MPa']:.0f}",
            *(factor_cell(t.get(k)) for k in TABLE_SAFETY), _estimate_cell(t)]


def _estimate_cell(t: dict) -> str:
    """A tooth's own error estimate (%): one decimal, none from 100, "-" without one."""
    e = t.get("error_estimate_pct")
    return "-" if e is None else f"{e:.1f}" if e < 100 else ">99"


def _number(v: float) -> float | None:
    """``v``, or None for NaN (a value the model did not compute; JSON has no NaN)."""
    return None if math.isnan(v) else v


def _tangent(summary: dict) -> str:
    k = summary.get("tangent_stiffness_Nm_per_rad")
    return ("" if k is None else
            f" secant, {stiffness_cell(k)} tangent (dT/dθ, the contact set kept)")


def deviations_words(d: dict | None) -> str:
    """A summary's deviations in words, comma-separated (none: the empty text)."""
    if not d:
        return ""
    parts = [f"gear {g} tooth {t} {k.split('_')[0]} {v:+g} µm"
             for g in (1, 2) for t, tooth in d[f"gear{g}"].items()
             for k, v in tooth.items() if k.endswith("_um") and v]
    parts += [f"gear {g} tooth {t} a measured form" for g in (1, 2)
              for t, tooth in d[f"gear{g}"].items() if "form_curve_um" in tooth]
    if d["centre_distance_um"]:
        parts.append(f"centre distance {d['centre_distance_um']:+g} µm")
    parts += [f"gear {g} runout {d[f'runout{g}']['fr_um']:g} µm at "
              f"{d[f'runout{g}']['phase_deg']:g}°" for g in (1, 2) if d[f"runout{g}"]["fr_um"]]
    return ", ".join(parts)


def _estimate_time(summary: dict) -> str:
    """The error estimate's time after the solve (its second solve may have run in parallel
    with the first) in the time line, if there was one."""
    if not summary.get("estimate_s"):
        return ""
    return (f"; error estimate (the case again at {summary['error_estimate_from']}) "
            f"{summary['estimate_s']:.2f} after the solve")


def cycle_rows(sols, allowables: Allowables = DEFAULT_ALLOWABLES) -> list[dict]:
    """One row per position of a :func:`fegear.toothpair.solve_positions` run: headline
    stresses (whether the von Mises stress is the surface estimate: no submodel there), the
    safety factors at ``allowables``, transmission error, stiffness, teeth in contact and
    ``share_<tooth>`` for every paired tooth."""
    teeth = sorted({t.tooth for s in sols for t in s.teeth})
    rows = []
    for s in sols:
        share = {t.tooth: t.load_share for t in s.teeth}
        rows.append({"position_deg": math.degrees(s.case.beta), **s.headline(),
                     **safety_factors(s.headline(), allowables),
                     "von_mises_estimated": s.von_mises_estimated,
                     "edge_load_N": sum(t.edge_load_N for t in s.teeth),
                     "transmission_error_urad": 1e6 * (s.rotation - s.first_touch),
                     "rotation_urad": 1e6 * s.rotation, "first_touch_urad": 1e6 * s.first_touch,
                     "mesh_stiffness_Nm_per_rad": s.mesh_stiffness,
                     "tangent_stiffness_Nm_per_rad": _number(s.tangent_stiffness),
                     "teeth_in_contact": s.teeth_in_contact,
                     "torque_balance_error": s.checks.balance_error,
                     **{f"share_{t}": share.get(t, 0.0) for t in teeth}})
    return rows


def cycle_summary(rows: list[dict]) -> dict:
    """Extremes over the cycle: the largest of each headline stress and where it occurs, the
    smallest safety factors and where, transmission-error and stiffness range, teeth in
    contact."""
    out = {}
    for k in HEADLINE:
        worst = max(rows, key=lambda r: r[k])
        out[k] = {"max": worst[k], "at_position_deg": worst["position_deg"]}
    out.update(smallest(rows))
    for k in ("transmission_error_urad", "mesh_stiffness_Nm_per_rad",
              "tangent_stiffness_Nm_per_rad"):
        v = [r[k] for r in rows if r.get(k) is not None]
        if not v:
            continue
        out[k] = {"min": min(v), "max": max(v), "mean": sum(v) / len(v),
                  "peak_to_peak": max(v) - min(v)}
    n = [r["teeth_in_contact"] for r in rows]
    out["teeth_in_contact"] = {"min": min(n), "max": max(n)}
    return out

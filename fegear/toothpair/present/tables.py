"""The tables ``fegear solve`` prints of a pair (:func:`pair_table`: the design, the headline
stresses with their error estimate, the safety factors, the loaded teeth, the notes and
checks) from its summary (:mod:`..summary`), and the cells and aligned tables the analyses'
tables share (:func:`aligned_table`, :func:`factor_cell`, :func:`stiffness_cell`,
:func:`deviations_words`)."""

from __future__ import annotations

from ... import quantities
from ...quantities import FACTORS
from ..case import HEADLINE
from ..safety import ALLOWABLE_KEYS

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



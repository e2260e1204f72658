"""The JSON summary of a tooth-pair solve (``fegear solve --json``, summary.json, a study's
record): the pictured position's inputs, headline stresses, safety factors, per-tooth results
and checks (:func:`pair_summary`), each tooth's own error estimate
(:func:`add_tooth_estimates`), and a mesh cycle's rows and extremes (:func:`cycle_rows`,
:func:`cycle_summary`). Numbers only: the tables that print them are the presentation's
(:mod:`.present.tables`)."""

from __future__ import annotations

import math
from dataclasses import fields

from ..fe import Allowables
from ..quantities import HELD
from .case import HEADLINE, PairSolution, SolveCase, ToothResult
from .safety import DEFAULT_ALLOWABLES, SAFETY, safety_factors, smallest, with_safety

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


def _edge_summary(loaded) -> dict:
    """Which teeth press on their tip round, how hard and with how much of the load."""
    edge = [t for t in loaded if t.edge_contact]
    total = sum(t.load_N for t in loaded)
    on_rounds = sum(t.edge_load_N for t in edge)
    return {"teeth": [t.tooth for t in edge], "load_N": on_rounds,
            "load_fraction": on_rounds / total if total > 0 else 0.0,
            "max_pressure_MPa": max((t.edge_p_MPa for t in edge), default=0.0)}


def _number(v: float) -> float | None:
    """``v``, or None for NaN (a value the model did not compute; JSON has no NaN)."""
    return None if math.isnan(v) else v


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

"""What a designer reads at the end of a search: the best designs solved again at ``standard``
over the same cycle with the error estimate, beside the baseline and the relieved baseline,
each with what limits it, and the ``fegear solve`` line that gives its numbers.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from pathlib import Path

from .. import quantities
from ..quantities import HELD
from ..toothpair import (
    prepare_job,
    solve_command,
    solve_job,
    stiffness_cell,
    write_job,
    write_report,
)
from .design import carrying_tooth
from .space import Space

#: the relief ``fegear relief`` sizes for the seed pair at 200 N·m (docs/solve.md): the
#: relieved baseline a search is compared with
BASELINE_RELIEF = {"relief": 3.0, "relief-extent": 0.5, "tip-clearance": 0.02}
#: the safety factors a design is judged by, by the cycle summary's keys, each under its
#: name in the final table (:attr:`~fegear.quantities.Factor.name`)
FACTORS = {quantities.FACTORS[k].name: k for k in ("safety_bending_gear1", "safety_bending_gear2",
                                                    "safety_contact_flank", "safety_contact")}
CHECK_QUALITY = "standard"


def resolve(values: Mapping, positions: int, out: Path | None) -> dict:
    """``values`` solved at ``standard`` over ``positions`` rolling angles with the error
    estimate, as ``fegear solve`` does (its files in ``out`` unless None): a row of the
    final table. ``safety`` is the smallest of every safety factor over the cycle, S_H with
    a loaded tip round included (for a design that keeps its rounds unloaded, the search's
    objective); ``limited_by`` names it, with the rolling angle and the tooth."""
    inputs = {**values, "quality": CHECK_QUALITY, "positions": positions}
    solved = solve_job(prepare_job(inputs))
    if out is not None:   # its files and its one-page report
        files = write_job(solved, out, fields=False, pictures=True)
        write_report(solved.summary, files, out, solve_command(inputs))
    c, s = solved.summary["cycle"], solved.summary
    row = {"inputs": dict(values), "command": solve_command(inputs)}
    for name, key in FACTORS.items():
        row[name] = c[key]["min"]
        row[f"{name}_beta_deg"] = c[key]["at_position_deg"]
    have = [k for k in FACTORS if row[k] is not None]
    limit = min(have, key=lambda k: row[k])
    row["safety"], row["limited_by"] = row[limit], limit
    row["limited_tooth"] = _tooth(solved.solutions, row[f"{limit}_beta_deg"], limit)
    row["edge_load_N"] = max(r["edge_load_N"] for r in c["rows"])
    for q in HELD:
        row[q.key] = c[q.key]["max"]
    row["estimate_pct"] = s.get("error_estimate_by_stress_pct") or {}
    row["te_p2p_urad"] = c["transmission_error_urad"]["peak_to_peak"]
    row["stiffness_Nm_per_rad"] = c["mesh_stiffness_Nm_per_rad"]["mean"]
    return row


def _tooth(solutions, beta_deg: float, factor: str) -> int:
    """The gear-1 tooth that sets ``factor`` at the rolling angle ``beta_deg``."""
    sol = min(solutions, key=lambda x: abs(math.degrees(x.case.beta) - beta_deg))
    return carrying_tooth(sol, quantities.FACTORS[FACTORS[factor]].stress.key)


def baselines(space: Space) -> dict[str, dict]:
    """The baseline (the fixed inputs, the varied ones at their defaults) and the relieved
    baseline (:data:`BASELINE_RELIEF` on it) as inputs by name."""
    varied = {v.name for v in space.variables}
    base = {k: v for k, v in space.fixed.items() if k not in varied}
    return {"baseline": base, "relieved baseline": {**base, **BASELINE_RELIEF}}


def final_table(rows: Mapping[str, dict], space: Space) -> str:
    """Markdown: a row a design (name → :func:`resolve` row), its varied inputs, the smallest
    safety factors over the cycle, the largest estimate of the stresses behind them, the load on
    the tip rounds, the transmission error's peak to peak and the mean mesh stiffness over the
    cycle, and what limits it."""
    names = [v.name for v in space.variables]
    head = ("| design | " + " | ".join(names) + " | S_F1 | S_F2 | S_H flank | S_H | smallest "
            "| gain % | est. % | tip rounds N | TE p-p µrad | k N·m/rad | limited by |")
    lines = [head, "|---|" + "---:|" * (len(names) + 10) + "---|"]
    ref = rows.get("relieved baseline", {}).get("safety")
    for label, r in rows.items():
        values = [r["inputs"].get(n) for n in names]
        est = r["estimate_pct"]
        worst = max((est.get(k) or 0.0) for k in ("root_stress_gear1_MPa",
                                                  "root_stress_gear2_MPa",
                                                  "contact_pressure_MPa",
                                                  "flank_contact_pressure_MPa"))
        gain = (f"{100 * (r['safety'] / ref - 1):+.1f}" if ref and label != "relieved baseline"
                else "-")
        where = (f"{r['limited_by']}, tooth {r['limited_tooth']}, β "
                 f"{r[r['limited_by'] + '_beta_deg']:.2f}°")
        lines.append(f"| {label} | " + " | ".join("-" if v is None else f"{v:.4g}"
                                                  for v in values)
                     + f" | {_f(r['S_F1'])} | {_f(r['S_F2'])} | {_f(r['S_H_flank'])} | "
                       f"{_f(r['S_H'])} | **{_f(r['safety'])}** | {gain} | {worst:.1f} | "
                       f"{r['edge_load_N']:.1f} | {r['te_p2p_urad']:.1f} | "
                       f"{stiffness_cell(r['stiffness_Nm_per_rad'])} | {where} |")
    return "\n".join(lines)


def _f(v) -> str:
    return "-" if v is None or not math.isfinite(v) else f"{v:.2f}"


#: the headline stresses of the final table: those held against an allowable
HEADLINES = {q.key: q.label for q in HELD}


def headline_table(rows: Mapping[str, dict]) -> str:
    """Markdown: each design's headline stresses, the largest over the cycle (MPa), each with
    its error estimate (%, `standard` against the next coarser level, at the position of the
    largest gear-1 root stress)."""
    lines = ["| design | " + " | ".join(HEADLINES.values()) + " |",
             "|---|" + "---:|" * len(HEADLINES)]
    for label, r in rows.items():
        est = r["estimate_pct"]
        lines.append(f"| {label} | " + " | ".join(
            f"{r[k]:.1f} ± {est[k]:.1f} %" if est.get(k) is not None else f"{r[k]:.1f}"
            for k in HEADLINES) + " |")
    return "\n".join(lines)

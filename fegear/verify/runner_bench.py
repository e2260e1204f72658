"""The study runner's own cost: a small study of real solves, timed against its solves.

Target (issue 6): the runner's per-case overhead (everything but the solve: worker hand-off,
validation in the worker, records, progress) under 5 % of the solve time. The one-off costs,
starting the worker processes and writing the table and plots, are reported beside it.
"""

from __future__ import annotations

import tempfile
from pathlib import Path

from ..geometry import PairParameters
from ..study import StudyReport, build_study, run_study

OVERHEAD_TARGET_PCT = 5.0


def study_overhead(params: PairParameters, cases: int, workers: int = 1,
                   quality: str = "coarse") -> StudyReport:
    """Run ``cases`` solves of ``params`` (torques 10, 20, … N·m, no second level) as a study
    in a temporary directory and return its report."""
    base = {"m": params.m, "z1": params.z1, "z2": params.z2, "h1": params.h1, "f1": params.f1,
            "shift": params.shift, "rotation": params.rotation, "quality": quality,
            "no-estimate": True}
    if params.tip_clearance is not None:
        base["tip-clearance"] = params.tip_clearance
    doc = {"study": {"name": "bench"}, "base": base,
           "sweep": [{"torque": [10.0 * (i + 1) for i in range(cases)]}]}
    with tempfile.TemporaryDirectory(prefix="fegear-bench-study-") as tmp:
        study = build_study(doc, Path(tmp) / "bench.toml")
        return run_study(study, Path(tmp) / "out", workers=workers, progress=False)


def overhead_table(r: StudyReport, workers: int) -> str:
    """Markdown table of a :func:`study_overhead` report and the target line."""
    mean = r.solve_s / max(r.computed, 1)
    pct = 100.0 * r.overhead_per_case_s / mean if mean else float("nan")
    status = "met" if pct < OVERHEAD_TARGET_PCT else "MISSED"
    return "\n".join([
        "### Study runner overhead",
        "",
        "| cases | workers | study wall [s] | solves [s] | mean solve [s] | worker start [s] "
        "| table + plots [s] | runner per case [s] | per case / solve |",
        "|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
        f"| {r.computed} | {workers} | {r.wall_s:.2f} | {r.solve_s:.2f} | {mean:.2f} | "
        f"{r.startup_s:.2f} | {r.table_s:.2f} | {r.overhead_per_case_s:.3f} | {pct:.2f} % |",
        "",
        f"* runner overhead per case {pct:.2f} % of the solve (target < "
        f"{OVERHEAD_TARGET_PCT:g} %: {status}); one-off: worker start {r.startup_s:.1f} s, "
        f"table and plots {r.table_s:.1f} s",
    ])

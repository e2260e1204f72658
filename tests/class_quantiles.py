"""A tolerance class's P95 of the pairs that turn, solved as `fegear solve --grade` solves it,
for the tests that hold a small class's quantile against a large one's (disjoint draws)."""

from __future__ import annotations

import math

#: the shifted baseline with backlash enough that few of a class-5 class's pairs jam, `coarse`
SHIFTED_CLASS_5 = {"shift": 0.03, "rotation": 0.002, "quality": "coarse", "no-estimate": True,
                   "grade": 5}


def turning_p95(values: dict, seed: int, count: int) -> tuple[dict, dict]:
    """The class of ``values`` (job inputs) with ``count`` pairs drawn with ``seed``: its
    samples' summary and each headline's P95 of the pairs that turn (value and error)."""
    from fegear.running import spare_core
    from fegear.toothpair import prepare_job, solve_job

    job = prepare_job({**values, "samples": count, "seed": seed})
    with spare_core() as executor:
        s = solve_job(job, executor=executor).summary["samples"]
    return s, {k: next(q for q in v["turning"] if q["q"] == 0.95)
               for k, v in s["stresses"].items()}


def apart(a: dict, b: dict) -> float:
    """How far two quantiles (value and error) lie apart, in their combined errors."""
    return abs(a["value"] - b["value"]) / math.hypot(a["error"], b["error"])

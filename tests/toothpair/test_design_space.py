"""The design space swept one input at a time, as issue 32 asks and a designer would: h1 from its
lowest value to past its loop limit in steps of 0.02 at f1 0.05, 0.15 and 0.3; f1 from 0 to 0.6
at h1 0.2, 0.3 and 0.45; z1 from 8 to 120 at z2 − z1 = 1 and 2. Every design either builds and
solves (``coarse``, one position, the torque balanced and no overlap where pressure acts) or is
refused in one line naming an input, with a range that excludes the refused value (slow: about
300 solves; the table it prints is in docs/geometry.md)."""

import re
from collections import Counter

import numpy as np
import pytest

from fegear.errors import FegearError, ParameterError
from fegear.toothpair.job import prepare_job
from fegear.toothpair.pair import solve_positions


def sweeps():
    for f1 in (0.05, 0.15, 0.3):
        for h1 in np.arange(0.05, 1.0, 0.02):
            yield f"h1 at f1 {f1}", {"h1": round(float(h1), 2), "f1": f1}
    for h1 in (0.2, 0.3, 0.45):
        for f1 in np.arange(0.0, 0.601, 0.02):
            yield f"f1 at h1 {h1}", {"h1": h1, "f1": round(float(f1), 2)}
    for dz in (1, 2):
        for z1 in range(8, 121):
            yield f"z1 at z2 - z1 = {dz}", {"z1": z1, "z2": z1 + dz}


def outcome(values: dict) -> str:
    """built-and-solved, refused (correctly), or wrong (a refusal whose range holds its value,
    or an error after the check)."""
    try:
        job = prepare_job({**values, "quality": "coarse", "no-estimate": True})
    except ParameterError as err:
        m = re.match(rf"(-?[\d.]+) <=? {re.escape(err.name)} <=? (-?[\d.]+)", err.admissible)
        if m and float(m.group(1)) <= float(err.value) <= float(m.group(2)):
            return f"wrong: {err}"
        return "refused"
    try:
        sol = solve_positions(job.case, job.betas)[0]
    except FegearError as err:
        return f"wrong: built, then {type(err).__name__}: {err}"
    ok = sol.checks.balance_error < 1e-9 and sol.checks.max_penetration < 1e-9
    return "solved" if ok else "wrong: built, not converged"


@pytest.mark.slow
def test_every_swept_design_solves_or_is_refused_with_a_true_range():
    table, wrong = {}, []
    for sweep, values in sweeps():
        result = outcome(values)
        counts = table.setdefault(sweep, Counter())
        counts[result.split(":")[0]] += 1
        counts["built"] += result == "solved" or result.startswith("wrong: built")
        if result.startswith("wrong"):
            wrong.append((values, result))
    print("| sweep | tried | built | solved | refused | wrong |\n|---|---:|---:|---:|---:|---:|")
    for sweep, c in table.items():
        tried = c["solved"] + c["refused"] + c["wrong"]
        print(f"| {sweep} | {tried} | {c['built']} | {c['solved']} | {c['refused']} | "
              f"{c['wrong']} |")
    assert not wrong, wrong

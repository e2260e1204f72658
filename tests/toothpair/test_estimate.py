"""The error estimate is honest (issue 34): on the baseline and two designs of another shape (a
taller tooth pressing on its round at 3.4 GPa, a smaller module with fatter teeth), every
headline stress at `fine` lies inside the estimate `standard` prints for it (slow: three
`standard` solves with their estimates and three `fine` ones, about 1.5 minutes)."""

import pytest

from fegear.toothpair.job import prepare_job, solve_job

DESIGNS = {"baseline": {}, "h1 0.4": {"h1": 0.4}, "m 1.5, f1 0.2": {"m": 1.5, "f1": 0.2}}


@pytest.mark.slow
@pytest.mark.parametrize("values", DESIGNS.values(), ids=DESIGNS.keys())
def test_the_fine_value_lies_inside_the_standard_estimate(values):
    standard = solve_job(prepare_job({**values, "quality": "standard"})).summary
    fine = solve_job(prepare_job({**values, "quality": "fine", "no-estimate": True})).summary
    estimate = standard["error_estimate_by_stress_pct"]
    assert set(estimate) >= {"root_stress_gear1_MPa", "contact_pressure_MPa",
                             "von_mises_max_MPa"}
    for key, pct in estimate.items():
        off = 100.0 * abs(fine[key] / standard[key] - 1.0)
        assert off <= pct, (key, standard[key], fine[key], pct)

"""Random Hertz disk contacts (hypothesis, derandomised so CI sees the same cases every run):
radii, a bore or not, load 1 mN … 10 kN, thickness, E, ν; each admissible draw converges with
the load balanced, the penetration within the solver's bound and a finite summary, or is refused
with a named error (at most 2 % of them; slow: 200 cases take about 2 minutes)."""

import pytest
from draws import Draws, finite
from hypothesis import HealthCheck, Phase, given, reject, settings
from hypothesis import strategies as st

from fegear.errors import FegearError, ParameterError
from fegear.verify import DiskCase, solve_disks

SETTINGS = settings(max_examples=200, deadline=None, derandomize=True,
                    phases=[Phase.explicit, Phase.reuse, Phase.generate, Phase.shrink],
                    suppress_health_check=[HealthCheck.too_slow])


@st.composite
def disks(draw):
    """A disk case whose inputs are admissible (the others are rejected, not counted)."""
    r1 = draw(st.floats(1.0, 100.0))
    bore = draw(st.booleans())
    r2 = -draw(st.floats(1.05 * r1, 1.05 * r1 + 100.0)) if bore else draw(st.floats(1.0, 100.0))
    try:
        return DiskCase(r1=r1, r2=r2, load=10 ** draw(st.floats(-3.0, 4.0)),
                        thickness=draw(st.floats(0.5, 50.0)), E=draw(st.floats(5e4, 4e5)),
                        nu=draw(st.floats(0.0, 0.45)), quality="coarse")
    except ParameterError:  # e.g. a load whose Hertz width exceeds half a radius
        reject()


@pytest.mark.slow
def test_random_disk_contacts_converge_or_raise_a_named_error():
    draws = Draws(max_refused_share=0.02)

    @SETTINGS
    @given(case=disks())
    def one(case):
        try:
            r = solve_disks(case)
        except FegearError as err:
            draws.refuse(case, err)
            return
        sol = r.solution
        assert sol.balance_error < 1e-3
        assert sol.max_penetration < 0.01 * r.half_width  # the solver's stated bound
        assert max(sol.residuals) < 1e-8
        assert finite(r.summary()) is None, finite(r.summary())
        draws.ok()

    one()
    draws.check()


def test_finite_check_finds_a_nan_deep_in_a_summary():
    assert finite({"a": [1.0, {"b": float("nan")}]}) == "summary.a[1].b"
    assert finite({"a": [1.0, None, "x"], "b": (2, -0.0)}) is None
    assert finite([float("-inf")]) == "summary[0]"


def test_a_regression_that_makes_every_draw_raise_fails():
    draws = Draws(max_refused_share=0.1)
    for k in range(5):
        draws.refuse(k, FegearError("contact ill-posed"))
    draws.ok()
    with pytest.raises(AssertionError, match="5 refused by name"):
        draws.check()

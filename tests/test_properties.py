"""Property-based checks (hypothesis, derandomised so CI sees the same cases every run): random
admissible-looking inputs either give finite results that pass the physical checks or raise a
named fegear error. No NaN or infinity may reach an output.

Covered here: the Hertz disk FE case (coarse) and random tooth pairs through the whole solve
(coarse; 200 cases take about an hour, so both are marked slow). The failures these found are
regression tests in tests/test_profile.py and tests/test_toothpair.py."""

import math

import pytest
from hypothesis import HealthCheck, Phase, given, reject, settings
from hypothesis import strategies as st

from fegear.errors import FegearError, ParameterError
from fegear.geometry.admissible import check_admissible
from fegear.geometry.parameters import PairParameters
from fegear.toothpair.case import SolveCase
from fegear.toothpair.report import pair_summary
from fegear.toothpair.solve import solve_pair
from fegear.verify.disks import DiskCase, solve_disks

SETTINGS = settings(max_examples=200, deadline=None, derandomize=True,
                    phases=[Phase.explicit, Phase.reuse, Phase.generate, Phase.shrink],
                    suppress_health_check=[HealthCheck.too_slow])


def _finite(value, path="summary"):
    """Every number in a JSON-like tree is finite (None allowed); returns the offending path."""
    if isinstance(value, dict):
        return next((p for k, v in value.items() if (p := _finite(v, f"{path}.{k}"))), None)
    if isinstance(value, (list, tuple)):
        return next((p for i, v in enumerate(value) if (p := _finite(v, f"{path}[{i}]"))), None)
    if isinstance(value, float) and not math.isfinite(value):
        return path
    return None


@st.composite
def disks(draw):
    r1 = draw(st.floats(1.0, 100.0))
    bore = draw(st.booleans())
    r2 = -draw(st.floats(1.05 * r1, 1.05 * r1 + 100.0)) if bore else draw(st.floats(1.0, 100.0))
    return DiskCase(r1=r1, r2=r2, load=10 ** draw(st.floats(-3.0, 4.0)),
                    thickness=draw(st.floats(0.5, 50.0)), E=draw(st.floats(5e4, 4e5)),
                    nu=draw(st.floats(0.0, 0.45)), quality="coarse")


@pytest.mark.slow
@SETTINGS
@given(data=st.data())
def test_random_disk_contacts_converge_or_raise_a_named_error(data):
    try:
        case = data.draw(disks())
        r = solve_disks(case)
    except FegearError:
        return
    sol = r.solution
    assert sol.balance_error < 1e-3
    assert sol.max_penetration < 0.01 * r.half_width  # the solver's stated bound
    assert max(sol.residuals) < 1e-8
    assert _finite(r.summary()) is None, _finite(r.summary())


def test_finite_check_finds_a_nan_deep_in_a_summary():
    assert _finite({"a": [1.0, {"b": float("nan")}]}) == "summary.a[1].b"
    assert _finite({"a": [1.0, None, "x"], "b": (2, -0.0)}) is None
    assert _finite([float("-inf")]) == "summary[0]"


@st.composite
def pairs(draw):
    """An admissible pair (inadmissible draws are rejected, not counted) and a torque that
    loads a module-m tooth like 1…300 N·m load the m = 2 baseline."""
    z1 = draw(st.integers(12, 80))
    m = draw(st.floats(0.5, 4.0))
    try:
        p = PairParameters(m=m, z1=z1, z2=z1 + draw(st.sampled_from([1, 1, 1, 2])),
                           h1=draw(st.floats(0.05, 0.6)), f1=draw(st.floats(0.0, 0.4)),
                           shift=draw(st.floats(0.0, 0.01 * m)),
                           rotation=draw(st.floats(0.0, 0.002 * m)))
        check_admissible(p)
    except ParameterError:
        reject()
    torque = 10 ** draw(st.floats(0.0, math.log10(300.0))) * (m / 2.0) ** 2 * z1 / 44
    return SolveCase(p, torque=torque, quality="coarse")


@pytest.mark.slow
@settings(SETTINGS, phases=[Phase.explicit, Phase.reuse, Phase.generate])  # a solve takes
@given(data=st.data())                        # 5-60 s: a failure is reported as drawn, unshrunk
def test_random_tooth_pairs_converge_or_raise_a_named_error(data):
    case = data.draw(pairs())
    try:
        sol = solve_pair(case)
    except FegearError:
        return
    widest = max(pt.half_width for pt in sol.contact.patches)
    assert sol.contact.balance_error < 1e-3
    assert sol.contact.max_penetration < 0.01 * widest  # the solver's stated bound
    summary = pair_summary(sol)
    assert _finite(summary) is None, _finite(summary)

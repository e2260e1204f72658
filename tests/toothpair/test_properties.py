"""Random admissible tooth pairs through the whole solve of the ring model (hypothesis,
derandomised so CI sees the same cases every run; coarse): m, z1, z2 − z1, h1, f1, shift,
rotation and a torque that loads the teeth like 1 … 300 N·m load the baseline. Each admissible
draw converges with the torque balanced, no overlap where pressure acts and a finite summary,
or is refused with a named error, at most ``MAX_REFUSED`` of them (slow). The failures this
found are regression tests in tests/geometry and tests/toothpair."""

import math

import pytest
from draws import Draws, finite
from hypothesis import HealthCheck, Phase, given, reject, settings
from hypothesis import strategies as st

from fegear.errors import FegearError, GeometryError, ParameterError
from fegear.geometry import Gear1Profile, ToothContact
from fegear.geometry.admissible import check_admissible
from fegear.geometry.parameters import PairParameters
from fegear.toothpair.case import SolveCase
from fegear.toothpair.pair import solve_pair
from fegear.toothpair.report import pair_summary
from fegear.toothpair.teeth import refuse_interference

#: admissible draws that may be refused by name; the 200-draw run (2026-11-23, 25 min 54 s)
#: refused 3 (1.5 %), each a MeshError: an inverted element in gear 2's template
MAX_REFUSED = 0.02

# a solve takes 5-60 s: a failure is reported as drawn, unshrunk
SETTINGS = settings(max_examples=200, deadline=None, derandomize=True,
                    phases=[Phase.explicit, Phase.reuse, Phase.generate],
                    suppress_health_check=[HealthCheck.too_slow])


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
        # designs the geometry stage refuses by name are not the solver's to converge: no
        # conjugate gear 1 (the gear-2 normal misses the pitch circle; 8 of the 200 draws),
        # or teeth that overlap before any load (the shift and rotation against the default
        # tip clearance; 30)
        refuse_interference([(0.0, ToothContact(p, Gear1Profile(p)).state(0.0))])
    except (ParameterError, GeometryError):
        reject()
    torque = 10 ** draw(st.floats(0.0, math.log10(300.0))) * (m / 2.0) ** 2 * z1 / 44
    return SolveCase(p, torque=torque, quality="coarse")


@pytest.mark.slow
def test_random_tooth_pairs_converge_or_raise_a_named_error():
    draws = Draws(max_refused_share=MAX_REFUSED)

    @SETTINGS
    @given(case=pairs())
    def one(case):
        try:
            sol = solve_pair(case)
        except FegearError as err:
            draws.refuse(case, err)
            return
        assert sol.checks.balance_error < 1e-9
        assert sol.checks.max_penetration < 1e-9  # mm: gaps and pressures complementary
        summary = pair_summary(sol)
        assert finite(summary) is None, finite(summary)
        draws.ok()

    one()
    draws.check()

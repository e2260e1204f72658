"""The solved contact linearised (:mod:`fegear.toothpair.ring.tangent`): the tangent mesh
stiffness against two solves."""

from dataclasses import replace

import pytest

from fegear.toothpair.pair import solve_positions


@pytest.mark.parametrize("torque", [50.0, 200.0, 400.0])
def test_the_tangent_stiffness_is_the_slope_of_two_solves(baseline_ring, torque):
    """dT/dθ with the contact set kept against the central difference of two solves at ±1 %
    of the torque (measured within 0.5 % at `coarse`, 0.25 % at `standard`: the two solves'
    grids are placed for their own loads); larger than the secant T/δ, the more the more
    teeth the load brings in (1.1× at 50 N·m, 1.6× at 400)."""
    case = replace(baseline_ring.case, torque=torque)
    sol, lo, hi = (solve_positions(replace(case, torque=torque * f), (case.beta,),
                                   model=baseline_ring, contact_only=True)[0]
                   for f in (1.0, 0.99, 1.01))
    difference = 0.02 * torque / (hi.rotation - lo.rotation)
    assert sol.tangent_stiffness == pytest.approx(difference, rel=0.01)
    assert sol.tangent_stiffness > 1.05 * sol.mesh_stiffness

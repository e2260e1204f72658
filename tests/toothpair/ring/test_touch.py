"""The rotation of first touch (:mod:`fegear.toothpair.ring.touch`): measured again on the
points near touching alone, it is where the closest grid point touches, from any start."""

import pytest

from fegear.toothpair.ring import contact
from fegear.toothpair.ring.touch import touch_rotation


@pytest.mark.parametrize("start_um", [0.0, 3.0, -40.0])
def test_the_first_touch_is_where_the_closest_grid_point_touches(baseline_200, start_um):
    # measured again on the points near touching alone, from a start off by start_um of arc:
    # every point's rigid gap is then open or closed to rounding, and one point touches
    d = baseline_200.detail
    p = d.case.params
    touch = touch_rotation(d.model, d.contact, baseline_200.first_touch + p.turn_of(start_um))
    g0, _ = contact.rigid_gap(d.model, d.contact, p.ratio * d.contact.beta + touch,
                              d.contact.feet.copy())
    assert g0.min() == pytest.approx(0.0, abs=1e-12)
    assert touch == pytest.approx(baseline_200.first_touch, abs=1e-13)

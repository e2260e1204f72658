"""Gear 2's exact curve placed at a rolling angle (fegear/toothpair/ring/master.py): a point
moved off the curve along its normal is found at that distance, its foot where it started,
and the curve turned by β turns every foot with it."""

import numpy as np
import pytest

from fegear.geometry import PairParameters, gear2_curve
from fegear.toothpair.ring.master import Gear2Master


@pytest.mark.parametrize("beta", [0.0, 0.3])
def test_a_point_off_the_curve_along_its_normal_is_found_at_that_distance(beta):
    curve = gear2_curve(PairParameters())
    xi = np.linspace(-0.06, 0.06, 7)
    on, tangent, normal, _ = curve.frame(xi)
    c, s = np.cos(beta), np.sin(beta)
    turn = np.array([[c, -s], [s, c]])
    d = np.array([-3e-3, -1e-4, 0.0, 2e-4, 1e-3, 5e-3, 8e-3])
    points = (on + d[:, None] * normal) @ turn.T
    found = Gear2Master(curve, beta).closest(points, feet=np.full(len(xi), np.nan))
    assert np.abs(np.abs(found.distance) - np.abs(d)).max() < 1e-10
    assert np.abs(found.foot - on @ turn.T).max() < 1e-9
    assert np.abs(np.linalg.norm(found.normal, axis=1) - 1.0).max() < 1e-12
    # the sign: one side of the curve positive, the other negative
    signs = np.sign(found.distance[d != 0]) * np.sign(d[d != 0])
    assert len(set(signs)) == 1

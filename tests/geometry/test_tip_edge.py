"""Gear 1's tip edges rounded for the stress model: tangent, material only removed."""

import math

import numpy as np
import pytest

from fegear.errors import ParameterError
from fegear.geometry.gear1 import Gear1Profile
from fegear.geometry.parameters import PairParameters
from fegear.geometry.tip_edge import RoundedProfile


@pytest.mark.parametrize("rho, pair, kink_deg", [
    (0.1, "baseline", 15), (0.25, "baseline", 15), (0.5, "baseline", 15),
    # f1 at its admissible limit: a 14° kink on a steep flank, where the tangent points
    # guessed from the polar radius collapsed onto the kink and every radius was refused
    (0.05, dict(f1=0.39), 10), (0.25, dict(f1=0.39), 10)])
def test_tip_round_is_tangent_and_only_removes_material(rho, pair, kink_deg, request):
    p = request.getfixturevalue(pair) if isinstance(pair, str) else PairParameters(**pair)
    sharp = Gear1Profile(p)
    shape = RoundedProfile(sharp, rho)
    assert len(shape.kinks) == 2 and all(math.degrees(g) > kink_deg for _, g in shape.kinks)
    for f in shape.fillets:
        c = np.asarray(f.centre)
        for phi in (f.phi_a, f.phi_b):
            # the arc meets the flank at the tangent point: same point, same normal
            q = shape.point(np.array([phi]))[0]
            ev = sharp.evaluate(np.array([phi]))
            assert np.linalg.norm(q - ev.q[0]) < 1e-9
            assert np.allclose((q - c) / rho, ev.normal[0], atol=1e-7)
        inside = np.linspace(f.phi_a, f.phi_b, 50)
        assert np.allclose(np.linalg.norm(shape.point(inside) - c, axis=1), rho, atol=1e-9)
        assert np.allclose(shape.curvature(inside[1:-1]), 1.0 / rho)
    phi = np.linspace(shape.phi_space, shape.phi_space + 3 * shape.pitch, 20001)
    removed = sharp.radius(phi) - shape.radius(phi)
    assert removed.min() > -1e-12            # material is only removed
    assert 0.0 < removed.max() < 0.2 * rho   # and only near the edge
    # a second tooth turn carries the same round
    f = shape.fillets[0]
    mid = 0.5 * (f.phi_a + f.phi_b)
    assert shape.radius(np.array([mid + shape.pitch]))[0] == pytest.approx(
        shape.radius(np.array([mid]))[0], abs=1e-12)
    assert shape.on_round(np.array([mid, mid + shape.pitch, f.phi_a + 1e-9])).all()
    assert not shape.on_round(np.array([f.phi_a - 1e-6, f.phi_b + 1e-6])).any()


def test_tip_round_too_large_is_refused_with_the_largest_that_fits():
    profile = Gear1Profile(PairParameters())
    with pytest.raises(ParameterError, match="tip-round") as err:
        RoundedProfile(profile, 5.0)
    largest = float(err.value.admissible.split("<= tip-round <=")[1].split()[0])
    assert len(RoundedProfile(profile, largest).fillets) == 2
    with pytest.raises(ParameterError):
        RoundedProfile(profile, largest + 2e-4)



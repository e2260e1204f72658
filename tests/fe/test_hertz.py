"""Hertz line contact: the formulas by hand, signed radii, plane strain, and the refusals."""

import math

import pytest

from fegear.errors import ParameterError
from fegear.fe.hertz import line_contact


def test_hertz_formulas_by_hand():
    # r1 = r2 = 10 mm → R* = 5 mm; E* = E/2 = 103000 MPa; q = 1000 N / 5 mm = 200 N/mm
    h = line_contact(10.0, 10.0, 1000.0, 5.0)
    b = math.sqrt(4 * 200 * 5 / (math.pi * 103000))
    assert h.R_star == pytest.approx(5.0, rel=1e-15)
    assert h.E_star == pytest.approx(103000.0, rel=1e-15)
    assert h.b == pytest.approx(b, rel=1e-15)
    assert h.p0 == pytest.approx(2 * 200 / (math.pi * b), rel=1e-15)
    assert math.pi / 2 * h.p0 * h.b == pytest.approx(200.0, rel=1e-14)  # ∫p = q
    assert h.b_over_R == pytest.approx(b / 5.0)
    bore = line_contact(10.0, -12.0, 1000.0, 5.0)  # concave: 1/R* = 1/10 − 1/12
    assert bore.R_star == pytest.approx(60.0, rel=1e-14)
    strain = line_contact(10.0, 10.0, 1000.0, 5.0, plane="strain")
    assert strain.E_star == pytest.approx(103000.0 / (1 - 0.29**2), rel=1e-14)


@pytest.mark.parametrize("r2", [-5.0, -10.0, 0.0])
def test_hertz_refuses_bodies_that_cannot_touch_at_a_point(r2):
    with pytest.raises(ParameterError, match="r2"):
        line_contact(10.0, r2, 1000.0, 5.0)

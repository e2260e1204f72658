"""The life factors on ISO 6336-2/-3's tabulated points, and Miner's sum against one written
from the tables' points by interpolation alone; the safety factor at a required life is the
largest stress factor that leaves the sum at most 1."""

import math

import numpy as np
import pytest

from fegear.rating import BENDING, CONTACT, damage, safety_at_life

#: the tables' points (cycles, factor): ISO 6336-3:2019 Table 4 and ISO 6336-2:2019 Table 2
POINTS = {("bending", "through-hardened"): ((1e4, 2.5), (3e6, 1.0)),
          ("bending", "case-hardened"): ((1e3, 2.5), (3e6, 1.0)),
          ("bending", "nitrided"): ((1e3, 1.6), (3e6, 1.0)),
          ("contact", "through-hardened"): ((1e5, 1.6), (5e7, 1.0)),
          ("contact", "nitrided"): ((1e5, 1.3), (2e6, 1.0))}


def _curve(kind, treatment):
    return (BENDING if kind == "bending" else CONTACT)[treatment]


@pytest.mark.parametrize("kind, treatment", POINTS)
def test_the_factors_pass_through_the_tables_points(kind, treatment):
    curve = _curve(kind, treatment)
    (n0, y0), (n1, y1) = POINTS[kind, treatment]
    assert curve.factor(n0) == pytest.approx(y0, rel=1e-12)
    assert curve.factor(n0 / 10) == y0           # flat before the first point …
    assert curve.factor(n1) == pytest.approx(y1, rel=1e-12)
    assert curve.factor(n1 * 1e3) == 1.0         # … and beyond the knee
    mid = math.sqrt(n0 * n1)                     # straight on log-log axes between
    assert math.log(curve.factor(mid)) == pytest.approx(0.5 * math.log(y0), rel=1e-12)


def test_the_exponents_are_the_ones_iso_6336_6_quotes():
    assert BENDING["through-hardened"].exponent == pytest.approx(6.2, abs=0.05)
    assert CONTACT["through-hardened"].exponent == pytest.approx(13.2, abs=0.05)


def _cycles_from_points(ratio, points):
    """The cycles a stress ``ratio`` times the limit lasts, by interpolating the table's two
    points in log-log (the test's own reading, not the product's formula)."""
    (n0, y0), (n1, _) = points
    if ratio <= 1.0:
        return math.inf
    if ratio > y0:
        return 0.0
    t = math.log(y0 / ratio) / math.log(y0)          # 0 at the first point, 1 at the knee
    return math.exp(math.log(n0) + t * (math.log(n1) - math.log(n0)))


@pytest.mark.parametrize("kind, treatment", POINTS)
def test_miners_sum_agrees_with_one_from_the_tables_points(kind, treatment):
    rng = np.random.default_rng(7)
    curve = _curve(kind, treatment)
    limit = 600.0
    y0 = POINTS[kind, treatment][0][1]
    for _ in range(20):
        stresses = limit * rng.uniform(0.8, y0, size=4)
        cycles = 10 ** rng.uniform(2, 8, size=4)
        expected = sum(n / _cycles_from_points(s / limit, POINTS[kind, treatment])
                       for s, n in zip(stresses, cycles))
        assert damage(stresses, cycles, limit, curve) == pytest.approx(expected, rel=1e-9)


def test_a_level_beyond_the_static_strength_breaks_at_once_and_one_below_the_limit_is_free():
    curve = BENDING["through-hardened"]
    assert damage([2.6 * 500], [1], 500, curve) == math.inf
    assert damage([0.99 * 500], [1e12], 500, curve) == 0.0


def test_the_safety_factor_at_life_brings_the_sum_to_one():
    curve = CONTACT["through-hardened"]
    stresses, cycles, limit = [700.0, 900.0, 1000.0], [1e7, 1e5, 1e3], 745.0
    x = safety_at_life(stresses, cycles, limit, curve)
    # the sum is 1 there where it is continuous (no level at its limit with more cycles
    # than the knee's)
    assert damage([x * s for s in stresses], cycles, limit, curve) == pytest.approx(1.0,
                                                                                   rel=1e-9)
    assert damage([0.99 * x * s for s in stresses], cycles, limit, curve) < 1.0


def test_the_safety_factor_where_a_level_reaches_the_limit_with_more_than_the_knee_s_cycles():
    # the line is flat beyond its knee: a level of 10^8 cycles costs nothing below the limit
    # and 10^8 / 5·10^7 = 2 just above it, so the sum jumps past 1 there
    curve = CONTACT["through-hardened"]
    x = safety_at_life([500.0], [1e8], 745.0, curve)
    assert x == pytest.approx(745.0 / 500.0, rel=1e-9)
    assert damage([0.999 * x * 500.0], [1e8], 745.0, curve) == 0.0


def test_no_load_has_no_limit():
    assert safety_at_life([0.0], [1e6], 500.0, BENDING["case-hardened"]) == math.inf

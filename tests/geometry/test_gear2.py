"""Gear 2: the compound cycloid against paper eq. (11), exact derivatives, polar form."""

import numpy as np
import pytest
from swept_reference import eq11

from fegear.geometry.gear2 import Cycloid, gear2_curve
from fegear.geometry.parameters import PairParameters

XI = np.linspace(-np.pi, np.pi, 4001)


@pytest.mark.parametrize("d2", [0.0, 0.002, -0.01])
def test_matches_paper_eq11(d2):
    c = Cycloid(45.0, 0.6, 0.09, 45, d2)
    assert np.abs(c.point(XI) - eq11(XI, 45.0, 0.6, 0.09, 45, d2)).max() < 1e-12


def test_derivatives_match_eq11_term_by_term():
    c = Cycloid(45.0, 0.6, 0.09, 45, 0.002)
    p, d1, d2 = c.derivatives(XI, 2)
    assert np.abs(d1 - eq11(XI, 45.0, 0.6, 0.09, 45, 0.002, 1)).max() < 1e-10
    assert np.abs(d2 - eq11(XI, 45.0, 0.6, 0.09, 45, 0.002, 2)).max() < 1e-8


def test_third_derivative_by_central_difference():
    c = Cycloid(45.0, 0.6, 0.09, 45, 0.002)
    h = 1e-5
    d3 = c.derivatives(XI, 3)[3]
    fd = (c.derivatives(XI + h, 2)[2] - c.derivatives(XI - h, 2)[2]) / (2 * h)
    assert np.abs(d3 - fd).max() / np.abs(d3).max() < 1e-6  # FD truncation ~1e-7


def test_the_curvatures_rate_is_its_derivative_along_the_arc():
    c = Cycloid(45.0, 0.6, 0.09, 45, 0.002)
    h = 1e-6
    speed = np.hypot(*c.derivatives(XI, 1)[1].T)
    fd = (c.frame(XI + h)[3] - c.frame(XI - h)[3]) / (2 * h) / speed
    rate = c.curvature_rate(XI)
    assert np.abs(rate - fd).max() / np.abs(rate).max() < 1e-6


def test_baseline_radii_and_parameter_convention():
    p = PairParameters()
    assert (p.r0, p.e1, p.e2, p.e) == pytest.approx((45.0, 0.6, 0.09, 1.0))
    r = np.hypot(*gear2_curve(p).point(XI).T)
    assert r.min() == pytest.approx(43.8, abs=1e-12)
    assert r.max() == pytest.approx(46.2, abs=1e-9)


def test_polar_inversion_round_trip():
    c = Cycloid(45.0, 0.6, 0.09, 45, 0.002)
    theta = c.polar_angle(XI)
    assert np.abs(c.xi_at_angle(theta) - XI).max() < 1e-13
    pts = c.point(XI)
    assert np.abs(c.radius_at_angle(theta) - np.hypot(*pts.T)).max() < 1e-12


class Counted(Cycloid):
    """A cycloid that counts its evaluations of u, w."""

    calls: list = []

    def _uw(self, xi, order):
        self.calls.append(len(xi))
        return super()._uw(xi, order)


@pytest.mark.parametrize("tabled, steps", [(False, 8), (True, 4)])
def test_polar_inversion_converges_quadratically(tabled, steps):
    # Newton from ξ = θ reaches 1e-13 in about five steps, from the pitch table in three; a
    # root hit exactly once ended its own bracket and was bisected away again (47 evaluations
    # of u, w for 200 points)
    c = Counted(45.0, 0.6, 0.09, 45, 0.002)
    theta = np.random.default_rng(0).uniform(-np.pi, np.pi, 200)
    c.xi_at_angle(theta[:1], tabled=tabled)      # the table made
    Counted.calls.clear()
    xi = c.xi_at_angle(theta, tabled=tabled)
    assert np.abs(c.polar_angle(xi) - theta).max() < 1e-14
    assert len(Counted.calls) <= steps


def test_polar_table_start_gives_the_same_angles():
    # the table only starts Newton: the same ξ within the few ulps a point is done within,
    # over several turns either way and at a rotation modification
    c = Cycloid(45.0, 0.6, 0.09, 45, -0.01)
    theta = np.random.default_rng(1).uniform(-20.0, 20.0, 2000)
    xi, plain = c.xi_at_angle(theta), c.xi_at_angle(theta, tabled=False)
    assert np.abs(xi - plain).max() <= 8 * np.spacing(np.abs(plain)).max()
    assert np.abs(c.closest(c.point(xi) * 1.001)[0]
                  - c.closest(c.point(xi) * 1.001, tabled=False)[0]).max() < 1e-12


def test_foot_search_from_feet_found_before_gives_the_same_feet_in_fewer_steps():
    # the rigid gap at nearby rotations starts each point's search from its last foot: the
    # same feet within the few ulps a point is done within, NaN starts from the polar angle
    c = Counted(45.0, 0.6, 0.09, 45, 0.002)
    rng = np.random.default_rng(4)
    y = c.point(rng.uniform(-np.pi, np.pi, 300)) * rng.uniform(0.999, 1.001, (300, 1))
    before = c.feet(y)
    turned = y @ np.array([[np.cos(1e-6), np.sin(1e-6)], [-np.sin(1e-6), np.cos(1e-6)]])
    start = before.copy()
    start[:10] = np.nan
    Counted.calls.clear()
    plain = c.feet(turned)
    polar = sum(Counted.calls)                 # points evaluated, over the steps
    Counted.calls.clear()
    warm = c.feet(turned, start=start)
    assert sum(Counted.calls) < 0.6 * polar
    assert np.abs(warm - plain).max() <= 8 * np.spacing(np.abs(plain)).max()
    assert np.allclose(c.at_feet(turned, warm)[2], c.closest(turned)[2], rtol=0, atol=1e-13)


def test_signed_distance_along_normal():
    c = Cycloid(45.0, 0.6, 0.09, 45)
    p, _, n, _ = c.frame(XI[::7])
    for d in (-0.003, 0.0, 0.01):
        assert np.abs(c.signed_distance(p + d * n) - d).max() < 1e-12


def test_curvature_radius_at_tip_and_root():
    # at the tooth tip (ξ = 0) and tooth-space middle the curvature follows from u, w exactly
    r0, e1, e2, z = 45.0, 0.6, 0.09, 45
    c = Cycloid(r0, e1, e2, z)
    # κ = (P' × P'') / |P'|³ with P' = (u + w') t̂, P'' = (u'' - 2w' - u) ê_r at ξ = 0
    u, w1, u2 = r0 - 2 * e1, 4 * z * e2, 2 * e1 * z**2
    kappa = -(u + w1) * (u2 - 2 * w1 - u) / (u + w1) ** 3
    assert c.curvature_radius(np.array([0.0]))[0] == pytest.approx(-1 / kappa, rel=1e-12)


def test_polyline_chord_error_bound():
    c = Cycloid(45.0, 0.6, 0.09, 45)
    tol = 1e-4
    pts = c.polyline(tol, 0.0, 2 * np.pi / 45)
    xi = np.linspace(0, 2 * np.pi / 45, 20001)
    dense = c.point(xi)
    # distance of every dense curve point to the polyline (nearest segment)
    a, b = pts[:-1], pts[1:]
    ab = b - a
    t = np.clip(np.einsum("ijk,jk->ij", dense[:, None, :] - a[None], ab)
                / np.einsum("jk,jk->j", ab, ab), 0, 1)
    proj = a[None] + t[..., None] * ab[None]
    dist = np.min(np.linalg.norm(dense[:, None, :] - proj, axis=-1), axis=1)
    assert dist.max() <= tol

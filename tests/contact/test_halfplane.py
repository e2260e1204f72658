"""The half-plane (Flamant, plane stress) hat integrals against numerical quadrature of the
point-load solution, and the displacement kernel against the stresses it must derive from; the
line contact on an arbitrary gap against Hertz where the gap is a parabola."""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from fegear.contact.halfplane import (
    approach_matrix,
    gap_contact,
    hat_columns,
    strain_matrix,
    surface_matrix,
)
from fegear.fe import line_contact

E, NU = 206000.0, 0.29


def point_approach(t, d):
    """Δ of a unit line load (N/mm): surface minus depth-d normal displacement, mm."""
    return (math.log1p(d * d / (t * t)) - (1 + NU) * d * d / (t * t + d * d)) / (math.pi * E)


def point_strain(t, d):
    r2 = t * t + d * d
    return -2.0 / (math.pi * E) * d * (t * t - NU * d * d) / r2 ** 2


def hat(s, j, x):
    return np.interp(x, s, np.eye(len(s))[j], left=0.0, right=0.0)


def _hat_quadrature(s, t, d, point):
    """Reference matrix: the point solution ``point(t − x, d)`` integrated against hat j over
    its support, split at the hat's peak and at the field point."""
    ref = np.empty((len(t), len(s)))
    for i in range(len(t)):
        for j in range(len(s)):
            lo, hi = s[max(j - 1, 0)], s[min(j + 1, len(s) - 1)]
            breaks = [x for x in (s[j], t[i]) if lo < x < hi]
            ref[i, j] = quad(lambda x, i=i, j=j: hat(s, j, x) * point(t[i] - x, d[i]), lo, hi,
                             points=breaks or None, limit=200, epsabs=0, epsrel=1e-11)[0]
    return ref


@pytest.mark.parametrize("kernel,point", [(approach_matrix, point_approach),
                                          (strain_matrix, point_strain)])
def test_hat_integrals_equal_quadrature_of_the_point_load(kernel, point):
    s = np.array([-0.03, -0.01, 0.0, 0.004, 0.02, 0.05])
    t = np.array([-0.02, 0.0, 0.002, 0.004, 0.031, 0.3])
    d = np.array([0.01, 0.005, 0.02, 0.001, 0.04, 0.02])
    K = kernel(t, d, s, E, NU)
    ref = _hat_quadrature(s, t, d, point)
    for (i, j), value in np.ndenumerate(ref):
        assert K[i, j] == pytest.approx(value, rel=1e-7, abs=1e-12 * abs(K).max()), (i, j)


def test_the_surface_kernel_is_the_log_of_the_point_load_and_the_approach_kernel_far_down():
    s = np.array([-0.03, -0.01, 0.0, 0.004, 0.02, 0.05])
    K = surface_matrix(s, E)
    ref = _hat_quadrature(s, s, np.zeros(len(s)),
                          lambda t, d: -2.0 * math.log(abs(t)) / (math.pi * E))
    for (i, j), value in np.ndenumerate(ref):
        assert K[i, j] == pytest.approx(value, rel=1e-7, abs=1e-12 * abs(K).max()), (i, j)
    # far down, the depth-referenced kernel (ν = −1 drops its second term) is the surface
    # kernel plus the rigid approach 2 ln(d)/(π E) per unit of the hat's area, up to
    # ln(1 + u²/d²) < 1e-6
    d = 100.0
    area = np.zeros(len(s))
    area[:-1] += 0.5 * np.diff(s)
    area[1:] += 0.5 * np.diff(s)
    deep = approach_matrix(s, np.full(len(s), d), s, E, -1.0)
    assert deep == pytest.approx(K + 2.0 * math.log(d) / (math.pi * E) * area, rel=1e-6)


@pytest.mark.parametrize("per_b,tolerance", [(4, 0.007), (8, 0.002), (16, 5e-4)])
def test_the_contact_on_a_parabolic_gap_is_hertz(per_b, tolerance):
    """Two 10 mm disks, 1000 N over 5 mm (Hertz p0 1145.18 MPa, b 0.111 mm): the gap
    s²/(2R*) gives Hertz's peak and half-width on grids of 4, 8, 16 points per half-width,
    wherever the grid's points fall against the contact's middle."""
    hz = line_contact(10.0, 10.0, 1000.0, 5.0, E, NU)
    for offset in (0.0, 0.2, 0.5):
        s = (np.arange(-5 * per_b, 5 * per_b + 1) + offset) * hz.b / per_b
        p = gap_contact(s, s * s / (2.0 * hz.R_star), 1000.0 / 5.0, E / 2.0)
        assert p.max() == pytest.approx(hz.p0, rel=tolerance)
        on = s[p > 0]
        assert 0.5 * (on.max() - on.min()) == pytest.approx(hz.b, abs=hz.b / per_b)
        w = np.gradient(s)
        assert (w * p).sum() == pytest.approx(200.0, rel=1e-12)


def test_the_gap_beyond_its_curvature_at_one_point_moves_and_reshapes_the_pressure():
    """Hertz knows the gap's curvature at one point. A cubic term (the curvature changing
    across the contact, as on gear 2's flank) moves the pressure towards the side where the gap
    opens more slowly and leaves its peak (within 0.1 %); a quartic term (the gap closing
    faster than its parabola, as between nearly conformal flanks) narrows the contact and
    raises its peak. Mirrored gaps give mirrored pressures."""
    hz = line_contact(10.0, 10.0, 1000.0, 5.0, E, NU)
    s = np.linspace(-4 * hz.b, 4 * hz.b, 161)
    parabola = s * s / (2.0 * hz.R_star)
    cubic = parabola * (1.0 + s / (8.0 * hz.b))          # at least half the parabola
    p = gap_contact(s, cubic, 200.0, E / 2.0)
    assert (s * p).sum() / p.sum() < -0.04 * hz.b
    assert p.max() == pytest.approx(hz.p0, rel=1e-3)
    mirrored = gap_contact(-s[::-1], cubic[::-1], 200.0, E / 2.0)
    assert mirrored == pytest.approx(p[::-1], rel=1e-9, abs=1e-9 * p.max())
    quartic = gap_contact(s, parabola * (1.0 + (s / hz.b) ** 2), 200.0, E / 2.0)
    on = s[quartic > 0]
    assert quartic.max() > 1.1 * hz.p0 and 0.5 * (on.max() - on.min()) < 0.8 * hz.b


@pytest.mark.parametrize("lo, hi", [(0, 4), (3, 9), (7, 12), (0, 12)])
def test_a_run_of_hats_alone_has_their_columns_over_the_whole_grid(lo, hi):
    s = np.sort(np.random.default_rng(1).uniform(0.0, 0.3, 12))
    t, d = s + 0.004, np.full(12, 0.05)
    whole = approach_matrix(t, d, s, 210e3, 0.3)
    np.testing.assert_allclose(hat_columns(t, d, s, lo, hi, 210e3, 0.3), whole[:, lo:hi],
                               rtol=1e-12, atol=1e-15 * np.abs(whole).max())

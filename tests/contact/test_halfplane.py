"""The half-plane (Flamant, plane stress) hat integrals against numerical quadrature of the
point-load solution, and the displacement kernel against the stresses it must derive from."""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from fegear.contact.halfplane import approach_matrix, strain_matrix

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


def test_approach_and_strain_come_from_one_displacement_field():
    # −∂Δ/∂d is the normal strain at depth d, ε_zz = (σ_zz − ν σ_tt)/E, of the same loads;
    # the tangential strain kernel is the σ_tt − ν σ_zz of the same point solution
    s = np.linspace(-0.02, 0.02, 9)
    t, d, h = np.array([0.003, -0.011, 0.05]), np.array([0.01, 0.02, 0.015]), 1e-7
    dz = -(approach_matrix(t, d + h, s, E, NU) - approach_matrix(t, d - h, s, E, NU)) / (2 * h)

    def eps_zz(tt, dd):
        r2 = tt * tt + dd * dd
        return -2.0 / (math.pi * E) * dd * (dd * dd - NU * tt * tt) / r2 ** 2

    for (i, j), value in np.ndenumerate(_hat_quadrature(s, t, d, eps_zz)):
        assert dz[i, j] == pytest.approx(value, rel=1e-5, abs=1e-16), (i, j)


def test_a_uniform_pressure_far_away_has_a_vanishing_approach():
    s = np.linspace(-1.0, 1.0, 41)
    near = approach_matrix(np.array([0.0]), np.array([0.1]), s, E, NU).sum()
    far = approach_matrix(np.array([50.0]), np.array([0.1]), s, E, NU).sum()
    assert near > 0 and abs(far) < 1e-4 * near  # decays like (d/t)², here 4e-6

"""The stiffness, mass and stress-projection matrices of fe/forms.py: scikit-fem's own
assembly of the same forms on a mesh with curved boundary elements, to rounding; rigid motions
strain-free; the mass of the whole body its area."""

import math

import numpy as np
import pytest

from fegear.fe import ElasticMaterial, forms

MAT = ElasticMaterial(E=206e3, nu=0.3, thickness=3.0)  # plane stress


def _close(a, b, rel):
    return abs(a - b).max() <= rel * abs(b).max()


def test_the_forms_are_scikit_fems_on_curved_elements(annulus):
    from skfem import Basis, BilinearForm, ElementTriP2, ElementVector, asm
    from skfem.models.elasticity import linear_elasticity

    lam, mu = MAT.lame
    vector = Basis(annulus, ElementVector(ElementTriP2()))
    scalar = Basis(annulus, ElementTriP2(), quadrature=vector.quadrature)
    K = MAT.thickness * asm(linear_elasticity(lam, mu), vector)
    assert _close(forms.stiffness(annulus, lam, mu, MAT.thickness), K, 1e-11)
    mass, parts = forms.projection(annulus, lam, mu)
    assert _close(mass, asm(BilinearForm(lambda a, b, w: a * b), scalar), 1e-12)
    sigma = (lambda g: lam * (g[0, 0] + g[1, 1]) + 2 * mu * g[0, 0],
             lambda g: lam * (g[0, 0] + g[1, 1]) + 2 * mu * g[1, 1],
             lambda g: mu * (g[0, 1] + g[1, 0]))
    for C, component in zip(parts, sigma, strict=True):
        form = BilinearForm(lambda v, q, w, c=component: q * c(v.grad))
        assert _close(C, asm(form, vector, scalar), 1e-12)


def test_rigid_motions_strain_nothing_and_the_mass_is_the_area(annulus):
    lam, mu = MAT.lame
    x = annulus.doflocs.T
    K = forms.stiffness(annulus, lam, mu, MAT.thickness)
    mass, parts = forms.projection(annulus, lam, mu)
    scale = abs(K).max() * 10.0
    for motion in (np.tile([1.0, 0.0], len(x)), np.tile([0.0, 1.0], len(x)),
                   np.column_stack([-x[:, 1], x[:, 0]]).ravel()):
        assert np.abs(K @ motion).max() < 1e-10 * scale
        for C in parts:
            assert np.abs(C @ motion).max() < 1e-10 * abs(C).max() * 10.0
    area = math.pi * (10.0 ** 2 - 6.0 ** 2)
    assert mass.sum() == pytest.approx(area, rel=1e-5)   # the P2 edges off the circles: 1e-6

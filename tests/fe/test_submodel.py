"""Points in a curved quadratic mesh (fe/probe.py) and submodels (fe/submodel.py): exact
interpolation of fields the elements represent, and a submodel at the bore of a thick ring
held at Lamé's displacement against Lamé's hoop stress, converging at P2's rate."""


import numpy as np
import pytest

from fegear.errors import FegearError
from fegear.fe import ElasticMaterial, Probe, StarCurve, SubmodelProblem, solve_submodels

MAT = ElasticMaterial(thickness=3.0)  # plane stress


def test_probe_evaluates_fields_as_the_elements_do_also_under_curved_edges(annulus):
    """At every quadrature point of the mesh (scikit-fem's isoparametric map places them, curved
    boundary elements included) the probe's value and strain of a P2 field equal scikit-fem's
    own interpolation."""
    from skfem import Basis, ElementTriP2, ElementVector

    basis = Basis(annulus, ElementVector(ElementTriP2()))
    rng = np.random.default_rng(4)
    u = rng.normal(size=basis.N)
    field = basis.interpolate(u)
    pts = np.column_stack([basis.global_coordinates()[d].ravel() for d in (0, 1)])
    value = np.column_stack([field[d].ravel() for d in (0, 1)])
    probe = Probe(annulus)
    assert np.abs(probe.displacement(pts, u) - value).max() < 1e-10 * np.abs(value).max()
    d = rng.normal(size=pts.shape)
    d /= np.linalg.norm(d, axis=1)[:, None]
    grad = np.stack([[field.grad[i, j].ravel() for j in (0, 1)] for i in (0, 1)])  # (2, 2, n)
    strain = np.einsum("in,ijn,jn->n", d.T, grad, d.T)
    assert np.abs(probe.rows(pts, d, strain=True) @ u - strain).max() \
        < 1e-9 * np.abs(strain).max()
    # rows at points located once are the rows of the points, for any subset of them
    cells, some = probe.locate(pts), np.arange(0, len(pts), 3)
    assert (probe.rows_at(cells.take(some), d[some], strain=True)
            != probe.rows(pts[some], d[some], strain=True)).nnz == 0
    with pytest.raises(FegearError, match="outside the mesh"):
        probe.locate(np.array([[0.0, 0.0]]))


def lame(a, b, p):
    """Thick ring a < r < b, internal pressure p, plane stress: radial displacement and the
    hoop stress at the bore."""
    E, nu = MAT.E, MAT.nu
    A, B = p * a * a / (b * b - a * a), p * a * a * b * b / (b * b - a * a)

    def u(x):
        r = np.linalg.norm(x, axis=1)
        ur = ((1 - nu) * A * r + (1 + nu) * B / r) / E
        return x / r[:, None] * ur[:, None]

    return u, A + B / (a * a)


def test_submodel_at_a_bore_held_at_lame_converges_to_the_hoop_stress():
    """Gear 2's kind of boundary (material beyond the curve): the patch of radius 1.5 mm about a
    bore point, pressure p on the bore, the cut held at Lamé's displacement. The bore's hoop
    stress converges as the elements shrink (measured 1.2e-3, 9.8e-4, 3.0e-4, 1.2e-4)."""
    a, b, p = 6.0, 10.0, 100.0
    u, hoop = lame(a, b, p)
    bore = StarCurve(lambda t: a * np.column_stack([np.cos(t), np.sin(t)]), inside=False)
    errors = []
    for size in (0.4, 0.1, 0.05):
        problem = SubmodelProblem(bore, 0.4, 1.5, size, 0.5, lambda x: np.full(len(x), p), u)
        (sm,) = solve_submodels([problem], MAT)
        peak, where = sm.peak(sm.stress.s1)
        assert np.linalg.norm(where) == pytest.approx(a, abs=1e-9)   # on the bore
        errors.append(abs(peak / hoop - 1.0))
        x = sm.mesh.mesh.doflocs.T[sm.core]
        assert np.abs(sm.u.reshape(-1, 2)[sm.core] - u(x)).max() < 1e-4 * np.abs(u(x)).max()
    assert errors[0] > errors[1] > errors[2] and errors[2] < 2e-4, errors


def test_submodel_refuses_a_circle_that_misses_the_boundary():
    line = StarCurve(lambda t: 6.0 * np.column_stack([np.cos(t), np.sin(t)]), inside=True)
    big = SubmodelProblem(line, 0.0, 20.0, 0.5, 1.0, lambda x: np.zeros(len(x)),
                          lambda x: np.zeros_like(x))
    with pytest.raises(FegearError, match="does not cut the boundary"):
        solve_submodels([big], MAT)

"""P2 plane elasticity against analytic references: constants, patch test, Lamé convergence,
rigid rotation of an annulus through its bore, stress recovery."""

import math

import numpy as np
import pytest
from skfem import ElementTriP2, ElementVector, FacetBasis, LinearForm, asm, condense, solve
from skfem.helpers import dot

from fegear.fe.assembly import RigidLink, assemble_body, facet_nodes
from fegear.fe.material import ElasticMaterial
from fegear.fe.mesh import BodyGeometry, Segment, mesh_bodies
from fegear.fe.stress import quadrature_stress, recover, recover_many
from fegear.verify.penalty.model import Circle

E, NU, T = 206000.0, 0.29, 5.0


def arc(c, r, a0, a1, n=40):
    a = np.linspace(a0, a1, n)
    return np.asarray(c) + r * np.column_stack([np.cos(a), np.sin(a)])


def test_plane_stress_constants_are_lame_parameters():
    # scikit-fem 12.0.2 returns Lamé (λ*, μ) from plane_stress: λ* = Eν/(1−ν²), μ = E/(2(1+ν))
    lam, mu = ElasticMaterial(E, NU, T, "stress").lame
    assert lam == pytest.approx(E * NU / (1 - NU**2), rel=1e-14)
    assert mu == pytest.approx(E / (2 * (1 + NU)), rel=1e-14)
    lam, mu = ElasticMaterial(E, NU, T, "strain").lame
    assert lam == pytest.approx(E * NU / ((1 + NU) * (1 - 2 * NU)), rel=1e-14)
    assert ElasticMaterial(E, NU, T, "strain").plane_modulus == pytest.approx(E / (1 - NU**2))


def irregular_plate():
    """A curved-sided plate with an off-centre hole: an unstructured, graded P2 mesh."""
    c = Circle((0.3, 0.2), 0.5, "outside")
    outer = (Segment("bottom", np.array([[-2.0, -1.5], [2.5, -1.0]])),
             Segment("right", np.array([[2.5, -1.0], [2.0, 1.5]])),
             Segment("top", arc((0.0, -3.0), math.hypot(2.0, 4.5),
                                math.atan2(4.5, 2.0), math.atan2(4.5, -2.0))),
             Segment("left", np.array([[-2.0, 1.5], [-2.0, -1.5]])))
    hole = (Segment("hole_a", arc(c.center, c.radius, 0, math.pi), c.project),
            Segment("hole_b", arc(c.center, c.radius, math.pi, 2 * math.pi), c.project))
    (bm,) = mesh_bodies([BodyGeometry("plate", outer, size=0.6, holes=(hole,))])
    return bm


@pytest.mark.parametrize("plane", ["stress", "strain"])
def test_patch_test_linear_field_is_reproduced(plane):
    body = assemble_body(irregular_plate(), ElasticMaterial(E, NU, T, plane), fixed=("left",))
    x, y = body.mesh.doflocs
    A = np.array([[1e-3, -4e-4], [7e-4, 2e-3]])
    exact = np.column_stack([1e-2 + A[0, 0] * x + A[0, 1] * y,
                             -3e-3 + A[1, 0] * x + A[1, 1] * y]).ravel()
    boundary = np.concatenate([body.mesh.boundaries[n] for n in body.mesh.boundaries])
    D = np.unique(body.node_dofs(np.unique(facet_nodes(body.mesh, boundary))).ravel())
    u = solve(*condense(body.K, np.zeros(body.ndofs), x=exact, D=D))
    assert np.abs(u - exact).max() < 1e-10 * np.abs(exact).max()
    # constant stress, at the quadrature points and after recovery
    eps = 0.5 * (A + A.T)
    lam, mu = body.material.lame
    sig = lam * np.trace(eps) * np.eye(2) + 2 * mu * eps
    sq = quadrature_stress(body, u)
    for comp, ref in zip(sq, (sig[0, 0], sig[1, 1], sig[0, 1])):
        assert np.abs(comp - ref).max() < 1e-10 * np.abs(sig).max()
    rec = recover(body, u)
    assert np.abs(rec.sxx - sig[0, 0]).max() < 1e-9 * np.abs(sig).max()
    assert np.abs(rec.sxy - sig[0, 1]).max() < 1e-9 * np.abs(sig).max()
    szz = 0.0 if plane == "stress" else NU * (sig[0, 0] + sig[1, 1])
    assert np.abs(rec.szz - szz).max() < 1e-9 * np.abs(sig).max()
    # several fields in one solve: each as recovered alone, and linear in the field
    both = recover_many(body, np.column_stack([u, -2.0 * u]))
    for got, scale in zip(both, (1.0, -2.0)):
        for name in ("sxx", "syy", "sxy", "szz"):
            assert np.allclose(getattr(got, name), scale * getattr(rec, name), rtol=0,
                               atol=1e-12 * np.abs(sig).max())


def lame_error(size, a=10.0, b=20.0, p=100.0):
    """L2 stress error of a quarter thick-walled cylinder under internal pressure p."""
    inner = Circle((0.0, 0.0), a, "outside")
    outer = Circle((0.0, 0.0), b, "inside")
    geo = BodyGeometry("lame", (
        Segment("sym_y", np.array([[a, 0.0], [b, 0.0]])),
        Segment("outer", arc((0, 0), b, 0, math.pi / 2, 60), outer.project),
        Segment("sym_x", np.array([[0.0, b], [0.0, a]])),
        Segment("bore", arc((0, 0), a, math.pi / 2, 0, 60), inner.project),
    ), size=size)
    (bm,) = mesh_bodies([geo])
    body = assemble_body(bm, ElasticMaterial(E, NU, T), fixed=("sym_y",))  # K only; BCs below
    m = body.mesh
    nodes_y = np.unique(facet_nodes(m, m.boundaries["sym_y"]))
    nodes_x = np.unique(facet_nodes(m, m.boundaries["sym_x"]))
    D = np.concatenate([2 * nodes_y + 1, 2 * nodes_x])  # u_y = 0 on y = 0, u_x = 0 on x = 0
    fb = FacetBasis(m, ElementVector(ElementTriP2()), facets=m.boundaries["bore"])
    f = T * asm(LinearForm(lambda v, w: -p * dot(w.n, v)), fb)
    u = solve(*condense(body.K, f, D=D))
    sq = quadrature_stress(body, u)
    xq = body.basis.mapping.F(body.basis.X)  # (2, nelem, nqp)
    r2 = xq[0] ** 2 + xq[1] ** 2
    A = p * a * a / (b * b - a * a)
    B = A * b * b
    c2, s2, cs = xq[0] ** 2 / r2, xq[1] ** 2 / r2, xq[0] * xq[1] / r2
    sr, st = A - B / r2, A + B / r2
    exact = (sr * c2 + st * s2, sr * s2 + st * c2, (sr - st) * cs)
    dx = body.basis.dx
    err = math.sqrt(sum(np.sum((s - e) ** 2 * dx) for s, e in zip(sq, exact)))
    ref = math.sqrt(sum(np.sum(e**2 * dx) for e in exact))
    h = math.sqrt(np.sum(dx) / m.t.shape[1])
    return h, err / ref


def test_lame_cylinder_stress_converges_at_p2_rate():
    hs, errs = zip(*(lame_error(s) for s in (2.0, 1.0, 0.5, 0.25)))
    slope = np.polyfit(np.log(hs), np.log(errs), 1)[0]
    assert abs(slope - 2.0) < 0.2, (slope, errs)
    assert errs[-1] < 3e-4


def annulus(a, b, size):
    """Annulus about the origin: outer boundary "rim" and hole "bore", each of two halves
    (a name may cover several segments)."""
    bore = Circle((0, 0), a, "outside")
    rim = Circle((0, 0), b, "inside")
    geo = BodyGeometry("annulus", (
        Segment("rim", arc((0, 0), b, 0, math.pi), rim.project),
        Segment("rim", arc((0, 0), b, math.pi, 2 * math.pi), rim.project),
    ), size=size, holes=((
        Segment("bore", arc((0, 0), a, 0, math.pi), bore.project),
        Segment("bore", arc((0, 0), a, math.pi, 2 * math.pi), bore.project),
    ),))
    return mesh_bodies([geo])[0]


def test_annulus_turned_through_its_bore_rotates_by_closed_form():
    a, b, torque = 5.0, 20.0, 2.0e5  # mm, mm, N·mm
    bm = annulus(a, b, size=1.5)
    mat = ElasticMaterial(E, NU, T)
    body = assemble_body(bm, mat, fixed=("rim",), link=RigidLink("bore", "rotation"))
    assert not body.is_mechanism
    theta = torque / body.link_stiffness
    exact = torque / (4 * math.pi * mat.shear_modulus * T) * (1 / a**2 - 1 / b**2)
    assert theta == pytest.approx(exact, rel=5e-3)
    # the bore turns rigidly: ψ on the bore is ẑ × r
    nodes = np.unique(facet_nodes(body.mesh, body.mesh.boundaries["bore"]))
    x = body.mesh.doflocs.T[nodes]
    assert np.allclose(body.psi.reshape(-1, 2)[nodes], np.column_stack([-x[:, 1], x[:, 0]]),
                       atol=1e-14)


def test_mechanism_link_gives_rigid_response():
    b = 20.0
    bm = annulus(5.0, b, size=4.0)
    body = assemble_body(bm, ElasticMaterial(E, NU, T), link=RigidLink("bore", "rotation"))
    assert body.is_mechanism and body.link_stiffness == 0.0
    assert np.abs(body.K @ body.psi).max() < 1e-8 * np.abs(body.K).max() * b

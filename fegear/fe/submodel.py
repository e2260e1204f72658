"""Submodels: a small patch of a body around a boundary point, meshed finely and solved again
with the displacement of a coarser solution held on its cut and a pressure on its boundary.

A coarse model carries the load paths; the stress where it peaks (a root fillet, a contact only
µm wide) needs elements far smaller than that model can afford everywhere. The submodel's
patch is the body inside a circle of ``radius`` about a point of its boundary: the exact
boundary curve between the two points where the circle cuts it, and the circular arc through
the material. The arc is held at the coarse model's displacement (rigid motions included:
they strain nothing); the boundary carries the pressure. Away from the arc, by a fraction of
the radius, the submodel's stress is the fine solution of the same problem; ``core`` is where
it is read.

Units: mm, N, MPa. The boundary curve is star-shaped about the body frame's origin: points by
polar angle, with the material below it (an external gear) or beyond it (an internal gear).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from ..errors import FegearError
from .dofs import facet_nodes, node_dofs
from .forms import stiffness
from .material import ElasticMaterial
from .mesh import BodyGeometry, BodyMesh, Refinement, Segment, halved, mesh_bodies
from .solvers import Factor
from .stress import StressField, pickled_cache, recover

CORE = 0.6          # stresses are read within this fraction of the radius of the centre
ARC_POINTS = 48     # polyline points of the cut arc
QUADRATURE = 6      # Gauss points per boundary facet for the pressure
GROWTH = 0.3        # element growth away from the boundary (mm per mm)
SNAP_CHORD = 0.1    # boundary polylines stray from the curve by at most this of the finest
MAX_POINTS = 1000   # element size, with up to this many points a piece
#: gmsh's precision placing nodes along the patch's curves (Mesh.LcIntegrationPrecision; its
#: default 1e-9 spent 0.10 s of a submodel's 0.11 s there, the size falling 90-fold towards
#: the contact): 1e-5 meshes one in 0.02 s and moves the baseline's von Mises stress by 2e-5.
#: The templates keep the default: meshed at 1e-5, a design's flank pressure at `fine` moved
#: by 0.35 %, outside `standard`'s estimate
CURVE_PRECISION = 1e-5


@dataclass(frozen=True)
class StarCurve:
    """A body's boundary as points by polar angle (rad) about its frame's origin, and on which
    side the material lies: at smaller radii (``inside``) or at larger ones. Mesh nodes are
    snapped onto it along their polar angle, or by ``foot`` (points to their feet on the
    curve) where given: along the normal a node on a nearly radial stretch stays put."""

    point: Callable[[np.ndarray], np.ndarray]
    inside: bool
    foot: Callable[[np.ndarray], np.ndarray] | None = None

    def project(self, x: np.ndarray) -> np.ndarray:
        if self.foot is not None:
            return self.foot(x)
        return self.point(np.arctan2(x[:, 1], x[:, 0]))


@dataclass(eq=False)
class Submodel:
    """A solved submodel: its mesh (body frame), displacement, nodal stresses, the patch's
    centre (mm) and radius (mm), and the boundary's polar-angle range (rad)."""

    mesh: BodyMesh
    u: np.ndarray = field(repr=False)
    stress: StressField = field(repr=False)
    centre: np.ndarray
    radius: float
    angles: tuple[float, float]

    @property
    def core(self) -> np.ndarray:
        """Nodes within CORE radii of the centre: where the arc's held displacement no longer
        matters."""
        d = np.linalg.norm(self.mesh.mesh.doflocs.T - self.centre, axis=1)
        return d < CORE * self.radius

    def peak(self, values: np.ndarray) -> tuple[float, np.ndarray]:
        """Largest of nodal ``values`` in the core, and where (mm, body frame)."""
        core = np.flatnonzero(self.core)
        i = core[int(np.argmax(values[core]))]
        return float(values[i]), self.mesh.mesh.doflocs[:, i].copy()


@dataclass(frozen=True)
class _Piece:
    """What :func:`~fegear.fe.stress.recover` needs of a body."""

    mesh: object
    material: ElasticMaterial
    cache: dict


@dataclass(frozen=True)
class SubmodelProblem:
    """A submodel to solve: the patch of ``radius`` (mm) about the boundary point at polar angle
    ``angle`` of ``curve``; elements of ``size`` (mm) on the boundary within ``focus`` (mm)
    of that point, growing away from it; ``pressure(x)`` (MPa) on the boundary and
    ``held(x)``, the displacement (n, 2) imposed on the cut arc."""

    curve: StarCurve
    angle: float
    radius: float
    size: float
    focus: float
    pressure: Callable[[np.ndarray], np.ndarray]
    held: Callable[[np.ndarray], np.ndarray]
    name: str = "submodel"
    key: object = None


@dataclass(eq=False)
class _Prepared:
    """A submodel's mesh with its assembly and factorisation: what a later problem with the
    same key reuses (only the held displacement and the pressure change)."""

    mesh: BodyMesh
    centre: np.ndarray
    angles: tuple[float, float]
    piece: _Piece
    cut: np.ndarray
    fixed: np.ndarray
    free: np.ndarray
    K: object
    K_free_fixed: object
    factor: object


@dataclass(frozen=True)
class SubmodelMesh:
    """A submodel's mesh, centre, boundary angles, stiffness and what its stress recovery
    keeps (:func:`~.stress.recover`'s matrices), without a factorisation (as a model cache
    keeps it): :func:`solve_submodels` factorises it when first asked for it."""

    mesh: BodyMesh
    centre: np.ndarray
    angles: tuple[float, float]
    K: object = None
    cache: dict = field(default_factory=dict)


def submodel_meshes(kept: dict) -> dict:
    """The submodels in ``kept`` as :class:`SubmodelMesh` es (key → mesh), prepared or not:
    what a later process needs to skip meshing and assembling them."""
    return {k: v if isinstance(v, SubmodelMesh) else
            SubmodelMesh(v.mesh, v.centre, v.angles, v.K, pickled_cache(v.piece.cache))
            for k, v in kept.items()}


def solve_submodels(problems: list[SubmodelProblem], material: ElasticMaterial,
                    kept: dict | None = None) -> list[Submodel]:
    """Solve each submodel (those not prepared yet are meshed, a key asked for twice once).
    A problem whose ``key`` is in ``kept`` reuses that mesh and factorisation (the caller
    makes the key name one patch of one curve: the same key, the same geometry; a
    :class:`SubmodelMesh` there is assembled and factorised first); new ones are kept
    there."""
    kept = {} if kept is None else kept
    fresh = prepare_submodels(problems, material, kept)
    out = []
    for pb in problems:
        prep = fresh.get(id(pb)) or kept[pb.key]
        if isinstance(prep, SubmodelMesh):
            prep = kept[pb.key] = _prepare(prep.mesh, prep.centre, prep.angles, material,
                                           prep.K, prep.cache)
        m = prep.mesh.mesh
        f = _pressure_loads(m, m.boundaries["boundary"], pb.pressure, material.thickness)
        u = np.zeros(2 * m.doflocs.shape[1])
        u[prep.fixed] = pb.held(m.doflocs.T[prep.cut]).ravel()
        u[prep.free] = prep.factor.solve(f[prep.free] - prep.K_free_fixed @ u[prep.fixed])
        out.append(Submodel(prep.mesh, u, recover(prep.piece, u), prep.centre, float(pb.radius),
                            prep.angles))
    return out


def prepare_submodels(problems: list[SubmodelProblem], material: ElasticMaterial,
                      kept: dict) -> dict:
    """Mesh, assemble and factorise the submodels of ``problems`` whose key is not in
    ``kept`` (a key asked for twice once), keep them there under their keys, and return them
    by the problem's id (a problem without a key is kept only there): what
    :func:`solve_submodels` solves on, or what a caller prepares ahead where it has a
    moment to spare."""
    todo, keys = [], set()
    for pb in problems:
        if pb.key is None or (pb.key not in kept and pb.key not in keys):
            todo.append(pb)
            keys.add(pb.key)
    shapes = [_geometry(pb) for pb in todo]
    meshes = mesh_bodies([geo for geo, _, _ in shapes]) if shapes else ()
    fresh = {id(pb): _prepare(mesh, centre, angles, material)
             for pb, (_, centre, angles), mesh in zip(todo, shapes, meshes)}
    for pb in todo:
        if pb.key is not None:
            kept[pb.key] = fresh[id(pb)]
    return fresh


def _prepare(mesh: BodyMesh, centre, angles, material: ElasticMaterial, K=None,
             cache: dict | None = None) -> _Prepared:
    """Assemble (unless its stiffness ``K`` is given) and factorise a submodel's mesh;
    ``cache``: its stress recovery's matrices, if kept."""
    m = mesh.mesh
    if K is None:
        K = stiffness(m, *material.lame, material.thickness)
    cut = np.unique(facet_nodes(m, m.boundaries["cut"]))
    fixed = node_dofs(cut).ravel()
    free = np.setdiff1d(np.arange(2 * m.doflocs.shape[1]), fixed)
    return _Prepared(mesh, centre, angles, _Piece(m, material, dict(cache or {})), cut,
                     fixed, free, K, K[free][:, fixed], Factor(K[free][:, free]))


def _geometry(pb: SubmodelProblem):
    """The submodel's body (boundary curve and cut arc), centre (mm) and boundary angles."""
    curve, radius, size = pb.curve, pb.radius, pb.size
    centre = curve.point(np.array([pb.angle]))[0]
    focus = min(pb.focus, 0.5 * radius)
    (a, b), (lo, hi) = _cut_angles(curve, pb.angle, centre, (focus, radius))
    pieces = []
    for t0, t1, zone in ((lo, a, None), (a, b, "focus"), (b, hi, None)):
        span = np.linalg.norm(np.diff(curve.point(np.array([t0, t1])), axis=0))
        # a spline point every few elements: nodes are snapped onto the curve anyway, and
        # gmsh's cost grows with the spline's points
        samples = int(min(200, max(8, 0.5 * span / (size if zone else radius / 8))))
        t = np.linspace(t0, t1, samples)
        points = halved(curve.point, t, curve.point(t), SNAP_CHORD * size, MAX_POINTS)
        pieces.append(Segment("boundary", points, curve.project, zone))
    arc = _arc(curve, centre, radius, pieces[-1].points[-1], pieces[0].points[0])
    geo = BodyGeometry(pb.name, (
        *pieces,
        Segment("cut", arc, lambda x: centre + radius * (x - centre)
                / np.linalg.norm(x - centre, axis=1)[:, None]),
    ), size=max(radius / 4, size), refinements=(Refinement(("focus",), size, GROWTH),),
        curve_precision=CURVE_PRECISION)
    return geo, centre, (lo, hi)


def _cut_angles(curve: StarCurve, angle: float, centre: np.ndarray, radii
                ) -> list[tuple[float, float]]:
    """Per radius of ``radii`` (ascending), the polar angles on each side of ``angle`` where
    the boundary crosses the circle of that radius: the first sign change of
    |x(a) − centre| − radius along each side, its bracket then narrowed twice 160-fold."""
    r = float(np.linalg.norm(centre))
    out = {radius: [] for radius in radii}
    for side in (-1.0, 1.0):
        span = 0.5 * radii[-1] / r
        for _ in range(12):
            a = angle + side * np.linspace(0.0, span, 161)
            d = np.linalg.norm(curve.point(a) - centre, axis=1)
            if d[-1] > radii[-1]:
                break
            span *= 4.0
        else:
            raise FegearError("the submodel's circle does not cut the boundary twice")
        for radius in radii:
            k = int(np.flatnonzero(d > radius)[0])
            lo, hi = a[k - 1], a[k]
            for _ in range(2):
                t = np.linspace(lo, hi, 161)
                dt = np.linalg.norm(curve.point(t) - centre, axis=1)
                j = int(np.flatnonzero(dt > radius)[0]) if np.any(dt > radius) else len(t) - 1
                lo, hi = t[max(j - 1, 0)], t[j]
            out[radius].append(0.5 * (lo + hi))
    return [tuple(sorted(out[radius])) for radius in radii]


def _arc(curve: StarCurve, centre: np.ndarray, radius: float, start: np.ndarray,
         end: np.ndarray) -> np.ndarray:
    """Points of the circle from ``start`` to ``end`` through the material."""
    a = math.atan2(*(start - centre)[::-1])
    span = (math.atan2(*(end - centre)[::-1]) - a) % (2 * math.pi)
    for sweep in (span, span - 2 * math.pi):
        mid = centre + radius * np.array([math.cos(a + 0.5 * sweep), math.sin(a + 0.5 * sweep)])
        # the curve's radius at the point's polar angle (the curve is star-shaped; its
        # nearest point is no test where it bends sharply, as on a pointed gear-2 tip)
        edge = np.linalg.norm(curve.point(np.array([math.atan2(mid[1], mid[0])]))[0])
        if (np.linalg.norm(mid) < edge) == curve.inside:
            t = a + np.linspace(0.0, sweep, ARC_POINTS)
            pts = centre + radius * np.column_stack([np.cos(t), np.sin(t)])
            pts[0], pts[-1] = start, end
            return pts
    raise FegearError("the submodel's arc does not pass through the material")


def _pressure_loads(m, facets: np.ndarray, pressure, thickness: float) -> np.ndarray:
    """Consistent nodal loads of the pressure on boundary ``facets`` (traction −p n, n out of
    the material), Gauss quadrature on each quadratic facet."""
    nodes = facet_nodes(m, facets)
    gq, gw = np.polynomial.legendre.leggauss(QUADRATURE)
    s, w = 0.5 * (gq + 1.0), 0.5 * gw
    N = np.column_stack([(1 - s) * (1 - 2 * s), s * (2 * s - 1), 4 * s * (1 - s)])
    dN = np.column_stack([4 * s - 3, 4 * s - 1, 4 - 8 * s])
    X = m.doflocs.T[nodes]                                       # (nf, 3, 2)
    xq = np.einsum("qk,fkd->fqd", N, X)
    tq = np.einsum("qk,fkd->fqd", dN, X)
    jac = np.linalg.norm(tq, axis=2)
    normal = np.stack([tq[..., 1], -tq[..., 0]], axis=-1) / jac[..., None]
    centroid = m.p[:, m.t[:, m.f2t[0, facets]]].mean(axis=1).T    # orient out of the element
    normal *= np.sign(np.einsum("fd,fd->f", X[:, 2] - centroid, normal[:, 2]))[:, None, None]
    p = pressure(xq.reshape(-1, 2)).reshape(jac.shape)
    f = np.zeros(2 * m.doflocs.shape[1])
    for k in range(3):
        for d in range(2):
            np.add.at(f, 2 * nodes[:, k] + d,
                      -thickness * np.sum(p * normal[..., d] * N[None, :, k] * jac * w, axis=1))
    return f

"""Meshing: second-order triangle meshes of plane bodies with named boundary parts.

The only module that imports gmsh. A body is a closed outer loop (plus optional hole loops) of
named :class:`Segment` s; each segment is a dense polyline along an exact curve and may carry a
``project`` callable that maps points onto that curve, so that every boundary node, midside
nodes included, is snapped onto the exact geometry after meshing. Local refinement is a gmsh
Distance + Threshold field per refined segment, combined by Min as the background size.

The quadratic mesh is built into :class:`skfem.MeshTri2` here, corner nodes first, with the
boundary facets taken from the first two nodes of each ``line3`` (``from_meshio`` would drop the
named boundaries, docs/model.md, "Library notes"). Coordinates are mm.
"""

from __future__ import annotations

import contextlib
import logging
import math
import signal
import threading
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np
from skfem import MeshTri2

from ..errors import FegearError
from ..files import write_atomic
from .dofs import facet_nodes
from .probe import p2_grad

log = logging.getLogger(__name__)

#: how precisely gmsh integrates the size field along each curve to place its nodes (its
#: Mesh.LcIntegrationPrecision), by default: a body may ask for less (a contact submodel:
#: :data:`~.submodel.CURVE_PRECISION`)
CURVE_PRECISION = 1e-9

_TRIANGLE6 = 9
_LINE3 = 8


class MeshError(FegearError):
    """A body could not be meshed, or its mesh failed the quality check."""


@dataclass(frozen=True)
class Segment:
    """A named piece of boundary.

    ``points`` is an (n, 2) polyline in mm, ordered along the loop (outer loops counter-clockwise,
    holes clockwise are both accepted: gmsh orients them). Two points make a straight line; more
    make a spline through them. ``project`` maps an (k, 2) array of points onto the exact curve.
    ``zone`` is an extra name a :class:`Refinement` can refer to (the boundary keeps ``name``).
    """

    name: str
    points: np.ndarray
    project: Callable[[np.ndarray], np.ndarray] | None = None
    zone: str | None = None

    def __post_init__(self) -> None:
        pts = np.asarray(self.points, dtype=float)
        if pts.ndim != 2 or pts.shape[1] != 2 or len(pts) < 2 or not np.all(np.isfinite(pts)):
            raise MeshError(f"segment {self.name!r}: points must be a finite (n>=2, 2) array")
        object.__setattr__(self, "points", pts)


@dataclass(frozen=True)
class Refinement:
    """Element size ``size`` (mm) on the segments named (or zoned) ``segments``, growing by
    ``growth`` mm per mm away."""

    segments: tuple[str, ...]
    size: float
    growth: float = 0.25


@dataclass(frozen=True)
class Periodic:
    """Segment ``slave`` meshed as segment ``master`` turned by ``angle`` (rad) about the origin:
    the two cut faces of a sector of a cyclic body carry matching nodes."""

    slave: str
    master: str
    angle: float


@dataclass(frozen=True)
class BodyGeometry:
    """A plane body: outer loop, holes, global element size ``size`` (mm), refinements,
    periodic segment pairs and how precisely gmsh places the nodes along its curves
    (:data:`CURVE_PRECISION`)."""

    name: str
    outer: tuple[Segment, ...]
    size: float
    holes: tuple[tuple[Segment, ...], ...] = ()
    refinements: tuple[Refinement, ...] = ()
    min_quality: float = 0.15
    periodic: tuple[Periodic, ...] = ()
    curve_precision: float = CURVE_PRECISION

    def segments(self) -> Iterator[Segment]:
        yield from self.outer
        for hole in self.holes:
            yield from hole


@dataclass(frozen=True)
class MeshQuality:
    """Quality of a quadratic triangle mesh.

    ``min_shape``: smallest 4√3·A/Σl² of the corner triangles (1 = equilateral).
    ``min_jacobian_ratio``: smallest min/max of the quadratic map's Jacobian determinant over
    each element's nodes (≤ 0 means inverted).
    """

    elements: int
    nodes: int
    min_shape: float
    min_jacobian_ratio: float
    h_min: float
    h_max: float


@dataclass(frozen=True)
class BodyMesh:
    """A meshed body: the scikit-fem mesh (with ``mesh.boundaries`` by segment name), its
    quality and, per :class:`Periodic` pair (by slave name), the matching nodes: an (n, 2) array
    of (slave node, master node) indices into ``mesh.doflocs``, midside nodes included, in the
    master segment's node order."""

    name: str
    mesh: MeshTri2
    quality: MeshQuality
    periodic: dict = field(default_factory=dict)


@contextlib.contextmanager
def gmsh_session() -> Iterator[object]:
    """Initialise gmsh quietly and always finalise it, whatever happens inside. gmsh's
    initialisation sets SIGTERM back to the system's default (the process dies without a
    word, its temporary files left) and SIGPIPE too (a write to a closed pipe then kills the
    process instead of raising BrokenPipeError, as Python's own setting does): the handlers
    from before are put back."""
    import gmsh

    held = _signal_handlers()
    gmsh.initialize(readConfigFiles=False, interruptible=False)
    for signum, handler in held.items():
        signal.signal(signum, handler)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.option.setNumber("General.Verbosity", 1)
        yield gmsh
    finally:
        gmsh.finalize()


def _signal_handlers() -> dict:
    """Python's handlers of SIGTERM, SIGINT and SIGPIPE (none outside the main thread, where
    they cannot be set)."""
    if threading.current_thread() is not threading.main_thread():
        return {}
    return {s: h for s in (signal.SIGTERM, signal.SIGINT, signal.SIGPIPE)
            if (h := signal.getsignal(s)) is not None}


def import_gmsh() -> None:
    """Import gmsh now rather than at the first mesh (:func:`.libraries.import_libraries`)."""
    import gmsh  # noqa: F401


def mesh_bodies(bodies: Sequence[BodyGeometry]) -> tuple[BodyMesh, ...]:
    """Mesh each body with second-order triangles and check the quality of every mesh. Each
    body gets a gmsh session of its own (0.5 ms): meshed after another in the same session,
    a body's mesh came out different (1696 nodes instead of 1692 for a contact submodel), so
    that a mesh depended on what had been meshed before it."""
    out = []
    for body in bodies:
        with gmsh_session() as gmsh:
            out.append(_mesh_one(gmsh, body))
    return tuple(out)


def _loop(gmsh, segments: Sequence[Segment], tags: dict[str, list[int]],
          zones: dict[str, list[int]]) -> int:
    """A closed curve loop: each segment starts at the point where the one before ended (by
    tag, not by rounded coordinates: two ends 1e-13 mm apart once rounded apart and broke the
    loop), the last ends where the first started."""
    geo = gmsh.model.geo
    curves = []
    n = len(segments)
    first = start = geo.addPoint(*map(float, segments[0].points[0]), 0.0)
    for k, seg in enumerate(segments):
        nxt = segments[(k + 1) % n].points[0]
        if np.linalg.norm(seg.points[-1] - nxt) > 1e-9 * (1 + np.abs(nxt).max()):
            raise MeshError(f"segment {seg.name!r} does not end where the next segment starts")
        end = first if k == n - 1 else geo.addPoint(*map(float, seg.points[-1]), 0.0)
        pt = [start, end]
        start = end
        inner = [geo.addPoint(x, y, 0.0) for x, y in seg.points[1:-1]]
        if inner:
            c = geo.addSpline([pt[0], *inner, pt[1]])
        else:
            c = geo.addLine(pt[0], pt[1])
        curves.append(c)
        tags.setdefault(seg.name, []).append(c)
        if seg.zone is not None:
            zones.setdefault(seg.zone, []).append(c)
    return geo.addCurveLoop(curves)


def _mesh_one(gmsh, body: BodyGeometry) -> BodyMesh:
    if not (np.isfinite(body.size) and body.size > 0):
        raise MeshError(f"body {body.name!r}: global element size must be > 0")
    gmsh.model.add(body.name)
    geo = gmsh.model.geo
    curve_tags: dict[str, list[int]] = {}
    zone_tags: dict[str, list[int]] = {}
    try:
        loops = [_loop(gmsh, body.outer, curve_tags, zone_tags)]
        loops += [_loop(gmsh, hole, curve_tags, zone_tags) for hole in body.holes]
        surface = geo.addPlaneSurface(loops)
        geo.synchronize()
    except Exception as exc:  # gmsh raises plain Exception with its log message
        if isinstance(exc, MeshError):
            raise
        raise MeshError(f"body {body.name!r}: gmsh refused the boundary: {exc}") from None
    for pair in body.periodic:
        tags = [curve_tags.get(pair.slave, []), curve_tags.get(pair.master, [])]
        if any(len(t) != 1 for t in tags):
            raise MeshError(f"body {body.name!r}: periodic segments {pair.slave!r} and "
                            f"{pair.master!r} must be one segment each")
        c, s = math.cos(pair.angle), math.sin(pair.angle)
        gmsh.model.mesh.setPeriodic(1, tags[0], tags[1],
                                    [c, -s, 0, 0, s, c, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1])

    fields = []
    known = {**curve_tags, **zone_tags}
    for ref in body.refinements:
        missing = [s for s in ref.segments if s not in known]
        if missing or not (ref.size > 0 and ref.growth > 0):
            raise MeshError(f"body {body.name!r}: bad refinement {ref} (unknown {missing})")
        tags = sorted({t for s in ref.segments for t in known[s]})
        length = sum(_polyline_length(seg.points) for seg in body.segments()
                     if seg.name in ref.segments or seg.zone in ref.segments)
        dist = gmsh.model.mesh.field.add("Distance")
        gmsh.model.mesh.field.setNumbers(dist, "CurvesList", tags)
        gmsh.model.mesh.field.setNumber(dist, "Sampling", int(min(2e4, 4 * length / ref.size + 20)))
        thr = gmsh.model.mesh.field.add("Threshold")
        gmsh.model.mesh.field.setNumber(thr, "InField", dist)
        gmsh.model.mesh.field.setNumber(thr, "SizeMin", ref.size)
        gmsh.model.mesh.field.setNumber(thr, "SizeMax", body.size)
        gmsh.model.mesh.field.setNumber(thr, "DistMin", 0.5 * ref.size)
        gmsh.model.mesh.field.setNumber(thr, "DistMax",
                                        0.5 * ref.size + (body.size - ref.size) / ref.growth)
        fields.append(thr)
    if fields:
        fmin = gmsh.model.mesh.field.add("Min")
        gmsh.model.mesh.field.setNumbers(fmin, "FieldsList", fields)
        gmsh.model.mesh.field.setAsBackgroundMesh(fmin)
    opt = gmsh.option.setNumber
    opt("Mesh.MeshSizeExtendFromBoundary", 0)
    opt("Mesh.MeshSizeFromPoints", 0)
    opt("Mesh.MeshSizeFromCurvature", 0)
    opt("Mesh.MeshSizeMax", body.size)
    opt("Mesh.Algorithm", 6)
    opt("Mesh.LcIntegrationPrecision", body.curve_precision)
    opt("Mesh.ElementOrder", 2)
    opt("Mesh.SecondOrderLinear", 0)
    try:
        gmsh.model.mesh.generate(2)
    except Exception as exc:  # gmsh raises plain Exception with its log message
        raise MeshError(f"body {body.name!r}: gmsh failed: {exc}") from None

    node_tags, coords, _ = gmsh.model.mesh.getNodes()
    xy = np.asarray(coords).reshape(-1, 3)[:, :2]
    index = np.full(int(node_tags.max()) + 1, -1, dtype=np.int64)
    index[node_tags] = np.arange(len(node_tags))
    etypes, _, enodes = gmsh.model.mesh.getElements(2, surface)
    if list(etypes) != [_TRIANGLE6]:
        raise MeshError(f"body {body.name!r}: gmsh returned element types {list(etypes)}")
    tri = index[np.asarray(enodes[0]).reshape(-1, 6)]

    lines: dict[str, np.ndarray] = {}
    for name, tags in curve_tags.items():
        rows = []
        for tag in tags:
            ltypes, _, lnodes = gmsh.model.mesh.getElements(1, tag)
            rows.append(index[np.asarray(lnodes[0]).reshape(-1, 3)])
        lines[name] = np.vstack(rows)
    gmsh.model.remove()
    return _build(body, xy, tri, lines)


def halved(curve, theta: np.ndarray, points: np.ndarray, tol: float,
           max_points: int) -> np.ndarray:
    """The polyline ``points`` (``curve`` at the parameters ``theta``) with every interval
    halved until the curve strays at most ``tol`` (mm) from its chord there, up to
    ``max_points``. Nodes are snapped onto the exact curve after meshing: a chord that strays
    by a large part of an element moves its nodes that far and can invert the element (gear 2's
    flanks at m 0.5, turning at 0.26 mm, strayed 6 µm from 8-point polylines in 25 µm
    elements; a contact submodel's 8 points over 1.5 mm of a pointed tooth, 7 µm in 3 µm)."""
    for _ in range(20):
        mid = 0.5 * (theta[1:] + theta[:-1])
        at_mid = curve(mid)
        chord, off = np.diff(points, axis=0), at_mid - points[:-1]
        sag = np.abs(chord[:, 0] * off[:, 1] - chord[:, 1] * off[:, 0]) / np.hypot(*chord.T)
        far = sag > tol
        if not far.any() or len(theta) + far.sum() > max_points:
            break
        order = np.argsort(np.concatenate([theta, mid[far]]), kind="stable")
        theta = np.concatenate([theta, mid[far]])[order]
        points = np.concatenate([points, at_mid[far]])[order]
    return points


@dataclass(frozen=True)
class Circle:
    """A circle of ``radius`` (mm) about ``centre``: a loop of a plate (:func:`write_step`)."""

    radius: float
    centre: tuple[float, float] = (0.0, 0.0)


def write_step(path: str | Path, outer: Sequence[Segment] | Circle, thickness: float,
               holes: Sequence[Sequence[Segment] | Circle] = ()) -> Path:
    """Write the plate that the face inside ``outer`` and outside ``holes`` makes, extruded
    by ``thickness`` (mm) along +z from z = 0, as one solid in a STEP file (mm), built by
    gmsh's OpenCASCADE kernel. A loop is a :class:`Circle` or closed segments, each a spline
    through its points (a line through two) starting where the one before ended. Written
    atomically; raises :class:`MeshError` where the kernel refuses the plate."""
    if not (np.isfinite(thickness) and thickness > 0):
        raise MeshError(f"a plate's thickness must be > 0, not {thickness!r}")
    with gmsh_session() as gmsh:
        occ = gmsh.model.occ
        gmsh.model.add("plate")
        try:
            loops = [_occ_loop(occ, loop) for loop in (outer, *holes)]
            face = occ.addPlaneSurface(loops)
            occ.extrude([(2, face)], 0.0, 0.0, float(thickness))
            occ.synchronize()
        except Exception as exc:  # gmsh raises plain Exception with its log message
            if isinstance(exc, MeshError):
                raise
            raise MeshError(f"the kernel refused the plate: {exc}") from None
        if len(gmsh.model.getEntities(3)) != 1:
            raise MeshError("the plate is not one solid")
        with _stdout_silenced():
            return write_atomic(Path(path), lambda tmp: gmsh.write(str(tmp)))


@contextlib.contextmanager
def _stdout_silenced() -> Iterator[None]:
    """The process's standard output (file descriptor 1) sent to the null device for a
    while: OpenCASCADE's STEP writer prints its transfer statistics there whatever gmsh's
    verbosity, which would mix into a command's printed JSON."""
    import ctypes
    import os
    import sys

    sys.stdout.flush()
    saved, null = os.dup(1), os.open(os.devnull, os.O_WRONLY)
    try:
        os.dup2(null, 1)
        yield
    finally:
        try:                             # what C's stdio holds goes to the null device too
            ctypes.CDLL(None).fflush(None)
        except (OSError, AttributeError):    # no C library by that name (Windows)
            pass
        os.dup2(saved, 1)
        os.close(saved)
        os.close(null)


def _occ_loop(occ, loop: Sequence[Segment] | Circle) -> int:
    """An OpenCASCADE curve loop of a circle or of closed segments (:func:`write_step`),
    neighbours sharing their end points by tag as :func:`_loop`'s do."""
    if isinstance(loop, Circle):
        return occ.addCurveLoop([occ.addCircle(*loop.centre, 0.0, loop.radius)])
    first = start = occ.addPoint(*map(float, loop[0].points[0]), 0.0)
    curves = []
    for k, seg in enumerate(loop):
        nxt = loop[(k + 1) % len(loop)].points[0]
        if np.linalg.norm(seg.points[-1] - nxt) > 1e-9 * (1 + np.abs(nxt).max()):
            raise MeshError(f"segment {seg.name!r} does not end where the next segment starts")
        end = first if k == len(loop) - 1 else occ.addPoint(*map(float, seg.points[-1]), 0.0)
        inner = [occ.addPoint(x, y, 0.0) for x, y in seg.points[1:-1]]
        curves.append(occ.addSpline([start, *inner, end]) if inner else
                      occ.addLine(start, end))
        start = end
    return occ.addCurveLoop(curves)


def _polyline_length(points: np.ndarray) -> float:
    return float(np.sum(np.linalg.norm(np.diff(points, axis=0), axis=1)))


def _build(body: BodyGeometry, xy: np.ndarray, tri: np.ndarray,
           lines: dict[str, np.ndarray]) -> BodyMesh:
    """Snap boundary nodes onto exact curves, orient elements, build MeshTri2 with boundaries."""
    xy = xy.copy()
    segs = {s.name: s for s in body.segments()}
    for name, l3 in lines.items():
        if segs[name].project is not None:
            nodes = np.unique(l3)
            xy[nodes] = segs[name].project(xy[nodes])

    used = np.unique(tri)
    renum = np.full(len(xy), -1, dtype=np.int64)
    renum[used] = np.arange(len(used))
    xy, tri = xy[used], renum[tri]
    lines = {k: renum[v] for k, v in lines.items()}

    # counter-clockwise corners (gmsh's are, but the snapped geometry decides)
    a = _corner_areas(xy, tri)
    flip = a < 0
    tri[flip] = tri[flip][:, [0, 2, 1, 5, 4, 3]]

    mesh = MeshTri2(xy.T.copy(), tri.T.copy())
    # MeshTri2 renumbers corners first, preserving their relative order
    corners = np.unique(tri[:, :3])
    new_of_old = np.full(len(xy), -1, dtype=np.int64)
    new_of_old[corners] = np.arange(len(corners))
    facet_of = {tuple(f): i for i, f in enumerate(np.sort(mesh.facets, axis=0).T)}
    boundaries = {}
    for name, l3 in lines.items():
        ends = np.sort(new_of_old[l3[:, :2]], axis=1)
        try:
            boundaries[name] = np.array([facet_of[tuple(e)] for e in ends], dtype=np.int64)
        except KeyError:
            raise MeshError(f"body {body.name!r}: boundary {name!r} lost its facets") from None
    mesh = mesh.with_boundaries(boundaries)
    periodic = {pair.slave: _matching_nodes(body.name, mesh, pair) for pair in body.periodic}
    quality = mesh_quality(mesh)
    if quality.min_jacobian_ratio <= 0.0:
        raise MeshError(f"body {body.name!r}: inverted element "
                        f"(Jacobian ratio {quality.min_jacobian_ratio:.3g})")
    if quality.min_shape < body.min_quality:
        raise MeshError(f"body {body.name!r}: badly shaped element (quality "
                        f"{quality.min_shape:.3f} < {body.min_quality})")
    log.debug("meshed %s: %s", body.name, quality)
    return BodyMesh(body.name, mesh, quality, periodic)


def _matching_nodes(name: str, mesh: MeshTri2, pair: Periodic) -> np.ndarray:
    """(slave node, master node) pairs of a periodic segment pair, matched by position."""
    from scipy.spatial import cKDTree

    nodes = [np.unique(facet_nodes(mesh, mesh.boundaries[n])) for n in (pair.slave, pair.master)]
    x = mesh.doflocs.T
    c, s = math.cos(pair.angle), math.sin(pair.angle)
    turned = x[nodes[1]] @ np.array([[c, s], [-s, c]])
    dist, k = cKDTree(x[nodes[0]]).query(turned)
    scale = 1.0 + np.abs(x[nodes[1]]).max()
    if len(nodes[0]) != len(nodes[1]) or dist.max() > 1e-8 * scale or len(set(k)) != len(k):
        raise MeshError(f"body {name!r}: the nodes of {pair.slave!r} do not match those of "
                        f"{pair.master!r} turned by {pair.angle:g} rad")
    return np.column_stack([nodes[0][k], nodes[1]])


def jiggle(body: BodyMesh, fraction: float, seed: int = 0) -> BodyMesh:
    """The same mesh with every interior corner node moved by ``fraction`` of its shortest
    edge, each in a random direction; boundary nodes stay on the exact curves and interior
    edges stay straight (their midside nodes follow). For mesh-sensitivity checks."""
    mesh = body.mesh
    rng = np.random.default_rng(seed)
    x = mesh.doflocs.T.copy()
    t, mid = mesh.t.T, mesh.dofs.element_dofs.T[:, 3:]  # edges 01, 12, 02 (as mesh.t2f)
    ends = ((0, 1), (1, 2), (0, 2))
    length = np.full(len(x), np.inf)
    for a, b in ends:
        d = np.linalg.norm(x[t[:, a]] - x[t[:, b]], axis=1)
        np.minimum.at(length, t[:, a], d)
        np.minimum.at(length, t[:, b], d)
    on_boundary = np.zeros(mesh.facets.shape[1], dtype=bool)
    on_boundary[mesh.boundary_facets()] = True
    moving = np.setdiff1d(np.unique(t), mesh.facets[:, on_boundary])
    angle = rng.uniform(0.0, 2 * np.pi, len(moving))
    x[moving] += fraction * length[moving, None] * np.column_stack([np.cos(angle),
                                                                    np.sin(angle)])
    for k, (a, b) in enumerate(ends):
        inner = ~on_boundary[mesh.t2f[k]]
        x[mid[inner, k]] = 0.5 * (x[t[inner, a]] + x[t[inner, b]])
    moved = replace(mesh, doflocs=x.T.copy())
    quality = mesh_quality(moved)
    if quality.min_jacobian_ratio <= 0.0:
        raise MeshError(f"body {body.name!r}: jiggling by {fraction:g} inverted an element")
    return BodyMesh(body.name, moved, quality, body.periodic)


def _corner_areas(xy: np.ndarray, tri: np.ndarray) -> np.ndarray:
    p0, p1, p2 = xy[tri[:, 0]], xy[tri[:, 1]], xy[tri[:, 2]]
    d1, d2 = p1 - p0, p2 - p0
    return 0.5 * (d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0])


def mesh_quality(mesh: MeshTri2) -> MeshQuality:
    """Shape and Jacobian quality of every element of a quadratic triangle mesh."""
    p = mesh.p.T
    t = mesh.t.T
    e = np.stack([p[t[:, 1]] - p[t[:, 0]], p[t[:, 2]] - p[t[:, 1]], p[t[:, 0]] - p[t[:, 2]]])
    lsq = np.sum(e**2, axis=2)
    area = _corner_areas(p, t)
    shape = 4.0 * np.sqrt(3.0) * area / lsq.sum(axis=0)
    # Jacobian determinant of the quadratic map at the 6 nodes and the centroid
    x = mesh.doflocs[:, mesh.dofs.element_dofs]  # (2, 6, nelem): corners, then edges 01, 12, 02
    ref = np.array([[0, 0], [1, 0], [0, 1], [0.5, 0], [0.5, 0.5], [0, 0.5], [1 / 3, 1 / 3]])
    dets = []
    for xi, eta in ref:
        dn = p2_grad(xi, eta)  # (6, 2)
        jac = np.einsum("din,ij->ndj", x, dn)
        dets.append(jac[:, 0, 0] * jac[:, 1, 1] - jac[:, 0, 1] * jac[:, 1, 0])
    dets = np.array(dets)
    ratio = dets.min(axis=0) / np.abs(dets).max(axis=0)
    h = np.sqrt(lsq)
    return MeshQuality(mesh.t.shape[1], mesh.doflocs.shape[1], float(shape.min()),
                       float(ratio.min()), float(h.min()), float(h.max()))

"""A gear's tooth in 3D: how a load at one point of the face moves the flank along the face
(docs/model.md, "Across the face: the tooth in 3D"), the reference a slice model of the face
width is checked against. Gear 1's tooth by default; gear 2's (``gear=2``) alike, below.

The body is :data:`PITCHES` pitches of gear 1 about the loaded tooth 0, cut radially through
the middles of tooth spaces, down to the bore the solve takes (3 m below the root), with the
solve's tip rounds. Its section is meshed by gmsh (:func:`fegear.fe.mesh_bodies`: fine on the
load band, finer on tooth 0's loaded flank and on its neighbours) and extruded along the face
in equal layers, each triangular prism cut into three tetrahedra by the nodes' numbers (the
faces two prisms share are cut alike). The elements are quadratic (scikit-fem's
``ElementTetP2``, straight edges); :func:`tet_stiffness` forms their stiffness from
scikit-fem's shape gradients for all elements at once. The bore is held; the radial cuts and
the two ends of the face are free.

Gear 2's body (the internal gear, its teeth standing inward on an outer rim) is :data:`PITCHES`
pitches of its exact profile about its tooth 0 (the tooth tip's middle at polar angle 0: its
teeth are all alike), cut radially through the middles of its tooth spaces, out to the rim
the solve takes (``SolveCase.rims[1]`` beyond its root). The rim's outer arc is held. Its
loaded flank is the one before the tooth (smaller polar angle; the one gear 1's loaded flank
presses, :func:`~fegear.toothpair.teeth.tension_fillets`), its height by radius from the root
(the tooth space's middle, r0 + 2 e1) to the tip's middle (r0 − 2 e1).

The load: ``patches`` patches tile the face along one line of tooth 0's loaded flank, each
b/patches wide and :data:`PATCH` m along the profile, each under a normal pressure of unit
total force; the whole band under unit force is the uniform line load. A patch's response to
a load is its own load vector times the displacement: the mean displacement into the tooth
over the patch. So the influence matrix is Fᵀ K⁻¹ F.

The solver is conjugate gradients on all load cases at once, preconditioned by a two-level
cycle (:class:`TwoLevel`). Direct CHOLMOD is slow here: the ``cholespy`` wheel links the
reference BLAS, and the 3D factor took 42 s at 75k dofs and 168 s at 146k.
"""

from __future__ import annotations

import sys
from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp
from scipy.integrate import quad
from scipy.optimize import brentq
from skfem import Basis, ElementTetP2, ElementTriP2, ElementVector, MeshTet1, MeshTri1, asm
from skfem.models.elasticity import linear_elasticity

from ..errors import FegearError, ParameterError
from ..fe import STEEL_E, STEEL_NU, BodyGeometry, Factor, Refinement, Segment, mesh_bodies
from ..geometry import Cycloid, PairParameters, RoundedProfile, gear1_profile, gear2_curve
from ..timing import Stopwatch
from ..toothpair import (
    FlankBand,
    Layout,
    PolarCurve,
    SolveCase,
    flank_band,
    gear2_outline,
    gear2_polar,
    profile_segments,
    tip_round_of,
)

#: a patch's length along the profile, in modules (0.2 mm at m 2)
PATCH = 0.1
#: gear 1's pitches in the body, tooth 0 in the middle: the plane answer of 3 with their cuts
#: free was 8.5 % above that of 13, of 9 0.06 % (docs/model.md)
PITCHES = 9
#: the solver stops once every load case's residual is below this part of its load
TOLERANCE = 1e-10
ITERATIONS = 400
#: an outer rim's nodes held within this part of its radius: a rim edge's middle node sits on
#: its chord, 10 µm inside the arc at `coarse`'s 2 mm elements, the next node 0.5 mm or more
RIM_TOLERANCE = 1e-3


class SolveError(FegearError):
    """The conjugate gradients did not converge."""


@dataclass(frozen=True)
class Resolution:
    """A mesh level: elements along a patch's profile length, layers across a patch's width,
    and element sizes in modules on tooth 0's loaded flank, on the flanks of tooth 0 and its
    neighbours, and elsewhere (the teeth beyond them too)."""

    along: int
    layers: int
    loaded: float
    flank: float
    body: float
    growth: float = 0.5   # mm per mm away from a refined piece


SIZES = {"coarse": Resolution(2, 1, 0.15, 0.3, 1.0),
         "standard": Resolution(4, 3, 0.1, 0.2, 0.75),
         "fine": Resolution(6, 4, 0.075, 0.15, 0.6)}


@dataclass(frozen=True)
class FaceInfluence:
    """A gear's tooth under loads along the face at one profile point.

    Attributes:
        z: (n,) patch centres, mm from one end of the face.
        G: (n, n) µm per N: the mean displacement into the tooth over patch i (along the
            flank's normal) under a unit force on patch j.
        uniform: (n,) µm per N: the same at each patch under a unit force spread evenly
            over the whole face (the plane model's load).
        along_z, along: (k,) mm and (k, n + 1) µm per N: the displacement into the tooth,
            the mean over the patch band's profile length, at every node level along the
            face, under each patch's load and (last column) the uniform one.
        plane_stress, plane_strain: µm per N: the section in 2D (the same triangles, P2)
            under the uniform load, 1/b N/mm over the band.
        radius, height: the load point's radius (mm) and its place on the working flank,
            by radius (0 the root, the middle of the tooth space; 1 where gear 1's tip round
            starts, gear 2's tip's middle); tooth_height: between tip and root radius, mm.
        patch_width, patch_length: mm. dofs, dofs_2d: free unknowns; iterations: of the
            solver; times: s per stage.
    """

    z: np.ndarray
    G: np.ndarray
    uniform: np.ndarray
    along_z: np.ndarray
    along: np.ndarray
    plane_stress: float
    plane_strain: float
    radius: float
    height: float
    tooth_height: float
    patch_width: float
    patch_length: float
    size: str
    dofs: int
    dofs_2d: int
    elements: int
    iterations: int
    times: dict = field(default_factory=dict)
    gear: int = 1

    @property
    def maxwell(self) -> float:
        """‖G − Gᵀ‖ / ‖G‖ (Frobenius): zero but for the solver's tolerance."""
        return float(np.linalg.norm(self.G - self.G.T) / np.linalg.norm(self.G))

    @property
    def mirror(self) -> float:
        """The largest |G_ij − G_(n−1−i)(n−1−j)| over the largest G: the face is symmetric
        about its middle, the tetrahedra are not."""
        return float(np.abs(self.G - self.G[::-1, ::-1]).max() / np.abs(self.G).max())

    @property
    def diagonal(self) -> np.ndarray:
        """G's diagonal (µm per N): each patch under its own load."""
        return np.diagonal(self.G)

    @property
    def at_centres(self) -> np.ndarray:
        """``along`` at the patch centres (n, n + 1; µm per N): the last column is the
        uniform load's response there."""
        per = (len(self.along_z) - 1) // (2 * len(self.z))
        return self.along[(2 * np.arange(len(self.z)) + 1) * per]

    @property
    def mid_row(self) -> np.ndarray:
        """G's row of the patch in the middle of the face (µm per N)."""
        return self.G[len(self.z) // 2]


@dataclass(frozen=True)
class Section:
    """The meshed section: corner points (n, 2) and triangles (m, 3), the load band's edges
    (k, 2) with their lengths and outward normals (k, 2), the held arc's radius (``bore``:
    gear 1's bore, or with ``outer`` gear 2's outer rim), the load point's radius and the
    tooth height (mm)."""

    points: np.ndarray
    triangles: np.ndarray
    band: np.ndarray
    lengths: np.ndarray
    normals: np.ndarray
    bore: float
    radius: float
    tooth_height: float
    outer: bool = False

    def held(self, radius: np.ndarray) -> np.ndarray:
        """Whether nodes at ``radius`` (mm) lie on the held arc: within the bore, or on the
        outer rim (:data:`RIM_TOLERANCE`)."""
        if self.outer:
            return radius >= self.bore * (1 - RIM_TOLERANCE)
        return radius <= self.bore * (1 + 1e-9)


def face_influence(params: PairParameters, thickness: float = 5.0, E: float = STEEL_E,
                   nu: float = STEEL_NU, patches: int = 9, height: float | None = None,
                   size: str = "standard", gear: int = 1) -> FaceInfluence:
    """The influence of loads along the face on ``gear``'s tooth of ``params`` (module
    docstring): face width ``thickness`` (mm), ``E`` (MPa), ``nu``, ``patches`` across the
    face, at ``height`` of the working flank (default 0.5), at mesh level ``size``."""
    height = 0.5 if height is None else height
    if size not in SIZES:
        raise ParameterError("size", size, " or ".join(SIZES))
    if not (0.0 < height < 1.0):
        raise ParameterError("height", height, "0 < height < 1 (of the working flank)")
    if not thickness > 0:
        raise ParameterError("thickness", thickness, "> 0 mm")
    if not (isinstance(patches, int) and patches >= 2):
        raise ParameterError("patches", patches, "a whole number >= 2")
    if gear not in (1, 2):
        raise ParameterError("gear", gear, "1 or 2")
    level, watch, times = SIZES[size], Stopwatch(), {}
    section = section_of(params, height, level, gear=gear)
    times["mesh"] = watch.s
    body = Extrusion(section, thickness, patches * level.layers)
    K = tet_stiffness(body, E, nu)
    F, band = body.band_loads(patches)
    F = np.column_stack([F, F.mean(axis=1)])          # the uniform load, unit force
    times["assemble"] = watch.s - sum(times.values())
    U, iterations = TwoLevel(body, K).solve(F)
    times["solve"] = watch.s - sum(times.values())
    G = 1e3 * F.T @ U                                  # mm → µm
    stress, strain, dofs_2d = plane_answers(section, E, nu, thickness)
    times["plane"] = watch.s - sum(times.values())
    return FaceInfluence(
        z=(np.arange(patches) + 0.5) * thickness / patches, G=G[:patches, :patches],
        uniform=G[:patches, patches], along_z=body.level_z, along=1e3 * band.T @ U,
        plane_stress=stress, plane_strain=strain, radius=section.radius, height=height,
        tooth_height=section.tooth_height, patch_width=thickness / patches,
        patch_length=float(section.lengths.sum()), size=size, dofs=K.shape[0],
        dofs_2d=dofs_2d, elements=body.mesh.t.shape[1], iterations=iterations, times=times,
        gear=gear)


@dataclass(frozen=True)
class Outline:
    """A gear's body about its loaded tooth 0, to be meshed: its boundary's ``segments`` (the
    load band's named "patch"), the element ``sizes`` (mm) by segment or zone name, the held
    arc's radius ``held`` (mm) and whether it is the ``outer`` one, and the load ``band``
    (:class:`~fegear.toothpair.ring.face.FlankBand`, the gear's frame) with its ``outward``
    normal (2,) at the band's centre."""

    segments: tuple
    sizes: dict
    held: float
    outer: bool
    band: FlankBand
    outward: np.ndarray


def section_of(params: PairParameters, height: float, level: Resolution,
               pitches: int = PITCHES, gear: int = 1) -> Section:
    """``gear``'s ``pitches`` (odd) pitches about its tooth 0, its loaded flank cut at the load
    band's ends, meshed (module docstring)."""
    outline = (gear1_body if gear == 1 else gear2_body)(params, height, level, pitches)
    geometry = BodyGeometry("tooth3d", outline.segments, size=level.body * params.m,
                            refinements=tuple(Refinement((name,), s, level.growth)
                                              for name, s in outline.sizes.items()))
    (meshed,) = mesh_bodies([geometry])
    mesh = meshed.mesh
    corners = np.unique(mesh.t)
    number = np.full(mesh.doflocs.shape[1], -1)
    number[corners] = np.arange(len(corners))
    points = mesh.doflocs[:, corners].T
    band = number[mesh.facets[:, mesh.boundaries["patch"]].T]
    edge = points[band[:, 1]] - points[band[:, 0]]
    lengths = np.hypot(edge[:, 0], edge[:, 1])
    normals = np.column_stack([edge[:, 1], -edge[:, 0]]) / lengths[:, None]
    normals *= np.sign(normals @ outline.outward)[:, None]
    flank = outline.band
    return Section(points, number[mesh.t].T, band, lengths, normals, outline.held,
                   flank.radius, flank.tooth_height, outline.outer)


def _layout(flank: FlankBand, loaded: tuple[float, float], near: tuple[float, float],
            level: Resolution, m: float) -> Layout:
    """The profile's cuts: the load band a window named "patch", the ``loaded`` flank and the
    ``near`` teeth (polar angles, rad) refined (the tip rounds, 0.1 mm at m 2, take the
    flank's size), the teeth beyond them the body's."""
    sizes = {"patch": PATCH * m / level.along, "loaded": level.loaded * m,
             "near": level.flank * m}
    return Layout(windows=(("patch", 0.5 * (flank.lo + flank.hi), 0.5 * (flank.hi - flank.lo)),),
                  marks=((*loaded, "loaded"), (*near, "near")), sizes=sizes)


def gear1_body(params: PairParameters, height: float, level: Resolution,
               pitches: int) -> Outline:
    """Gear 1's ``pitches`` pitches about tooth 0, down to the solve's bore (module
    docstring)."""
    case, shape, flank = load_band(params, height)
    pitch, space = shape.pitch, flank.space
    root = float(shape.radius(np.array([space]))[0])
    a, b = (shape.phi_space + k * pitch for k in (-(pitches // 2), pitches // 2 + 1))
    layout = _layout(flank, (flank.top, space), (space - 2 * pitch, space + pitch), level,
                     params.m)

    def project(x):
        return shape.point(np.arctan2(x[:, 1], x[:, 0]))

    segs, _ = profile_segments("g1", PolarCurve(shape.point, project), a, b, layout)
    bore = root - case.rims[0]
    t = np.linspace(b, a, 20 * pitches)
    arc = bore * np.column_stack([np.cos(t), np.sin(t)])
    ends = shape.point(np.array([a, b]))
    segments = (*segs, Segment("cut_b", np.array([ends[1], arc[0]])),
                Segment("bore", arc, lambda x: bore * x / np.linalg.norm(x, axis=1)[:, None]),
                Segment("cut_a", np.array([arc[-1], ends[0]])))
    outward = shape.frame(np.array([flank.centre]))[1][0]
    return Outline(segments, dict(layout.sizes), bore, False, flank, outward)


def gear2_body(params: PairParameters, height: float, level: Resolution,
               pitches: int) -> Outline:
    """Gear 2's ``pitches`` pitches about its tooth 0, out to the solve's rim (module
    docstring)."""
    case = SolveCase(params=params, tip_round=tip_round_of(params, None))
    curve, flank = gear2_band(params, height)
    pitch = 2 * np.pi / params.z2
    a, b = (pitch * (k + 0.5) for k in (-(pitches // 2) - 1, pitches // 2))
    layout = _layout(flank, (flank.space, flank.top), (-1.5 * pitch, 1.5 * pitch), level,
                     params.m)
    polar = gear2_polar(curve)
    segs, _ = profile_segments("g2", polar, a, b, layout)
    outer = params.r0 + 2 * params.e1 + case.rims[1]
    segments = gear2_outline(polar.point, segs, a, b, outer, 20 * pitches)
    xi = curve.xi_at_angle(np.array([flank.centre]), tabled=False)
    outward = curve.frame(xi)[2][0]                    # the gap side: out of the tooth
    return Outline(segments, dict(layout.sizes), outer, True, flank, outward)


def load_band(params: PairParameters, height: float) -> tuple[SolveCase, RoundedProfile,
                                                               FlankBand]:
    """The solve's case of ``params``, gear 1's rounded profile (its tip rounds) and the load
    band at ``height`` of its working flank, :data:`PATCH` m along the profile
    (:func:`~fegear.toothpair.ring.face.flank_band`: the slice model reads its 2D parts on the
    same band)."""
    case = SolveCase(params=params, tip_round=tip_round_of(params, None))
    shape = RoundedProfile(gear1_profile(params), case.edge_radius)
    return case, shape, flank_band(shape, height, PATCH * params.m)


def gear2_band(params: PairParameters, height: float) -> tuple[Cycloid, FlankBand]:
    """Gear 2's curve and the load band at ``height`` of its tooth 0's loaded flank by radius
    (0 the root, r0 + 2 e1; 1 the tip's middle, r0 − 2 e1), :data:`PATCH` m along the
    profile: polar angles (rad) in its frame; its ``top`` is the tip's middle (0), its
    ``space`` the tooth space's middle before it (−π/z2)."""
    curve = gear2_curve(params)
    start = -np.pi / params.z2                       # ξ and the polar angle agree there

    def radius(xi):
        return float(np.hypot(*curve.point(np.array([xi]))[0]))

    def arc(xi0, xi1):
        return quad(lambda x: float(np.hypot(*curve.derivatives(np.array([x]), 1)[1][0])),
                    xi0, xi1, epsabs=1e-13)[0]

    root, tip = radius(start), radius(0.0)
    r = root + height * (tip - root)
    centre = brentq(lambda x: radius(x) - r, start, 0.0, xtol=1e-15)
    half = 0.5 * PATCH * params.m
    ends = [brentq(lambda x, s=s: arc(centre, x) - s, *sorted((centre, centre + 8 * s / r)),
                   xtol=1e-15) for s in (-half, half)]     # |dP/dξ| > r / 8 on the flank
    lo, mid, hi = curve.polar_angle(np.array([ends[0], centre, ends[1]]))
    return curve, FlankBand(float(lo), float(hi), float(mid), r, 0.0, start, root - tip)


class Extrusion:
    """The section extruded by ``thickness`` in ``layers`` equal layers and cut into
    tetrahedra, with its quadratic nodes: every node sits on a section node (a corner or a
    triangle edge's middle) at a level (0 … 2 layers, halves of a layer)."""

    def __init__(self, section: Section, thickness: float, layers: int) -> None:
        n = len(section.points)
        self.section, self.layers = section, layers
        self.level_z = np.linspace(0.0, thickness, 2 * layers + 1)
        p = np.vstack([np.tile(section.points.T, (1, layers + 1)),
                       np.repeat(self.level_z[::2], n)[None, :]])
        a, b, c = np.sort(section.triangles, axis=1).T
        prisms = [(a + k * n, b + k * n, c + k * n, a + (k + 1) * n, b + (k + 1) * n,
                   c + (k + 1) * n) for k in range(layers)]
        # the diagonal of every side face runs from its lower-numbered bottom corner to the
        # higher-numbered top corner, in both prisms that share it
        t = np.hstack([np.vstack(q) for a0, b0, c0, a1, b1, c1 in prisms
                       for q in ((a0, b0, c0, c1), (a0, b0, b1, c1), (a0, a1, b1, c1))])
        x = p[:, t]
        volume = np.einsum("ij,ij->j", np.cross((x[:, 1] - x[:, 0]).T,
                                                (x[:, 2] - x[:, 0]).T).T, x[:, 3] - x[:, 0])
        t[1:3, volume < 0] = t[2:0:-1, volume < 0]
        self.mesh = MeshTet1(p, t)
        self.basis = Basis(self.mesh, ElementTetP2(), intorder=2)  # exact on straight tets
        edges = _edges(section.triangles)
        keys = edges[:, 0] * n + edges[:, 1]
        self.node_of, self.level_of = np.empty((2, self.basis.N), dtype=np.int64)
        vertex = np.arange(p.shape[1])
        self.node_of[self.basis.nodal_dofs[0]] = vertex % n
        self.level_of[self.basis.nodal_dofs[0]] = 2 * (vertex // n)
        u, v = self.mesh.edges
        lo, hi = np.sort(np.vstack([u % n, v % n]), axis=0)
        across = np.searchsorted(keys, lo * n + hi)
        flat = lo == hi
        self.node_of[self.basis.edge_dofs[0]] = np.where(flat, lo, n + np.minimum(
            across, len(keys) - 1))
        self.level_of[self.basis.edge_dofs[0]] = u // n + v // n
        self.dof_at = np.full((n + len(edges), 2 * layers + 1), -1)
        self.dof_at[self.node_of, self.level_of] = np.arange(self.basis.N)
        radius = np.hypot(*self.basis.doflocs[:2])
        held = section.held(radius)
        self.free = np.cumsum(~held) - 1
        self.free[held] = -1
        self.keys = keys

    def band_loads(self, patches: int) -> tuple[np.ndarray, np.ndarray]:
        """Each patch's load (3 free dofs a node, patches): unit force into the tooth spread
        evenly over the patch, the consistent nodal forces of quadratic triangles (a
        rectangle of the band cut either way: a sixth of its area at the middle of each side,
        a third at its centre); and the band's means at every level (dofs, levels): the
        mean displacement into the tooth over the band's length there (Simpson on each
        edge)."""
        s = self.section
        u, v = s.band.T
        mids = len(s.points) + np.searchsorted(self.keys, np.sort(s.band, axis=1) @ [len(
            s.points), 1])
        levels = 2 * self.layers + 1
        loads = np.zeros((3 * self.free.max() + 3, patches))
        per, h = self.layers // patches, self.level_z[2]
        for k in range(self.layers):
            at = 2 * k + 1
            weight = [(mids, at - 1, 1 / 6), (mids, at + 1, 1 / 6), (u, at, 1 / 6),
                      (v, at, 1 / 6), (mids, at, 1 / 3)]
            for nodes, level, w in weight:
                self._add(loads[:, k // per], nodes, level, w * h * s.lengths)
        loads /= h * per * s.lengths.sum()
        means = np.zeros((loads.shape[0], levels))
        for level in range(levels):
            for nodes, w in ((u, 1 / 6), (v, 1 / 6), (mids, 2 / 3)):
                self._add(means[:, level], nodes, level, w * s.lengths)
        return loads, means / s.lengths.sum()

    def _add(self, out: np.ndarray, nodes: np.ndarray, level: int, weight: np.ndarray):
        """Add ``weight`` (per band edge) times the inward normal at the section ``nodes``
        of ``level`` to the vector ``out`` (3 free dofs a node)."""
        dof = 3 * self.free[self.dof_at[nodes, level]]
        for c in range(2):
            np.add.at(out, dof + c, -weight * self.section.normals[:, c])


def _edges(triangles: np.ndarray) -> np.ndarray:
    """The section's triangle edges (k, 2), each once, low corner first, sorted."""
    pairs = np.sort(triangles[:, [0, 1, 1, 2, 0, 2]].reshape(-1, 2), axis=1)
    return np.unique(pairs, axis=0)


def tet_stiffness(body: Extrusion, E: float, nu: float) -> sp.bsr_matrix:
    """The stiffness (N/mm) of ``body``'s quadratic tetrahedra between its free nodes, in
    3 × 3 blocks (free node i's dofs 3i, 3i + 1, 3i + 2): the same matrix as scikit-fem's
    ``linear_elasticity`` assembles, summed by node pair once."""
    lam, mu = E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))
    basis, free = body.basis, body.free
    nodes = free[basis.element_dofs]                          # (10, elements)
    n = int(free.max()) + 1
    rows, cols = np.repeat(nodes, 10, axis=0), np.tile(nodes, (10, 1))
    kept = (rows >= 0) & (cols >= 0)
    keys, inverse = np.unique((rows * n + cols)[kept], return_inverse=True)
    position = np.cumsum(kept.ravel()).reshape(kept.shape) - 1   # among the kept pairs
    data = np.zeros((len(keys), 3, 3))
    chunk = 8000
    for start in range(0, nodes.shape[1], chunk):
        part = slice(start, start + chunk)
        g = np.stack([phi[0].grad[:, part] for phi in basis.basis]).transpose(2, 3, 0, 1)
        gw = g * basis.dx[part][:, :, None, None]             # (e, q, a, i)
        pair = np.einsum("eqai,eqbj->abeij", gw, g, optimize=True)
        dot = np.trace(pair, axis1=3, axis2=4)
        k = lam * pair + mu * pair.transpose(0, 1, 2, 4, 3) + mu * dot[..., None, None] * \
            np.eye(3)
        here = kept[:, part]
        index = inverse[position[:, part][here]]
        for i in range(3):
            for j in range(3):
                data[:, i, j] += np.bincount(index, k[..., i, j].reshape(100, -1)[here],
                                             minlength=len(keys))
    indptr = np.searchsorted(keys // n, np.arange(n + 1))
    return sp.bsr_matrix((data, keys % n, indptr), shape=(3 * n, 3 * n))


class TwoLevel:
    """Conjugate gradients on K u = f for a block of loads, each preconditioned by a
    symmetric two-level cycle: Chebyshev smoothing (``degree`` steps on the spectrum of
    M⁻¹K from ``lower`` of its top, M being K on each line of nodes along the face, factorised
    as one block-diagonal matrix), the correction from the linear tetrahedra of the same
    mesh (corners; the middle nodes follow their edges), the smoothing again."""

    def __init__(self, body: Extrusion, K: sp.bsr_matrix, degree: int = 3,
                 lower: float = 0.1) -> None:
        self.K, self.degree = K.tocsr(), degree    # CSR: 1.5× BSR's speed on 10 columns
        n = K.shape[0] // 3
        line = body.node_of[body.free >= 0]
        rows = np.repeat(np.arange(n), np.diff(K.indptr))
        same = line[rows] == line[K.indices]
        starts = np.concatenate([[0], np.cumsum(np.bincount(rows[same], minlength=n))])
        self.lines = Factor(sp.bsr_matrix((K.data[same], K.indices[same], starts),
                                          shape=K.shape))
        self.P = sp.kron(self._corners(body), sp.eye(3), format="csr")
        self.coarse = Factor(self.P.T @ self.K @ self.P)
        x = np.random.default_rng(0).random(K.shape[0])
        for _ in range(20):                 # the top of M⁻¹K's spectrum, power iteration
            x = self.lines.solve(self.K @ x)
            top = float(np.linalg.norm(x))
            x /= top
        self.bounds = (lower * 1.1 * top, 1.1 * top)

    @staticmethod
    def _corners(body: Extrusion) -> sp.csr_matrix:
        """Free nodes from free corners: 1 at a corner, ½ from each end of an edge."""
        free, basis = body.free, body.basis
        corner = free[basis.nodal_dofs[0]]
        number = np.where(corner >= 0, np.cumsum(corner >= 0) - 1, -1)
        ends = number[body.mesh.edges]
        rows = np.concatenate([corner, np.tile(free[basis.edge_dofs[0]], 2)])
        cols = np.concatenate([number, ends[0], ends[1]])
        w = np.concatenate([np.ones(len(corner)), np.full(2 * len(ends[0]), 0.5)])
        keep = (rows >= 0) & (cols >= 0)
        return sp.csr_matrix((w[keep], (rows[keep], cols[keep])),
                             shape=(int(free.max()) + 1, int(number.max()) + 1))

    def _smooth(self, f: np.ndarray, u: np.ndarray | None) -> np.ndarray:
        lo, hi = self.bounds
        theta, delta = 0.5 * (hi + lo), 0.5 * (hi - lo)
        r = f if u is None else f - self.K @ u
        u = np.zeros_like(f) if u is None else u
        step, rho = self.lines.solve(r) / theta, delta / theta
        for k in range(self.degree):
            u = u + step
            if k < self.degree - 1:
                r = r - self.K @ step
                rho, before = 1.0 / (2 * theta / delta - rho), rho
                step = rho * before * step + 2 * rho / delta * self.lines.solve(r)
        return u

    def cycle(self, f: np.ndarray) -> np.ndarray:
        """The preconditioner applied to the residuals ``f`` (dofs, k)."""
        u = self._smooth(f, None)
        u = u + self.P @ self.coarse.solve(self.P.T @ (f - self.K @ u))
        return self._smooth(f, u)

    def solve(self, F: np.ndarray) -> tuple[np.ndarray, int]:
        """K⁻¹F (dofs, k) to :data:`TOLERANCE` and the iterations it took."""
        U, R = np.zeros_like(F), F.copy()
        Z = self.cycle(R)
        D, rz, scale = Z.copy(), np.sum(R * Z, axis=0), np.linalg.norm(F, axis=0)
        for k in range(1, ITERATIONS + 1):
            Q = self.K @ D
            alpha = rz / np.sum(D * Q, axis=0)
            U += D * alpha
            R -= Q * alpha
            if np.max(np.linalg.norm(R, axis=0) / scale) < TOLERANCE:
                return U, k
            Z = self.cycle(R)
            rz, before = np.sum(R * Z, axis=0), rz
            D = Z + D * (rz / before)
        raise SolveError(f"conjugate gradients: residual above {TOLERANCE:g} after "
                         f"{ITERATIONS} iterations")


def plane_answers(section: Section, E: float, nu: float,
                  thickness: float) -> tuple[float, float, int]:
    """The section in 2D, plane stress and plane strain, its held arc held, under 1/b N/mm
    spread evenly over the load band: the band's mean displacement into the tooth (µm per N
    over the face) each, and the free dofs."""
    mesh = MeshTri1(section.points.T.copy(), section.triangles.T.copy())
    basis = Basis(mesh, ElementVector(ElementTriP2()))
    keys = _keys(np.sort(mesh.facets, axis=0).T, len(section.points))
    order = np.argsort(keys)
    facet = order[np.searchsorted(keys[order], _keys(np.sort(section.band, axis=1),
                                                     len(section.points)))]
    weights = np.zeros(basis.N)
    for dofs, w in ((basis.nodal_dofs[:, section.band[:, 0]], 1 / 6),
                    (basis.nodal_dofs[:, section.band[:, 1]], 1 / 6),
                    (basis.facet_dofs[:, facet], 2 / 3)):
        for c in range(2):
            np.add.at(weights, dofs[c], -w * section.lengths * section.normals[:, c])
    weights /= section.lengths.sum()
    held = np.flatnonzero(section.held(np.hypot(*basis.doflocs)))
    free = np.setdiff1d(np.arange(basis.N), held)
    mu = E / (2 * (1 + nu))
    out = []
    for lam in (E * nu / (1 - nu**2), E * nu / ((1 + nu) * (1 - 2 * nu))):
        K = asm(linear_elasticity(lam, mu), basis).tocsc()[free][:, free]
        u = Factor(K).solve(weights[free] / thickness)
        out.append(1e3 * float(weights[free] @ u))
    return out[0], out[1], len(free)


def _keys(pairs: np.ndarray, n: int) -> np.ndarray:
    return pairs[:, 0].astype(np.int64) * n + pairs[:, 1]


def table(result: FaceInfluence, reference: FaceInfluence | None = None) -> str:
    """``result`` as text (µm per kN): the patches along the face with G's diagonal, the
    mid-face patch's row and the uniform load; the ends, the plane answers and the checks;
    and, given the same case at another ``reference`` size, the differences (%)."""
    r, h, mid = result, result.tooth_height, len(result.z) // 2
    u = r.along[:, -1]
    lines = [f"gear {r.gear}'s tooth in 3D, {r.size}: {r.dofs} dofs, {r.elements} P2 tetrahedra, "
             f"{r.iterations} CG iterations, " + ", ".join(
                 f"{k} {v:.1f} s" for k, v in r.times.items()),
             f"load at r = {r.radius:.3f} mm ({r.height:g} of the working flank), patches "
             f"{r.patch_width:.3f} × {r.patch_length:.3f} mm, tooth height {h:.3f} mm",
             "  z mm   |Δz|/h   G_ii    G_mid,j  /G_mid,mid  uniform  /mid   at z"]
    centres = r.at_centres[:, -1]
    for j, z in enumerate(r.z):
        lines.append(f"{z:7.3f} {abs(z - r.z[mid]) / h:7.3f} {1e3 * r.G[j, j]:8.3f} "
                     f"{1e3 * r.mid_row[j]:8.3f} {r.mid_row[j] / r.mid_row[mid]:9.3f} "
                     f"{1e3 * r.uniform[j]:9.4f} {r.uniform[j] / r.uniform[mid]:6.3f} "
                     f"{1e3 * centres[j]:7.4f}")
    ends = (0.5 * (u[0] + u[-1]) / u[len(u) // 2],
            0.5 * (r.uniform[0] + r.uniform[-1]) / r.uniform[mid])
    lines += [f"uniform load at the ends of the face {ends[0]:.4f} × mid-face (end patches "
              f"{ends[1]:.4f} ×)",
              f"2D: plane stress {1e3 * r.plane_stress:.4f}, plane strain "
              f"{1e3 * r.plane_strain:.4f} µm/kN ({r.dofs_2d} dofs); 3D mid-face / plane "
              f"stress {r.uniform[mid] / r.plane_stress:.4f}, face mean / plane stress "
              f"{r.uniform.mean() / r.plane_stress:.4f}",
              f"Maxwell ‖G − Gᵀ‖/‖G‖ {r.maxwell:.1e}, mirror {r.mirror:.1e}, uniform − G's "
              f"row means {np.abs(r.uniform - r.G.mean(axis=1)).max() / r.uniform.max():.1e}"]
    if reference is not None:
        def pct(name):
            a, b = (np.asarray(getattr(x, name)) for x in (r, reference))
            return f"{name} {100 * np.max(np.abs(a / b - 1)):.2f} %"
        lines.append(f"against {reference.size} (largest): " + ", ".join(
            pct(name) for name in ("diagonal", "mid_row", "uniform", "plane_stress")))
    return "\n".join(lines)


def main(argv: list[str]) -> str:
    """``python -m fegear.verify.tooth3d [size ...] [name=value ...]``: the tables of the
    sizes named (default standard), each after the first against it; the names are
    PairParameters' fields and thickness, height, patches, gear."""
    given = dict(a.split("=", 1) for a in argv if "=" in a)
    knobs = {k: (int if k in ("patches", "gear") else float)(given.pop(k))
             for k in ("thickness", "height", "patches", "gear") if k in given}
    params = PairParameters(**{k: int(v) if k in ("z1", "z2") else float(v)
                               for k, v in given.items()})
    results = []
    for size in [a for a in argv if "=" not in a] or ["standard"]:
        sys.stderr.write(f"solving {size} ...\n")
        results.append(face_influence(params, size=size, **knobs))
    return "\n\n".join(table(r, results[0] if k else None) for k, r in enumerate(results))


if __name__ == "__main__":
    sys.stdout.write(main(sys.argv[1:]) + "\n")

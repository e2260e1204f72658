"""The sector peer's two gears extruded across the face into quadratic wedges (CalculiX
C3D15), for the 3D pair check (:mod:`fegear.verify.calculix_face`).

* **The section.** The sector scene's geometries (:mod:`fegear.verify.sector.scene`: the same
  teeth, windows, cuts, bore and rim) are meshed again at :class:`FaceSizes` (windows 0.2 mm,
  tip rounds 0.05 mm, far roots 1 mm, growing 1 mm/mm): the coarse sector mesh has 2-8 µm
  elements on gear 1's tip rounds, which across 0.8 mm layers would be wedges 100× longer than
  wide, and 55k nodes, which extruded would be 1.5M (SPOOLES, the solver of Debian's ccx,
  factorises 0.25M in about 20 s on two cores).
* **The extrusion.** ``layers`` equal layers across the face width b, z from −b/2 to b/2
  (ζ = z/b). Each P2 triangle (CalculiX order: corners 1-3 counter-clockwise, midsides 4-6 on
  1-2, 2-3, 3-1) gives a C3D15: its nodes on the layer's lower plane (1-3, 7-9), upper plane
  (4-6, 10-12) and the three vertical midsides (13-15) on the layer's middle plane, which holds
  corner nodes only. A 2D boundary facet on edge f of its triangle is face f + 2 of the wedge
  (1-2-5-4, 2-3-6-5, 3-1-4-6), as CalculiX itself expands a CPS6.
* **Misalignment.** A body's nodes at face position ζ are written displaced by ζ·``shear``
  (mm, fixed frame): every section of gear 1 is translated rigidly, as the slice model
  displaces gear 1 section by section (:meth:`fegear.toothpair.face.Face.offsets`). This is a
  shear of the body by |shear|/b (0.002 at 10 µm over 5 mm), not a turn about a tilted axis;
  the two differ by an axial displacement (x·|shear|/b, tens of µm) which frictionless
  contact between flanks parallel to the axis does not feel.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from ..fe import BodyGeometry, Refinement, Segment, facet_nodes
from .calculix import element_nodes
from .ccx_files import PeerError

MIN_QUALITY = 0.1    # gmsh's sliver check (the product's 0.15): where a coarse window meets
                     # a finer root the transition leaves a few thinner triangles
SPACING = 0.25       # joined segments' points at least this many of their element sizes apart


def coarsened(geometry: BodyGeometry, sizes: FaceSizes, near: tuple[float, float]
              ) -> BodyGeometry:
    """``geometry`` with each refined segment's element size (the finest refinement over it)
    made no finer than ``sizes`` say (:class:`FaceSizes`); ``near`` (the geometry's own
    frame) is the middle of the loaded teeth. Consecutive segments of one name and size are
    joined: the scene cuts the tip rounds at their tangent points into pieces a few µm long,
    which would force µm edges among the round's elements. One refinement per size."""
    growth = sizes.growth
    zones: dict[float, str] = {}

    def size(seg) -> float:
        found = [r.size for r in geometry.refinements
                 if seg.name in r.segments or seg.zone in r.segments]
        if not found:
            return math.inf
        h = min(found)
        if "_root" in seg.name:
            far = np.linalg.norm(np.asarray(seg.points) - near, axis=1).min() > sizes.reach
            return max(h, sizes.far_root if far else sizes.root)
        return max(h, sizes.window if h >= 0.5 * sizes.window else sizes.edge)

    def zoned(segments):
        joined = []   # [name, size, points, project]
        for seg in segments:
            h = size(seg)
            if joined and joined[-1][:2] == [seg.name, h]:
                joined[-1][2].append(np.asarray(seg.points)[1:])
            else:
                joined.append([seg.name, h, [np.asarray(seg.points)], seg.project])
        out = []
        for name, h, parts, project in joined:
            refined = math.isfinite(h)
            points = np.concatenate(parts)
            points = _thinned(points, SPACING * h) if refined else points
            zone = zones.setdefault(h, f"face_size_{len(zones)}") if refined else None
            out.append(Segment(name, points, project, zone))
        return tuple(out)

    outer = zoned(geometry.outer)
    holes = tuple(zoned(hole) for hole in geometry.holes)
    return dataclasses.replace(
        geometry, outer=outer, holes=holes, min_quality=MIN_QUALITY,
        refinements=tuple(Refinement((zone,), h, growth) for h, zone in zones.items()))


@dataclass(frozen=True)
class FaceSizes:
    """The sections' smallest element sizes (mm): the contact ``window``s (a window the
    scene refines below half that keeps its size down to ``edge``, as do gear 1's tip rounds
    and gear 2 under them: a 0.25 mm round spans 0.09 mm of arc, and a coarser quadratic edge
    across it would stand µm off the profile where the teeth touch), the root zones within
    ``reach`` of the loaded teeth (``root``) and beyond (``far_root``); sizes grow away from
    them by ``growth`` mm/mm (the 2D meshes' 0.25 gave 21k section nodes, 1.0 gives 10k)."""

    window: float = 0.2
    edge: float = 0.05
    root: float = 0.4
    far_root: float = 1.0
    reach: float = 12.0
    growth: float = 1.0


def _thinned(points: np.ndarray, spacing: float) -> np.ndarray:
    """The polyline's points at least ``spacing`` (mm) apart, both ends kept: a spline
    through the joined pieces' µm-spaced points wiggles, and the snapped nodes invert."""
    keep, last = [0], points[0]
    for k in range(1, len(points) - 1):
        if np.linalg.norm(points[k] - last) >= spacing:
            keep.append(k)
            last = points[k]
    if len(keep) > 1 and np.linalg.norm(points[-1] - points[keep[-1]]) < spacing:
        keep.pop()
    return points[keep + [len(points) - 1]]


@dataclass(frozen=True)
class Extruded:
    """The P2 triangle ``mesh`` (the section) extruded into ``layers`` C3D15 layers across
    ``width`` (mm). ``nodes`` (n, 3) fixed-frame coordinates (mm): every section node on each
    of the layers + 1 planes, then the section's ``corners`` on each layer's middle plane;
    ``elements`` (e, 15) node indices (0-based, CalculiX order), layer by layer;
    ``conn2d`` the section's (t, 6) element nodes."""

    mesh: object
    nodes: np.ndarray
    elements: np.ndarray
    conn2d: np.ndarray
    layers: int
    width: float
    corners: np.ndarray

    @property
    def section_nodes(self) -> int:
        return self.mesh.doflocs.shape[1]

    @property
    def zeta(self) -> np.ndarray:
        """Each node's face position z / width, from −½ to ½."""
        return self.nodes[:, 2] / self.width

    def plane_node(self, plane: int, node: np.ndarray) -> np.ndarray:
        """Index of section ``node`` on layer plane ``plane`` (0 … layers)."""
        return plane * self.section_nodes + np.asarray(node)

    def through(self, node: np.ndarray) -> np.ndarray:
        """Every extruded node of section ``node``s: on every plane, and on the middle planes
        where they are corners."""
        node = np.asarray(node)
        out = [self.plane_node(k, node) for k in range(self.layers + 1)]
        mid = np.searchsorted(self.corners, node)
        is_corner = (mid < len(self.corners)) & (self.corners[np.minimum(
            mid, len(self.corners) - 1)] == node)
        base = (self.layers + 1) * self.section_nodes
        out += [base + k * len(self.corners) + mid[is_corner] for k in range(self.layers)]
        return np.concatenate(out)

    def boundary_nodes(self, name: str) -> np.ndarray:
        """Every extruded node on the section's boundary ``name``."""
        return self.through(np.unique(facet_nodes(self.mesh, self.boundary(name)).ravel()))

    def boundary(self, name: str) -> np.ndarray:
        if name not in self.mesh.boundaries:
            raise PeerError(f"the section has no boundary {name!r}")
        return np.asarray(self.mesh.boundaries[name])

    def faces(self, name: str, layer: int) -> tuple[np.ndarray, np.ndarray]:
        """Elements (0-based) and CalculiX wedge faces (3-5) of boundary ``name`` in ``layer``."""
        mesh = self.mesh
        f = self.boundary(name)
        elem = mesh.f2t[0, f]
        if np.any(mesh.f2t[1, f] >= 0):
            raise PeerError(f"boundary {name!r} is not on the outside")
        local = np.argmax(mesh.t2f[:, elem] == f, axis=0)
        return layer * self.conn2d.shape[0] + elem, local + 3


def extrude(name: str, mesh, to_fixed, layers: int, width: float,
            shear: tuple[float, float] = (0.0, 0.0)) -> Extruded:
    """Extrude the P2 ``mesh`` (body frame; ``to_fixed`` places (n, 2) points in the fixed
    frame) into ``layers`` C3D15 layers from z = −width/2 to width/2, each node displaced by
    ζ·``shear`` (mm; module docstring)."""
    if not (isinstance(layers, int) and layers >= 1 and width > 0):
        raise PeerError(f"layers ({layers!r}) must be an integer >= 1 and width ({width!r}) > 0")
    conn = element_nodes(_Section(name, mesh))
    corners = np.unique(conn[:, :3])
    xy = to_fixed(mesh.doflocs.T)
    n = xy.shape[0]
    z_full = np.linspace(-0.5 * width, 0.5 * width, layers + 1)
    z_mid = 0.5 * (z_full[1:] + z_full[:-1])
    parts = [np.column_stack([xy, np.full(n, z)]) for z in z_full]
    parts += [np.column_stack([xy[corners], np.full(len(corners), z)]) for z in z_mid]
    nodes = np.concatenate(parts)
    nodes[:, :2] += np.outer(nodes[:, 2] / width, shear)
    mid_of = np.full(n, -1)
    mid_of[corners] = np.arange(len(corners))
    base = (layers + 1) * n
    elements = [np.column_stack([k * n + conn[:, :3], (k + 1) * n + conn[:, :3],
                                 k * n + conn[:, 3:], (k + 1) * n + conn[:, 3:],
                                 base + k * len(corners) + mid_of[conn[:, :3]]])
                for k in range(layers)]
    return Extruded(mesh, nodes, np.concatenate(elements), conn, layers, float(width),
                    corners)


@dataclass(frozen=True)
class _Section:
    """What :func:`~fegear.verify.calculix.element_nodes` reads of a body: its name and mesh."""

    name: str
    mesh: object

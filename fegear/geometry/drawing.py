"""Drawings to manufacture from: each gear's whole outline about its own axis, as a polyline
within a stated chord error, and written as DXF (``fegear profile --out``: gear1.dxf,
gear2.dxf; docs/geometry.md, "Drawings for manufacture").

Every vertex of an outline is a point of the exact profile (gear 1's relieved envelope with
its tip edges rounded as a solve rounds them, gear 2's compound cycloid) and every chord
strays from it by at most the chord error; a tip round is a circular arc, and the DXF carries
its vertices' bulges, so that it is exact there. The outline breaks into smooth runs (the
pieces of gear 1's envelope, its rounds, where a relief starts, each half-tooth): a CAD
kernel makes each run one spline (:func:`~fegear.fe.mesh.write_step`).

A pair's deviations (:class:`~.deviations.Deviations`) are drawn as the solve takes them: a
tooth's pitch deviation turns it about the gear's axis (blended into its neighbours' turns
across :data:`BLEND` of a pitch about each space centre, where the space bottom, nearly a
circle about the axis, slides along itself); a profile slope or form deviation moves its
loaded flank along the normal by the departure at each point's roll fraction, up to the
tooth's peak, where the drawing steps back to the other flank (the model's step); a runout
moves the teeth off the axis, the bore or rim circle staying on it. The centre distance's
deviation is the assembly's and no part's: it is not drawn.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..files import write_atomic
from ..planar import rotate
from .deviations import NO_DEVIATIONS, Deviations
from .gear1 import gear1_profile
from .gear2 import adaptive_parameters, gear2_curve
from .parameters import PairParameters
from .relief import RelievedBranch
from .tip_edge import RoundedProfile

#: half-width (fraction of a pitch) of the blend between two teeth's pitch turns about each
#: space centre: gear 1's flanks start about 0.1 pitch from it (the seed paper's pair)
BLEND = 0.05
#: DXF layer of each gear's teeth and of its circle (gear 1's bore, gear 2's outer rim)
LAYERS = {1: ("GEAR1_TEETH", "GEAR1_BORE"), 2: ("GEAR2_TEETH", "GEAR2_RIM")}


@dataclass(frozen=True)
class Outline:
    """One gear's whole outline as drawn for manufacture, about its own axis at the origin,
    oriented as at β = 0 (mm).

    Attributes:
        gear: 1 (external, material inside the outline) or 2 (internal, material outside).
        points: (n, 2) vertices, counter-clockwise, the first not repeated at the end; each a
            point of the exact (or deviated) profile.
        bulges: (n,) DXF bulge of the segment from each vertex to the next: 0 a chord,
            tan(θ/4) an arc turning by θ (a tip round).
        starts: indices of the vertices where a smooth run of the outline starts, rising.
        circle: radius of the circle about the axis that closes the part (gear 1's bore, gear
            2's outer rim), mm.
        chord_error: the largest distance of a chord from the profile, mm.
        tip_round: gear 1's tip-edge round radius (mm; 0: sharp edges, and gear 2).
    """

    gear: int
    points: np.ndarray
    bulges: np.ndarray
    starts: tuple[int, ...]
    circle: float
    chord_error: float
    tip_round: float = 0.0

    def runs(self) -> list[np.ndarray]:
        """Each smooth run's vertices (k, 2), the last the next run's first."""
        ends = [*self.starts[1:], len(self.points) + self.starts[0]]
        closed = np.vstack([self.points, self.points])
        return [closed[a:b + 1] for a, b in zip(self.starts, ends)]


def gear1_outline(params: PairParameters, chord_error: float, tip_round: float,
                  bore: float, deviations: Deviations = NO_DEVIATIONS) -> Outline:
    """Gear 1's outline: its exact (relieved) profile, the tip edges rounded to ``tip_round``
    (mm; 0 leaves them sharp), all z1 teeth, chords within ``chord_error`` (mm), closed by its
    bore of radius ``bore`` (mm), with ``deviations``' gear-1 teeth and runout (module
    docstring)."""
    profile = gear1_profile(params)
    shape = RoundedProfile(profile, tip_round)
    phi, pts, bulges, breaks = _gear1_period(profile, shape, chord_error)
    normal = shape.frame(phi)[1]
    roots = float(profile.radius(np.array([profile.phi_space]))[0])
    tips = float(profile.radius(np.array([profile.tooth_center]))[0])
    centre = int(np.argmin(np.abs(phi - profile.tooth_center)))
    loaded = np.arange(centre, len(phi))   # gear 1's loaded flank faces counter-clockwise
    teeth = []
    for k in range(params.z1):
        d = deviations.teeth(1).get(k)
        tooth = (phi, pts, bulges, breaks)
        if d is not None and d.profiled:
            radius = np.hypot(pts[loaded, 0], pts[loaded, 1])
            um = d.normal_um((radius - roots) / (tips - roots))
            tooth = _stepped(tooth, centre, loaded, 1e-3 * um[:, None] * normal[loaded])
        teeth.append(_turned_copy(tooth, k * profile.pitch))
    return _assembled(1, teeth, params, deviations, profile.tooth_center, profile.pitch,
                      params.r1, bore, chord_error, tip_round)


def gear2_outline(params: PairParameters, chord_error: float, rim: float,
                  deviations: Deviations = NO_DEVIATIONS) -> Outline:
    """Gear 2's outline: the compound cycloid, all z2 teeth, chords within ``chord_error``
    (mm), closed by its outer rim of radius ``rim`` (mm), with ``deviations``' gear-2 teeth
    and runout (module docstring)."""
    curve = gear2_curve(params)
    pitch = 2 * np.pi / params.z2
    halves = [adaptive_parameters(lambda s: curve.derivatives(s, 2), a, b, chord_error)[:-1]
              for a, b in ((-0.5 * pitch, 0.0), (0.0, 0.5 * pitch))]
    xi = np.concatenate(halves)
    pts, _, normal, _ = curve.frame(xi)
    phi = curve.polar_angle(xi)
    bulges = np.zeros(len(xi))
    centre = len(halves[0])
    breaks = np.array([0, centre])
    loaded = np.arange(0, centre + 1)    # gear 2's loaded flank faces clockwise
    roots, tips = params.r0 + 2 * params.e1, params.r0 - 2 * params.e1
    teeth = []
    for k in range(params.z2):
        d = deviations.teeth(2).get(k)
        tooth = (phi, pts, bulges, breaks)
        if d is not None and d.profiled:
            radius = np.hypot(pts[loaded, 0], pts[loaded, 1])
            um = d.normal_um((roots - radius) / (roots - tips))
            tooth = _stepped(tooth, centre, loaded, 1e-3 * um[:, None] * normal[loaded],
                             moved_first=True)
        teeth.append(_turned_copy(tooth, k * pitch))
    return _assembled(2, teeth, params, deviations, 0.0, pitch, params.r0, rim, chord_error,
                      0.0)


def _gear1_period(profile, shape: RoundedProfile, chord_error: float):
    """One pitch of gear 1's outline, from the middle of a tooth space (polar angles φ rising
    from ``phi_space``): (φ, points, bulges, run starts). The exact profile's polyline with a
    vertex at the middle of the tooth, where a relief starts and at each piece's end, and each
    tip round's stretch replaced by arc points (a chord within ``chord_error`` each)."""
    pts = profile.period_polyline(chord_error)     # φ rising from phi_space
    phi = np.unwrap(np.arctan2(pts[:, 1], pts[:, 0]))
    phi += 2 * np.pi * np.round((profile.phi_space - phi[0]) / (2 * np.pi))
    marks = [profile.phi_space, profile.tooth_center, *(pc.phi0 for pc in profile.pieces[1:])]
    branch = profile.branches[0]
    if isinstance(branch, RelievedBranch):   # a relief's start: the curvature jumps there
        for zone in branch.zones:
            q = branch.evaluate(np.array([zone.start])).q[0]
            marks.append(profile.phi_space + (math.atan2(q[1], q[0]) - profile.phi_space)
                         % profile.pitch)
    for f in shape.fillets:
        marks = [m for m in marks if not f.phi_a < m < f.phi_b] + [f.phi_a, f.phi_b]
        keep = ~((phi > f.phi_a) & (phi < f.phi_b))
        phi, pts = phi[keep], pts[keep]
    marks = np.unique(marks)
    new = marks[np.min(np.abs(marks[:, None] - phi[None]), axis=1) > 1e-13]
    phi = np.concatenate([phi, new])
    pts = np.concatenate([pts, profile.evaluate(new).q])
    bulges = np.zeros(len(phi))
    for f in shape.fillets:
        arc_pts, arc_bulge = _arc(f, pts[np.argmin(np.abs(phi - f.phi_a))],
                                  pts[np.argmin(np.abs(phi - f.phi_b))], chord_error)
        arc_phi = profile.phi_space + np.mod(np.arctan2(arc_pts[:, 1], arc_pts[:, 0])
                                             - profile.phi_space, 2 * np.pi)
        phi, pts = np.concatenate([phi, arc_phi]), np.concatenate([pts, arc_pts])
        bulges = np.concatenate([bulges, np.full(len(arc_phi), arc_bulge)])
        bulges[np.argmin(np.abs(phi - f.phi_a))] = arc_bulge
    order = np.argsort(phi, kind="stable")
    phi, pts, bulges = phi[order], pts[order], bulges[order]
    return phi, pts, bulges, np.argmin(np.abs(phi[None] - marks[:, None]), axis=1)


def _arc(fillet, start: np.ndarray, end: np.ndarray, chord_error: float):
    """The inner vertices of a tip round from ``start`` to ``end`` (counter-clockwise about
    its centre), each chord within ``chord_error`` of the arc, and the bulge of each of the
    equal arcs between them."""
    c = np.asarray(fillet.centre)
    a0 = math.atan2(*(start - c)[::-1])
    sweep = (math.atan2(*(end - c)[::-1]) - a0) % (2 * np.pi)
    step = 2 * math.acos(max(1.0 - chord_error / fillet.radius, -1.0))
    n = max(1, math.ceil(sweep / step))
    a = a0 + sweep * np.arange(1, n) / n
    pts = c + fillet.radius * np.column_stack([np.cos(a), np.sin(a)])
    return pts, math.tan(sweep / n / 4)


def _stepped(tooth, centre: int, loaded: np.ndarray, move: np.ndarray,
             moved_first: bool = False):
    """A tooth's (φ, points, bulges, starts) with its loaded vertices ``loaded`` (the peak's,
    index ``centre``, among them) moved by ``move`` (n, 2), and an unmoved copy of the peak
    kept with the other flank, a straight step between the two: after the moved peak where
    the loaded flank comes first (gear 2's), else before it. Moved arcs are arcs no more:
    their bulges go."""
    phi, pts, bulges, starts = tooth
    stay = pts[centre]
    pts, bulges = pts.copy(), bulges.copy()
    pts[loaded] += move
    bulges[loaded] = 0.0
    at = centre + 1 if moved_first else centre
    starts = np.concatenate([np.where(starts > centre, starts + 1, starts), [centre + 1]])
    return (np.insert(phi, at, phi[centre]), np.insert(pts, at, stay, axis=0),
            np.insert(bulges, at, 0.0), np.unique(np.append(starts, centre)))


def _turned_copy(tooth, angle: float):
    """A period's (φ, points, bulges, starts) turned by ``angle`` (rad) about the axis."""
    phi, pts, bulges, starts = tooth
    return phi + angle, rotate(pts, angle), bulges, starts


def _assembled(gear: int, teeth: list, params, deviations: Deviations, centre0: float,
               pitch: float, radius: float, circle: float, chord_error: float,
               tip_round: float) -> Outline:
    """The teeth's periods joined into one outline, each vertex turned by its tooth's pitch
    deviation (blended across the spaces: :func:`pitch_turns`) and the teeth moved off the
    axis by the gear's runout (tooth 0 centred at polar angle ``centre0``)."""
    offsets = np.cumsum([0] + [len(t[0]) for t in teeth])
    phi = np.concatenate([t[0] for t in teeth])
    pts = np.concatenate([t[1] for t in teeth])
    bulges = np.concatenate([t[2] for t in teeth])
    starts = tuple(int(s) for t, o in zip(teeth, offsets) for s in t[3] + o)
    z = params.z1 if gear == 1 else params.z2
    table = deviations.turns(gear, np.arange(z), radius)
    if np.any(table):
        pts = rotate(pts, pitch_turns(phi, centre0, pitch, table))
    runout = deviations.runout1 if gear == 1 else deviations.runout2
    if runout.fr:
        pts = pts + runout.offset(centre0)
    return Outline(gear, pts, bulges, tuple(sorted(set(starts))), float(circle),
                   float(chord_error), float(tip_round))


def pitch_turns(phi: np.ndarray, centre0: float, pitch: float, table: np.ndarray
                ) -> np.ndarray:
    """The turn (rad) of the material at polar angles ``phi`` of a gear whose tooth k is
    centred at ``centre0 + k pitch`` and turned by ``table[k]``: each tooth's own turn,
    passing smoothly (its slope 0 at both ends) to the next one's over :data:`BLEND` of a
    pitch either side of the space centre between them."""
    u = (np.asarray(phi, dtype=float) - centre0) / pitch
    j = np.floor(u).astype(int)
    t = np.clip((u - j - 0.5) / BLEND, -1.0, 1.0)
    w = 0.5 + 0.5 * np.sin(0.5 * np.pi * t)
    a, b = table[np.mod(j, len(table))], table[np.mod(j + 1, len(table))]
    return a + w * (b - a)


def write_dxf(path: Path, outline: Outline, title: str) -> Path:
    """Write ``outline`` as a DXF drawing (R2010, mm): its teeth as one closed LWPOLYLINE on
    the layer ``GEARn_TEETH`` (the tip rounds as arcs, by their bulges) and its bore or rim as
    a CIRCLE on its own layer (:data:`LAYERS`); the chord error and ``title`` in the layers'
    descriptions and the header's custom properties. Written atomically."""
    import ezdxf
    from ezdxf import units

    teeth, ring = LAYERS[outline.gear]
    what = "bore" if outline.gear == 1 else "outer rim"
    tol = f"chord error <= {outline.chord_error * 1e3:g} um"
    doc = ezdxf.new("R2010", setup=False, units=units.MM)
    doc.header["$MEASUREMENT"] = 1
    doc.header["$LUPREC"] = 8
    doc.layers.add(teeth, color=1 if outline.gear == 1 else 4).description = (
        f"gear {outline.gear}, all teeth, about its own axis: exact profile points, {tol}"
        + (f", tip rounds r {outline.tip_round:g} mm as arcs" if outline.tip_round else ""))
    doc.layers.add(ring, color=8).description = f"gear {outline.gear}'s {what}"
    for key, value in (("fegear", title), ("gear", str(outline.gear)), ("units", "mm"),
                       ("chord_error_mm", f"{outline.chord_error:g}"),
                       ("frame", "the gear's own axis at the origin, as at beta = 0"),
                       ("tip_round_mm", f"{outline.tip_round:g}"),
                       (f"{what.replace(' ', '_')}_radius_mm", repr(outline.circle))):
        doc.header.custom_vars.append(key, value)
    msp = doc.modelspace()
    teeth_line = msp.add_lwpolyline([], close=True, dxfattribs={"layer": teeth})
    # all vertices at once as (x, y, start width, end width, bulge): add_lwpolyline appends
    # them one at a time, each copying the array (0.9 s for gear 1's 12 000)
    xyseb = np.zeros((len(outline.points), 5))
    xyseb[:, :2], xyseb[:, 4] = outline.points, outline.bulges
    teeth_line.lwpoints.set(xyseb)
    msp.add_circle((0.0, 0.0), outline.circle, dxfattribs={"layer": ring})
    return write_atomic(Path(path), lambda tmp: doc.saveas(tmp))

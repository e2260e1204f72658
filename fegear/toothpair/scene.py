"""The tooth-pair FE scene: which teeth to mesh and pair, and the two sector bodies.

Frames (README "Conventions"): gear 2 centred at the origin, gear 1 at O1 = (0, e); at rolling
angle β gear 2 is turned by β and gear 1 by α = (z2/z1) β. Each body is meshed in its own frame
and placed at β (:class:`fegear.fe.assembly.Placement`), so one factorisation serves every
position.

* Gear 1 is an annular sector: its exact profile over the chosen teeth, radial cuts through the
  middle of the ``extra``-th unpaired tooth beyond them at each end, and a bore of radius
  ρ1,min − ``rim1`` tied to the rotation unknown that carries the torque (a mechanism: rigid
  rotation about O1).
* Gear 2 is a ring sector: its exact profile over the same angular range, radial cuts through
  a gear-2 tooth tip just beyond gear 1's cuts, and the outer rim at ρ2,max + ``rim2``, fixed.
* Cut faces are traction free. The refined parts are a contact window on every paired flank
  (both gears), long enough to cover the tooth's contact points at every rolling angle of the
  scene, the root zone (the lower ``ROOT_BAND`` of the tooth height) of every tooth space,
  gear 1's tip rounds that a window reaches (and ``ROUND_SPILL`` round Hertz widths of flank
  beyond them), and gear 2's flank under each such round wherever the round comes within
  ``ROUND_GAP`` of it at some β, one Hertz width wider (an edge contact loads both sides over
  the same few µm, so both get the round's element size; gear 1, the contact slave, reaches
  further so that gear 2 never receives its forces as point loads from long slave facets).
  On gear 1 the two tangent points of each such round, where the curvature jumps and the
  edge pressure peaks, are refined again (``JUNCTION_SPAN``, ``JUNCTION_DENSITY``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..contact import CurvePoints
from ..errors import FegearError, ParameterError
from ..fe import BodyGeometry, Refinement, Segment, line_contact
from ..geometry import Cycloid, Gear1Profile, PairParameters, RoundedProfile, gear2_curve
from ..planar import rotate, wrap
from .inputs import QUALITY

ROOT_BAND = 0.3          # root zone: the lower 30 % of the tooth height
WINDOW_B = 2.5           # gear-1 window half-length, in Hertz half-widths at the shared load
WINDOW_MIN = 0.1         # … and at least this many modules
MASTER_FACTOR = 1.4      # gear-2 window half-length relative to gear 1's
SHARE_GUESS = 3.0        # teeth assumed to share the load when sizing the contact elements
ROUND_GAP = 0.05         # gear 2 is refined under a round that comes this close (modules)
ROUND_DENSITY = 2        # the edge zone is a third of the round's Hertz width: twice as fine
ROUND_SPILL = 2.0        # gear 1's round size reaches this many round Hertz widths onto the
                         # flank, gear 2's strip one: the slave is never coarser than the master
JUNCTION_SPAN = 0.25     # round-to-flank tangent points: refined over ± this many round
JUNCTION_DENSITY = 4     # Hertz widths, this many times finer than the round
SPLINE_CHORD = 1e-3      # mm, polyline handed to gmsh (nodes are snapped to the exact curve)
SNAP_CHORD = 0.1         # … and at most this fraction of the segment's element size, so that
                         # snapping moves a boundary node by a small part of its element
STEEP = 4.0              # … sampled evenly in arc length where it runs this many times faster
                         # than r dθ (the baseline flanks reach 2.9)
SIZE_FLOOR = 1e-4        # smallest element, in modules (0.2 µm at m = 2): at light load the
                         # sizes that follow the Hertz widths would shrink to nanometres


@dataclass(frozen=True)
class Gear2Master:
    """Gear 2's exact curve at rolling angle β, as an exact master curve (fixed frame)."""

    curve: Cycloid
    beta: float

    def closest(self, points: np.ndarray) -> CurvePoints:
        foot, normal, dist = self.curve.closest(rotate(np.asarray(points, float), -self.beta))
        return CurvePoints(rotate(foot, self.beta), rotate(normal, self.beta), dist)


@dataclass(frozen=True)
class Candidate:
    """A gear-1 tooth paired for contact: unloaded clearance (µm of arc at r0), the predicted
    contact point (fixed frame at β once the clearance is closed, mm), its polar angle on gear 1
    (body frame, rad) and on gear 2 (body frame, rad), and the analytic curvature radii there
    (mm, + convex)."""

    tooth: int
    clearance_um: float
    point: tuple[float, float]
    phi1: float
    theta2: float
    radius1: float
    radius2: float


@dataclass(frozen=True)
class Scene:
    """Both sector geometries for a set of rolling angles: the paired teeth (contact windows
    covering their contact points at every β of the set) and the exact gear-2 curve."""

    params: PairParameters
    betas: tuple[float, ...]
    gear1: BodyGeometry
    gear2: BodyGeometry
    paired: tuple[int, ...]       # gear-1 teeth with contact windows
    teeth1: tuple[int, ...]       # gear-1 teeth in the sector (paired teeth and extras)
    profile1: tuple[str, ...]     # boundary names along each gear's tooth profile
    profile2: tuple[str, ...]
    root_band1: tuple[float, float]  # radii (mm) of the root zone: the lower ROOT_BAND of the
    root_band2: tuple[float, float]  # tooth height, whatever segment the nodes belong to
    b_full: float                 # Hertz half-width for the whole load on one tooth, mm
    shape: RoundedProfile = field(repr=False)
    curve2: Cycloid = field(repr=False)

    def master(self, beta: float) -> Gear2Master:
        """Gear 2's exact curve placed at rolling angle β."""
        return Gear2Master(self.curve2, beta)


def candidate_data(params: PairParameters, shape: RoundedProfile, state, teeth,
                   beta: float) -> tuple[Candidate, ...]:
    """Contact point, polar angles and curvature radii of each paired tooth's + flank at β
    (teeth whose + flank has no contact point at β are left out)."""
    g2 = gear2_curve(params)
    alpha = params.ratio * beta
    out = []
    for c in state.teeth:
        if c.tooth not in teeth or c.plus_point is None:
            continue
        x = np.array([c.plus_point])
        o1 = np.array([0.0, params.e])
        body1 = rotate(x - o1, -alpha)
        phi1 = float(math.atan2(body1[0, 1], body1[0, 0]))
        r1 = float(1.0 / shape.curvature(np.array([phi1]))[0])
        # the gear-2 point is where that gear-1 point lands once the clearance is closed: on a
        # nearly conformal flank the relative curvature is a small difference of two large
        # ones, and gear 2's changes fast (the 6 µm of a baseline clearance doubled 1/R*)
        x = rotate(x - o1, c.plus_um * 1e-3 / params.r0) + o1
        foot = g2.closest(rotate(x, -beta))[0]
        theta2 = float(math.atan2(foot[0, 1], foot[0, 0]))
        xi = g2.xi_at_angle(np.array([theta2]))
        r2 = float(g2.curvature_radius(xi)[0])
        out.append(Candidate(c.tooth, float(c.plus_um), (float(x[0, 0]), float(x[0, 1])), phi1,
                             theta2, r1, r2))
    return tuple(out)


def hertz_half_width(params: PairParameters, torque_nmm: float, c: Candidate, thickness: float,
                     E: float, nu: float) -> float:
    """Hertz b (mm) at a candidate if it carried ``torque_nmm`` alone (normal load T / r0)."""
    load = torque_nmm / params.r0
    try:
        return line_contact(c.radius1, c.radius2, load, thickness, E, nu).b
    except ParameterError:  # not a Hertz pair (1/R* <= 0): size as a cylinder on a plane
        r = max(abs(c.radius1), abs(c.radius2))
        return line_contact(r, math.inf, load, thickness, E, nu).b


def build_scene(params: PairParameters, profile: Gear1Profile, positions, teeth: tuple[int, ...],
                torque_nmm: float, thickness: float, E: float, nu: float, quality: str,
                rim1: float, rim2: float, extra: int = 1, tip_round: float = 0.0,
                shape: RoundedProfile | None = None) -> Scene:
    """Sector geometries for the paired ``teeth`` (gear-1 indices) over ``positions``, a
    sequence of (β, clearance state at β): each tooth's contact windows cover its predicted
    contact points at every β, and the gear-2 sector covers gear 1's at every β.

    Gear 1's tip edges are rounded to ``tip_round`` mm (:mod:`fegear.geometry.tip_edge`);
    pass ``shape`` to reuse one :class:`RoundedProfile`."""
    n_b, root_m, global_m = QUALITY[quality]
    m = params.m
    shape = shape if shape is not None else RoundedProfile(profile, tip_round)
    betas = tuple(b for b, _ in positions)
    at = [(b, candidate_data(params, shape, st, teeth, b)) for b, st in positions]
    cands = [(b, c) for b, cs in at for c in cs]
    if not cands:
        raise ParameterError("teeth", teeth, "teeth with a contact point on the + flank")
    # element size from the tooth that touches first at each position (it carries the most
    # load), not from every paired tooth: pairing more teeth leaves the mesh of the others
    first = [min(cs, key=lambda c: c.clearance_um) for _, cs in at if cs]
    b_full = max(hertz_half_width(params, torque_nmm, c, thickness, E, nu) for c in first)
    b_shared = b_full / math.sqrt(SHARE_GUESS)  # b ∝ sqrt(load)
    floor = SIZE_FLOOR * m
    h_contact = max(b_shared / n_b, floor)

    # gear-1 sector: the shortest run of consecutive teeth (indices modulo z1) that holds
    # every paired tooth, widened by ``extra`` teeth on each side
    pitch1 = shape.pitch
    start, span = tooth_run(teeth, params.z1)
    lo, hi = -extra, span + extra
    if hi - lo + 2 > params.z1:
        raise FegearError(f"the paired teeth {list(teeth)} and {extra} more on each side span "
                          f"{hi - lo + 1} of gear 1's {params.z1} teeth: a full-ring model is "
                          "not built (lower the torque or raise the tip relief)")
    centre0 = shape.tooth_center + start * pitch1
    phi_a, phi_b = centre0 + lo * pitch1, centre0 + hi * pitch1
    teeth1 = tuple(int((start + k) % params.z1) for k in range(lo, hi + 1))
    mid1 = 0.5 * (phi_a + phi_b)
    paired = tuple(sorted({c.tooth for _, c in cands}))

    rho = shape.radius(np.linspace(0, pitch1, 400) + shape.phi_space)
    rho_min, rho_max = float(rho.min()), float(rho.max())
    bore = rho_min - rim1
    # window half-length per candidate: WINDOW_B Hertz half-widths of its own curvatures at
    # the shared load, at least WINDOW_MIN modules (a contact that only just closes)
    half = [(b, c, max(WINDOW_B * hertz_half_width(params, torque_nmm, c, thickness, E, nu)
                       / math.sqrt(SHARE_GUESS), WINDOW_MIN * m)) for b, c in cands]
    windows1 = _path_windows(
        paired, [(c.tooth, _unwrap_near(c.phi1, mid1),
                  w / math.hypot(*shape.point(np.array([c.phi1]))[0])) for _, c, w in half])
    roots1 = [(k, shape.phi_space + (start + k) * pitch1) for k in range(lo + 1, hi + 1)]
    root_half1 = _root_half_angle(shape.radius, roots1[0][1], pitch1, rho_min, rho_max)
    turn0 = math.floor((phi_a - shape.phi_space) / pitch1)
    # refine the rounds that a contact window reaches (the others never touch)
    fillets = shape.fillet_angles(range(turn0 - 1, turn0 + hi - lo + 2))
    rounds = [(c - h, c + h) for c, h, _ in fillets
              if any(abs(c - p) < h + w for _, p, w in windows1)]
    # the tangent points of every round within a module of a window cut the polyline: a
    # spline through a curvature jump overshoots by µm, which snapping onto the exact curve
    # cannot undo in µm elements (further away the elements are coarse; cut there too, a tip
    # land 0.1 mm long became two boundary edges of a sliver under 2 mm elements)
    reach = m / rho_max
    tangents = [(x, x, None) for c, h, _ in fillets for x in (c - h, c + h)
                if any(abs(x - p) < w + reach for _, p, w in windows1)]
    # the rounds meet the gear-2 flank like a cylinder of radius ρ on a plane: elements sized
    # to that Hertz half-width at the shared load
    b_round = min([b_shared] + [line_contact(f.radius, math.inf, torque_nmm / params.r0
                                             / SHARE_GUESS, thickness, E, nu).b
                                for f in shape.fillets])
    h_round = max(min(h_contact, b_round / (ROUND_DENSITY * n_b)), floor)
    h_junction = max(h_round / JUNCTION_DENSITY, floor)
    spill = ROUND_SPILL * b_round / rho_max
    # where a round meets the flank the curvature jumps (4 → 0.3 /mm on the baseline): the
    # pressure peaks there over a few µm, so those tangent points get a finer zone of their own
    span = JUNCTION_SPAN * b_round / rho_max
    junctions = [(x - span, x + span, "g1_junction") for a, b in rounds for x in (a, b)]

    def g1_project(x):
        return shape.point(np.arctan2(x[:, 1], x[:, 0]))

    segs1, names1 = _profile_segments(
        "g1", shape.point, g1_project, phi_a, phi_b,
        [(f"g1_contact_{t}", p, w) for t, p, w in windows1],
        [(f"g1_root_{k}", p, root_half1) for k, p in roots1],
        marks=junctions + [(a - spill, b + spill, "g1_round") for a, b in rounds] + tangents,
        sizes={"g1_round": h_round, "g1_junction": h_junction,
               **{f"g1_contact_{t}": h_contact for t in paired}})
    a0, b0 = shape.point(np.array([phi_a]))[0], shape.point(np.array([phi_b]))[0]
    bore_pts = bore * np.column_stack([np.cos(np.linspace(phi_b, phi_a, 60)),
                                       np.sin(np.linspace(phi_b, phi_a, 60))])

    def bore_project(x):
        return bore * x / np.linalg.norm(x, axis=1)[:, None]

    refine1 = [Refinement(tuple(f"g1_contact_{t}" for t in paired), h_contact),
               Refinement(tuple(n for n in names1 if n.startswith("g1_root")), root_m * m)]
    if any(s.zone == "g1_round" for s in segs1):
        refine1.append(Refinement(("g1_round",), h_round))
    if any(s.zone == "g1_junction" for s in segs1):
        refine1.append(Refinement(("g1_junction",), h_junction))
    geo1 = BodyGeometry("gear1", (
        *segs1,
        Segment("g1_cut_b", np.array([b0, bore_pts[0]])),
        Segment("g1_bore", bore_pts, bore_project),
        Segment("g1_cut_a", np.array([bore_pts[-1], a0])),
    ), size=global_m * m, refinements=tuple(refine1))

    # gear-2 sector, in gear 2's frame: the fixed-frame range of gear 1's sector at every β,
    # cut at gear-2 tooth tips
    g2 = gear2_curve(params)
    pitch2 = 2 * math.pi / params.z2

    def body2_angle(phi, beta):  # polar angle in gear 2's frame of a gear-1 body point at β
        x = rotate(shape.point(np.array([phi])), params.ratio * beta)[0] + np.array([0.0,
                                                                                      params.e])
        return math.atan2(x[1], x[0]) - beta

    t_a = min(_unwrap_near(body2_angle(phi_a, b), 0.0) for b in betas)
    t_b = max(_unwrap_near(body2_angle(phi_b, b), t_a + (phi_b - phi_a)) for b in betas)
    k_a, k_b = math.floor(t_a / pitch2), math.ceil(t_b / pitch2)
    th_a, th_b = k_a * pitch2, k_b * pitch2  # tooth tips (ξ = 2πk/z2 is a tip)
    R_max, R_min = params.r0 + 2 * params.e1, params.r0 - 2 * params.e1
    outer = R_max + rim2
    windows2 = _path_windows(
        paired, [(c.tooth, _unwrap_near(c.theta2, 0.5 * (th_a + th_b)),
                  MASTER_FACTOR * w / params.r0) for _, c, w in half])
    roots2 = [(k, (k + 0.5) * pitch2) for k in range(k_a, k_b)]
    root_half2 = _root_half_angle(lambda t: g2.radius_at_angle(t), roots2[0][1], pitch2,
                                  R_min, R_max, inverted=True)

    def g2_curve(theta):
        r = g2.radius_at_angle(theta)
        return np.column_stack([r * np.cos(theta), r * np.sin(theta)])

    def g2_project(x):
        return g2_curve(np.arctan2(x[:, 1], x[:, 0]))

    # where a refined round comes near gear 2 at some β, gear 2 under it gets the same size
    marks2 = _round_strips(params, shape, g2, rounds, betas, b_round / params.r0,
                           0.5 * (th_a + th_b))
    segs2, names2 = _profile_segments(
        "g2", g2_curve, g2_project, th_a, th_b,
        [("g2_contact", p, w) for _, p, w in windows2],
        [(f"g2_root_{k}", p, root_half2) for k, p in roots2], marks=marks2,
        sizes={"g2_contact": h_contact, "g2_round": h_round})
    rim_pts = outer * np.column_stack([np.cos(np.linspace(th_a, th_b, 80)),
                                       np.sin(np.linspace(th_a, th_b, 80))])

    def rim_project(x):
        return outer * x / np.linalg.norm(x, axis=1)[:, None]

    pa2, pb2 = g2_curve(np.array([th_a]))[0], g2_curve(np.array([th_b]))[0]
    reversed_segs = tuple(Segment(s.name, s.points[::-1], s.project, s.zone)
                          for s in reversed(segs2))
    geo2 = BodyGeometry("gear2", (
        Segment("g2_rim", rim_pts, rim_project),
        Segment("g2_cut_b", np.array([rim_pts[-1], pb2])),
        *reversed_segs,
        Segment("g2_cut_a", np.array([pa2, rim_pts[0]])),
    ), size=global_m * m, refinements=(
        Refinement(("g2_contact",), h_contact),
        Refinement(tuple(n for n in names2 if n.startswith("g2_root")), root_m * m),
        *([Refinement(("g2_round",), h_round)] if marks2 else [])))
    band1 = (rho_min, rho_min + ROOT_BAND * (rho_max - rho_min))
    band2 = (R_max - ROOT_BAND * (R_max - R_min), R_max)
    return Scene(params, betas, geo1, geo2, paired, teeth1, names1, names2, band1, band2, b_full,
                 shape, g2)


def tooth_run(teeth, z: int) -> tuple[int, int]:
    """The shortest run of consecutive tooth indices (modulo ``z``) that holds all of
    ``teeth``: its first tooth and its length minus one. The run leaves out the largest gap
    between paired teeth, wherever the indices wrap."""
    t = sorted({int(k) % z for k in teeth})
    gap, i = max(((t[(i + 1) % len(t)] - t[i]) % z or z, i) for i in range(len(t)))
    return t[(i + 1) % len(t)], z - gap


def _round_strips(params, shape, g2, rounds, betas, margin, ref):
    """Gear-2 polar-angle ranges (lo, hi, "g2_round") that gear 1's refined ``rounds`` (body
    angle ranges) face within ROUND_GAP modules at some β, widened by ``margin`` (rad);
    overlapping ranges are merged (no slivers between their ends)."""
    spans = []
    for lo, hi in rounds:
        pts1 = shape.point(np.linspace(lo, hi, 9))
        for beta in betas:
            x = rotate(rotate(pts1, params.ratio * beta) + np.array([0.0, params.e]), -beta)
            if g2.closest(x)[2].min() > ROUND_GAP * params.m:
                continue
            th = [_unwrap_near(math.atan2(y, z), ref) for z, y in x]
            spans.append((min(th) - margin, max(th) + margin))
    merged: list[list[float]] = []
    for lo, hi in sorted(spans):
        if merged and lo <= merged[-1][1]:
            merged[-1][1] = max(merged[-1][1], hi)
        else:
            merged.append([lo, hi])
    return [(lo, hi, "g2_round") for lo, hi in merged]


def _path_windows(teeth, points) -> list[tuple[int, float, float]]:
    """One window (tooth, centre angle, half-angle) per tooth covering all of its
    (tooth, angle, half-angle) contact windows: the contact path over the positions."""
    out = []
    for t in teeth:
        spans = [(p - h, p + h) for tooth, p, h in points if tooth == t]
        lo, hi = min(s[0] for s in spans), max(s[1] for s in spans)
        out.append((t, 0.5 * (lo + hi), 0.5 * (hi - lo)))
    return out


def _unwrap_near(angle: float, ref: float) -> float:
    return ref + float(wrap(angle - ref))


def _root_half_angle(radius, centre: float, pitch: float, r_min: float, r_max: float,
                     inverted: bool = False) -> float:
    """Half-angle about a tooth-space centre covering the lower ROOT_BAND of the tooth height."""
    t = np.linspace(0.0, 0.5 * pitch, 400)
    r = radius(centre + t)
    height = (r - r_min) / (r_max - r_min)
    if inverted:  # gear 2: the root is the outermost radius
        height = 1.0 - height
    inside = t[height <= ROOT_BAND]
    return float(inside.max()) if len(inside) else 0.05 * pitch


def _profile_segments(prefix, curve, project, a, b, windows, roots, marks=(), sizes=None):
    """Split the profile over polar angles [a, b] into named segments.

    ``windows``/``roots``: (name, centre angle, half-angle). Where two windows (in centre
    order) overlap they are cut halfway between their centres, so every window keeps its centre
    and one connected piece, also when nested in a longer one; windows take
    precedence over roots, and earlier roots over later ones (a root may become two pieces
    under one name); the rest is
    ``{prefix}_flank``. ``marks``: (lo, hi, zone) angle ranges whose pieces get that refinement
    zone (whatever their name); every mark end cuts a segment (zone None: only the cut).
    ``sizes``: element size (mm) per name or zone, which sets the
    sampling (:func:`_sampled`). Returns segments in increasing angle and the distinct names.
    """
    wins = sorted((c, max(a, c - h), min(b, c + h), name) for name, c, h in windows)
    cuts = [None] + [0.5 * (pc + c) if lo < phi_ else None
                     for (pc, _, phi_, _), (c, lo, _, _) in zip(wins, wins[1:])] + [None]
    pieces = []
    for i, (_, lo, hi, name) in enumerate(wins):
        lo = lo if cuts[i] is None else max(lo, cuts[i])
        hi = hi if cuts[i + 1] is None else min(hi, cuts[i + 1])
        if hi - lo > 1e-9:
            pieces.append((lo, hi, name))
    for name, c, h in roots:  # each root keeps only what no window or earlier root took
        parts = [(max(a, c - h), min(b, c + h))]
        for wlo, whi, _ in list(pieces):
            parts = [(lo, hi) for p_lo, p_hi in parts
                     for lo, hi in ((p_lo, min(p_hi, wlo)), (max(p_lo, whi), p_hi))
                     if hi - lo > 1e-9]
        pieces += [(lo, hi, name) for lo, hi in parts]
    pieces.sort()
    filled, pos = [], a
    for lo, hi, name in pieces:
        if lo - pos > 1e-9:
            filled.append((pos, lo, f"{prefix}_flank"))
        filled.append((lo, hi, name))
        pos = hi
    if b - pos > 1e-9:
        filled.append((pos, b, f"{prefix}_flank"))
    segments, names = [], []
    for lo, hi, name in filled:
        cuts = sorted({lo, hi} | {x for m_lo, m_hi, _ in marks for x in (m_lo, m_hi)
                                  if lo + 1e-9 < x < hi - 1e-9})
        for p0, p1 in zip(cuts, cuts[1:]):
            mid = 0.5 * (p0 + p1)
            zone = next((z for m_lo, m_hi, z in marks if m_lo <= mid <= m_hi), None)
            size = (sizes or {}).get(zone, (sizes or {}).get(name, math.inf))
            segments.append(_sampled(name, curve, project, p0, p1, zone, size))
        if name not in names:
            names.append(name)
    return tuple(segments), tuple(names)


def _sampled(name, curve, project, lo, hi, zone=None, size=math.inf) -> Segment:
    """The curve over polar angles [lo, hi] as a polyline whose chord error at 0.5 mm radius
    of curvature is SPLINE_CHORD, or SNAP_CHORD of the element ``size`` (mm) if smaller;
    points even in polar angle, or in arc length where the curve runs nearly radially."""
    r = np.hypot(*curve(np.array([0.5 * (lo + hi)]))[0])
    spacing = math.sqrt(8 * 0.5 * min(SPLINE_CHORD, SNAP_CHORD * size))
    n = min(max(8, int((hi - lo) * r / spacing) + 2), 2000)
    theta = np.linspace(lo, hi, n)
    points = curve(theta)
    gaps = np.hypot(*np.diff(points, axis=0).T)
    if gaps.max() > STEEP * r * (hi - lo) / (n - 1):
        # a nearly radial stretch (gear 2 near its looping limit): points even in polar angle
        # fall far apart there, and the spline between them overshoots by tens of µm
        dense = np.linspace(lo, hi, 16 * n)
        s = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(curve(dense), axis=0).T))])
        n = min(max(8, int(s[-1] / spacing) + 2), 4000)
        points = curve(np.interp(np.linspace(0.0, s[-1], n), s, dense))
    return Segment(name, points, project, zone)

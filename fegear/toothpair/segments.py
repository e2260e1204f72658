"""The tooth profiles cut into named boundary segments for meshing: contact windows along each
paired tooth's contact path, root zones, refinement zones (tip rounds, their tangent points,
gear 2 under the rounds) and the plain flank between them, each a polyline of exact points.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field

import numpy as np

from ..fe import Segment, halved
from ..geometry import Cycloid, PairParameters, RoundedProfile
from ..planar import rotate, wrap

ROOT_BAND = 0.3          # root zone: the lower 30 % of the tooth height
ROUND_GAP = 0.05         # gear 2 is refined under a round that comes this close (modules)
SPLINE_CHORD = 1e-3      # mm, polyline handed to gmsh (nodes are snapped to the exact curve)
SNAP_CHORD = 0.1         # … and at most this fraction of the segment's element size, so that
                         # snapping moves a boundary node by a small part of its element
STEEP = 4.0              # … sampled evenly in arc length where it runs this many times faster
                         # than r dθ (the baseline flanks reach 2.9)
MAX_POINTS = 4000        # … and chords that stray further than the chord error are halved, up
                         # to this many points a segment
SHORT = 0.5              # a piece of boundary shorter than this part of its element size joins
                         # a neighbour (a 0.6 µm piece under 57 µm elements made a sliver)


@dataclass(frozen=True)
class PolarCurve:
    """A profile by polar angle: ``point`` gives its points (n, 2; mm) at polar angles (rad),
    ``project`` carries points (n, 2) onto it, as the mesher snaps boundary nodes (None: they
    are not snapped)."""

    point: Callable[[np.ndarray], np.ndarray]
    project: Callable[[np.ndarray], np.ndarray] | None = None


@dataclass(frozen=True)
class Layout:
    """How :func:`profile_segments` cuts a profile: ``windows`` and ``roots`` (name, centre
    angle, half-angle; rad), ``marks`` (lo, hi, zone: polar-angle ranges, rad, whose pieces get
    that refinement zone; zone None: only a cut at lo) and ``sizes``, the element size (mm) per
    name or zone."""

    windows: tuple = ()
    roots: tuple = ()
    marks: tuple = ()
    sizes: Mapping[str, float] = field(default_factory=dict)


@dataclass(frozen=True)
class PairProfiles:
    """A pair's two profiles: its parameters, gear 1's rounded profile and gear 2's curve."""

    params: PairParameters
    shape: RoundedProfile
    curve2: Cycloid


def round_strips(pair: PairProfiles, rounds, betas, margin: float, ref: float):
    """Gear-2 polar-angle ranges (lo, hi, "g2_round") that gear 1's refined ``rounds`` (body
    angle ranges, rad) face within ROUND_GAP modules at some β of ``betas``, widened by
    ``margin`` (rad) and unwrapped near ``ref`` (rad); overlapping ranges are merged (no
    slivers between their ends)."""
    params = pair.params
    spans = []
    for lo, hi in rounds:
        pts1 = pair.shape.point(np.linspace(lo, hi, 9))
        for beta in betas:
            x = rotate(rotate(pts1, params.ratio * beta) + np.array([0.0, params.e]), -beta)
            if pair.curve2.closest(x)[2].min() > ROUND_GAP * params.m:
                continue
            th = [unwrap_near(math.atan2(y, z), ref) for z, y in x]
            spans.append((min(th) - margin, max(th) + margin))
    merged: list[list[float]] = []
    for lo, hi in sorted(spans):
        if merged and lo <= merged[-1][1]:
            merged[-1][1] = max(merged[-1][1], hi)
        else:
            merged.append([lo, hi])
    return [(lo, hi, "g2_round") for lo, hi in merged]


def path_windows(teeth, points) -> list[tuple[int, float, float]]:
    """One window (tooth, centre angle, half-angle) per tooth covering all of its
    (tooth, angle, half-angle) contact windows: the contact path over the positions."""
    out = []
    for t in teeth:
        spans = [(p - h, p + h) for tooth, p, h in points if tooth == t]
        lo, hi = min(s[0] for s in spans), max(s[1] for s in spans)
        out.append((t, 0.5 * (lo + hi), 0.5 * (hi - lo)))
    return out


def unwrap_near(angle: float, ref: float) -> float:
    return ref + float(wrap(angle - ref))


def root_half_angle(radius, centre: float, pitch: float, r_min: float, r_max: float,
                     inverted: bool = False) -> float:
    """Half-angle about a tooth-space centre covering the lower ROOT_BAND of the tooth height."""
    t = np.linspace(0.0, 0.5 * pitch, 400)
    r = radius(centre + t)
    height = (r - r_min) / (r_max - r_min)
    if inverted:  # gear 2: the root is the outermost radius
        height = 1.0 - height
    inside = t[height <= ROOT_BAND]
    return float(inside.max()) if len(inside) else 0.05 * pitch


def profile_segments(prefix: str, profile: PolarCurve, a: float, b: float,
                     layout: Layout) -> tuple[tuple[Segment, ...], tuple[str, ...]]:
    """Split the ``profile`` over polar angles [a, b] into named segments, as ``layout`` says.

    Where two windows (in centre order) overlap they are cut halfway between their centres, so
    every window keeps its centre and one connected piece, also when nested in a longer one;
    windows take precedence over roots, and earlier roots over later ones (a root may become
    two pieces under one name); the rest is ``{prefix}_flank`` (:func:`_named_pieces`). The
    marks' pieces get their refinement zone (whatever their name); every mark end cuts a
    segment. The sizes set the sampling (:func:`sampled`) and the shortest piece: a piece
    shorter than SHORT of its size (the finest size where it has none) joins a neighbour, and a
    zone end that close to another cut is left out. Returns segments in increasing angle and
    the distinct names.
    """
    marks, sizes = layout.marks, layout.sizes
    filled = _named_pieces(prefix, a, b, layout.windows, layout.roots)

    def zone_at(x):
        return next((z for m_lo, m_hi, z in marks if m_lo <= x <= m_hi), None)

    finest = min(sizes.values(), default=math.inf)
    ends = sorted({x for lo, hi, _ in filled for x in (lo, hi)}
                  | {x for m_lo, m_hi, _ in marks for x in (m_lo, m_hi)})
    at = dict(zip(ends, profile.point(np.array(ends))))  # every cut there can be, at once

    def too_short(lo, hi, name):  # shorter than SHORT of its element size (else the finest)
        size = sizes.get(zone_at(0.5 * (lo + hi)), sizes.get(name, finest))
        if hi - lo <= 1e-9:
            return True
        return math.isfinite(size) and float(np.hypot(*(at[hi] - at[lo]))) < SHORT * size

    jumps = sorted({m_lo for m_lo, _, z in marks if z is None})
    filled = _joined(filled, jumps, too_short, {name for name, _, _ in layout.windows})
    segments, names = [], []
    for lo, hi, name in filled:
        cuts = _cuts(lo, hi, name, marks, too_short)
        for p0, p1 in zip(cuts, cuts[1:]):
            zone = zone_at(0.5 * (p0 + p1))
            size = sizes.get(zone, sizes.get(name, math.inf))
            segments.append(sampled(name, profile, p0, p1, zone, size))
        if name not in names:
            names.append(name)
    return tuple(segments), tuple(names)


def _named_pieces(prefix: str, a: float, b: float, windows, roots) -> list[tuple]:
    """[a, b] as named pieces (lo, hi, name) in increasing angle: the ``windows`` (cut halfway
    between the centres of two that overlap), the ``roots`` where no window or earlier root
    is, ``{prefix}_flank`` between them (see :func:`profile_segments`)."""
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
    return filled


def _joined(pieces, jumps, too_short, keep):
    """The named ``pieces`` (lo, hi, name), in order, without pieces too short to mesh: a
    boundary between two pieces that falls just short of a curvature jump (``jumps``, which
    cut the boundary anyway) moves onto it, then a piece still too short joins the piece
    before it (the first, the one after), unless its name is in ``keep`` (the windows)."""
    out = [list(p) for p in pieces]
    for left, right in zip(out, out[1:]):
        x = left[1]
        near = min(jumps, key=lambda j: abs(j - x), default=None)
        if near is not None and left[0] < near < right[1] and (
                too_short(min(x, near), max(x, near), left[2])
                or too_short(min(x, near), max(x, near), right[2])):
            left[1] = right[0] = near
    i = 0
    while len(out) > 1 and i < len(out):
        lo, hi, name = out[i]
        if name in keep or not too_short(lo, hi, name):
            i += 1
            continue
        if i > 0:
            out[i - 1][1] = hi
        else:
            out[1][0] = lo
        del out[i]
    return [tuple(p) for p in out]


def _cuts(lo, hi, name, marks, too_short) -> list[float]:
    """Where the piece [lo, hi] named ``name`` is cut: its ends, every curvature jump (a mark
    with zone None) and every zone mark's end inside it, except a zone end that would leave a
    piece ``too_short(x0, x1, name)``: a refinement zone may end half an element early or
    late."""
    inside = sorted({(x, z is None) for m_lo, m_hi, z in marks for x in (m_lo, m_hi)
                     if lo + 1e-9 < x < hi - 1e-9})
    kept = [(lo, True)]
    for x, hard in [*inside, (hi, True)]:
        if too_short(kept[-1][0], x, name):
            if not hard:
                continue
            if not kept[-1][1]:
                kept.pop()
        kept.append((x, hard))
    return [x for x, _ in kept]


def sampled(name: str, profile: PolarCurve, lo: float, hi: float, zone: str | None = None,
            size: float = math.inf) -> Segment:
    """The ``profile`` over polar angles [lo, hi] as a polyline whose chord error is
    SPLINE_CHORD, or SNAP_CHORD of the element ``size`` (mm) if smaller: spaced for a 0.5 mm
    radius of curvature, even in polar angle, or in arc length where the curve runs nearly
    radially, then halved where the curve turns tighter."""
    curve = profile.point
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
        theta = np.interp(np.linspace(0.0, s[-1], n), s, dense)
        points = curve(theta)
    points = halved(curve, theta, points, min(SPLINE_CHORD, SNAP_CHORD * size),
                    MAX_POINTS)
    return Segment(name, points, profile.project, zone)


def gear2_polar(curve: Cycloid) -> PolarCurve:
    """Gear 2's profile by polar angle (its frame), projecting points onto it at the foot of
    their normal (along their polar angle a node on a nearly radial flank moved far along it
    and inverted its element: h1 0.83 at the seed paper's pair)."""

    def point(theta):   # a mesh's input: no table (Cycloid.xi_at_angle)
        r = curve.radius_at_angle(theta, tabled=False)
        return np.column_stack([r * np.cos(theta), r * np.sin(theta)])

    def project(x):
        return curve.closest(x, tabled=False)[0]

    return PolarCurve(point, project)


def gear2_outline(point, segs, a: float, b: float, outer: float,
                  rim_points: int) -> tuple[Segment, ...]:
    """Gear 2's sector from polar angle ``a`` to ``b`` as a closed outline: the rim arc of
    radius ``outer`` (``rim_points`` points), the cut at ``b``, the profile ``segs`` (given
    from a to b) reversed, the cut at ``a``. ``point``: the profile by polar angle."""
    t = np.linspace(a, b, rim_points)
    rim = outer * np.column_stack([np.cos(t), np.sin(t)])

    def rim_project(x):
        return outer * x / np.linalg.norm(x, axis=1)[:, None]

    pa, pb = point(np.array([a]))[0], point(np.array([b]))[0]
    return (Segment("g2_rim", rim, rim_project),
            Segment("g2_cut_b", np.array([rim[-1], pb])),
            *(Segment(s.name, s.points[::-1], s.project, s.zone) for s in reversed(segs)),
            Segment("g2_cut_a", np.array([pa, rim[0]])))

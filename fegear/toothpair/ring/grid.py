"""Contact grids: where on each gear-1 tooth the pressure is sought, and how finely.

The pressure on a tooth is piecewise linear on a grid along gear 1's exact (tip-rounded) profile,
independent of any mesh. The grid covers the stretch of the tooth that a positive rotation
closes and whose rigid gap is within reach of the expected elastic approach (``window``); its
spacing follows the local Hertz half-width of the relative curvature of the two profiles at the
expected tooth load, a ``per_b``-th of it, and is finer again around the points where a tip
round meets the flank (the curvature jumps there and the edge pressure peaks within µm of it),
graded back to the flank's spacing. The points are counted from a fixed point of the tooth at
the position (its smallest gap at the first touch), with the rounds' tangent points among them,
so the window's extent moves only its ends: the same position solved alone or within a cycle,
whose windows are placed for different expected rotations, has the same grid where pressure
acts (and the same stresses within 1e-4).

Every tooth of gear 1 is tooth 0 turned by whole pitches, so tooth 0 is sampled once per
geometry (:class:`ToothSamples`) and the windows and spacings of any tooth come from turned
copies; only the grid points themselves are evaluated exactly.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...geometry import Cycloid, RoundedProfile
from ...planar import rotate

SAMPLES = 4001        # samples of one tooth pitch to find windows and spacings on
COARSE = 10           # the windows are found on every COARSE-th sample first
MIN_POINTS = 24       # a fine grid's spacing is at most its stretch over this many
PROBE_POINTS = 24     # a probe grid has this many intervals, evenly
JUNCTION = 0.5        # refined zone around a round's tangent points, in round Hertz widths
JUNCTION_FACTOR = 4.0  # … this many times finer than the round, …
GRADING = 0.5          # … growing beyond by at most this fraction of the distance from it


@dataclass(frozen=True)
class ToothGrid:
    """The pressure grid on one gear-1 tooth: arc length ``s`` (mm, increasing with the polar
    angle), polar angles ``phi`` (gear 1's frame), points, unit normals out of gear 1 and
    curvature (1/mm) there, and whether each lies on a tip round."""

    tooth: int
    s: np.ndarray
    phi: np.ndarray
    x: np.ndarray
    normal: np.ndarray
    curvature: np.ndarray
    on_round: np.ndarray
    probe: bool = False   # a coarse grid on a tooth not expected to carry load
    coarse: np.ndarray | None = None   # its window's coarse feet (:class:`Window`)

    def __len__(self) -> int:
        return len(self.s)

    @property
    def weights(self) -> np.ndarray:
        """∫ φ_j ds of each hat (mm): a uniform pressure p gives the force p·w·thickness."""
        w = np.zeros(len(self.s))
        d = np.diff(self.s)
        w[:-1] += 0.5 * d
        w[1:] += 0.5 * d
        return w


@dataclass(frozen=True)
class ToothSamples:
    """Tooth 0 of the rounded gear 1 sampled over one pitch, from the middle of the tooth
    space before it to the middle of the one after: polar angles (rad), points, normals,
    curvature (1/mm, > 0 convex), arc length (mm) and whether each sample is on a round."""

    shape: RoundedProfile
    phi: np.ndarray
    x: np.ndarray
    normal: np.ndarray
    kappa: np.ndarray
    s: np.ndarray
    on_round: np.ndarray

    def turned(self, tooth: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Polar angles, points and normals of tooth ``tooth``'s samples."""
        turn = tooth * self.shape.pitch
        return self.phi + turn, rotate(self.x, turn), rotate(self.normal, turn)


def sample_tooth(shape: RoundedProfile, count: int = SAMPLES) -> ToothSamples:
    """Sample tooth 0 of ``shape`` (see :class:`ToothSamples`)."""
    centre = shape.tooth_center
    phi = np.linspace(centre - 0.5 * shape.pitch, centre + 0.5 * shape.pitch, count)
    x, n, kappa = shape.frame(phi)
    s = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(x, axis=0).T))])
    return ToothSamples(shape, phi, x, n, kappa, s, shape.on_round(phi))


@dataclass(frozen=True)
class Window:
    """The sample range [lo, hi] (indices into :class:`ToothSamples`) of a tooth that a
    positive rotation closes to within the reach, the samples' gear-2 curvature (1/mm, > 0
    convex) where they face gear 2 at the first touch, and the ``anchor``: the sample of the
    smallest gap there, from which the grid's points are counted (:func:`tooth_grid`)."""

    tooth: int
    lo: int
    hi: int
    kappa2: np.ndarray
    anchor: int
    coarse: np.ndarray | None = None   # gear 2's ξ at the feet of every COARSE-th sample


@dataclass(frozen=True)
class Facing:
    """Gear 2 as gear 1's teeth face it: its curve ``curve2`` turned by the rolling angle
    ``beta`` (rad), and gear 1 turned by ``turn`` (rad, its kinematic angle included) about its
    centre, ``e`` (mm) from gear 2's."""

    curve2: Cycloid
    turn: float
    beta: float
    e: float


def window(samples: ToothSamples, facing: Facing, tooth: int, reach: float) -> Window | None:
    """The stretch of ``tooth`` whose rigid gap to gear 2 (as it faces the tooth: ``facing``)
    is below ``reach`` (mm) and closes under a positive turn; None if there is none
    (:func:`windows` for one tooth)."""
    return windows(samples, facing, (tooth,), (reach,))[0]


def windows(samples: ToothSamples, facing: Facing, teeth, reaches,
            start: dict | None = None) -> list[Window | None]:
    """:func:`window` of each of ``teeth`` with its own reach (mm): every COARSE-th sample
    first, then every sample where that found the gap within reach of the threshold. The
    teeth's samples go to gear 2's closest-point search together, one call a pass (the points
    are independent: the same windows as one call a tooth, a tenth of the calls). ``start``:
    the coarse feet found before for some teeth (tooth → :attr:`Window.coarse`: the position
    before in a cycle), the coarse search's start there (two or three Newton steps, not the
    polar start's inversion and four to fifty steps)."""
    if not teeth:
        return []
    curve2 = facing.curve2
    coarse = np.arange(0, len(samples.x), COARSE)
    points = [samples.turned(tooth)[1] for tooth in teeth]
    before = start or {}
    first = np.concatenate([before.get(t, np.full(len(coarse), np.nan)) for t in teeth])
    gaps = _split(_gaps(np.vstack([x[coarse] for x in points]), facing, first),
                  [len(coarse)] * len(teeth))
    ranges = []
    for (gap, closing, _), reach in zip(gaps, reaches):
        slack = np.abs(np.diff(gap, prepend=gap[0], append=gap[-1]))
        slack = np.maximum(slack[:-1], slack[1:])         # how far the gap moves to a neighbour
        near = np.flatnonzero((gap < reach + slack) & closing)
        ranges.append(None if len(near) == 0 else
                      (coarse[max(int(near.min()) - 1, 0)],
                       coarse[min(int(near.max()) + 1, len(coarse) - 1)]))
    found = [(k, *r) for k, r in enumerate(ranges) if r is not None]   # (tooth index, lo, hi)
    out: list[Window | None] = [None] * len(teeth)
    if not found:
        return out
    # the fine pass's foot searches start from the coarse feet, interpolated (a sample's foot
    # is a tenth of a coarse step from its neighbours': two Newton steps, not the polar
    # start's three and four more)
    start = np.concatenate([np.interp(np.arange(lo, hi + 1), coarse, np.unwrap(gaps[k][2]))
                            for k, lo, hi in found])
    fine = _split(_gaps(np.vstack([points[k][lo:hi + 1] for k, lo, hi in found]), facing,
                        start), [hi + 1 - lo for _, lo, hi in found])
    for (k, lo, _), (gap, closing, xi) in zip(found, fine):
        near = np.flatnonzero((gap < reaches[k]) & closing)
        if len(near) == 0:
            continue
        a, b = max(int(near.min()) - 1, 0), min(int(near.max()) + 1, len(gap) - 1)
        anchor = lo + int(near[np.argmin(gap[near])])
        out[k] = Window(teeth[k], lo + a, lo + b, 1.0 / curve2.curvature_radius(xi[a:b + 1]),
                        anchor, gaps[k][2])
    return out


def _split(parts, sizes) -> list[tuple]:
    """The arrays of ``parts`` (gap, closing, feet) cut into consecutive pieces of ``sizes``."""
    cuts = np.cumsum(sizes)[:-1]
    return list(zip(*(np.split(p, cuts) for p in parts)))


def _gaps(x: np.ndarray, facing: Facing, start: np.ndarray | None = None):
    """Rigid gap (mm) of tooth-0-frame points ``x`` of gear 1 to gear 2 as it faces them,
    whether a positive turn closes it, and gear 2's curve parameter ξ at the feet (searched
    from ``start`` where given)."""
    curve2, beta = facing.curve2, facing.beta
    o1 = np.array([0.0, facing.e])
    fixed = rotate(x, facing.turn) + o1
    y = rotate(fixed, -beta)
    xi = curve2.feet(y, start=start)
    _, normal, gap = curve2.at_feet(y, xi)
    r = rotate(fixed - o1, -beta)
    closing = np.einsum("ij,ij->i", normal, np.column_stack([-r[:, 1], r[:, 0]])) < 0
    return gap, closing, xi


@dataclass(frozen=True)
class GridSpacing:
    """How finely a fine grid samples a tooth (:func:`tooth_grid`): a ``per_b``-th of the local
    Hertz half-width under the line load ``load`` (N/mm) at the contact modulus ``E_star``
    (MPa), at least ``floor`` (mm), at most a ``MIN_POINTS``-th of the stretch that a gap of
    ``reach`` (mm) spans at the window's anchor."""

    load: float
    E_star: float
    per_b: float
    floor: float
    reach: float


def tooth_grid(samples: ToothSamples, win: Window, spacing: GridSpacing,
               probe: bool = False) -> ToothGrid:
    """The grid over the window ``win``: its spacing a ``per_b``-th of the local Hertz
    half-width for the relative curvature of the two profiles, within the bounds of
    ``spacing``; ``JUNCTION_FACTOR`` times finer again within ``JUNCTION`` round widths of the
    rounds' tangent points, coarsening beyond by ``GRADING`` of the distance (from 1 µm to the
    flank's 19 µm in one step, `coarse` read the flank pressure beside an edge 1 % low). The
    points are counted from the window's anchor, so two windows of a tooth at one position
    share every point but their ends: a position solved in a cycle and alone has the same grid
    where it carries pressure, whatever rotation each placed its windows for. A ``probe``
    grid, on a tooth not expected to touch, has PROBE_POINTS evenly: enough to tell whether it
    does."""
    return tooth_grids(samples, (win,), spacing, (probe,))[0]


def tooth_grids(samples: ToothSamples, wins, spacing: GridSpacing,
                probes) -> tuple[ToothGrid, ...]:
    """:func:`tooth_grid` over each of the windows ``wins``, a probe where ``probes`` says:
    the exact profile evaluated for all their points at once (its Newton iterations are each
    point's own: the same points as one window at a time, a third of the time)."""
    angles = []
    for win, probe in zip(wins, probes):
        k = slice(win.lo, win.hi + 1)
        s = samples.s[k] - samples.s[win.lo]
        if probe:
            sg = np.linspace(0.0, s[-1], PROBE_POINTS + 1)
        else:
            sg = _counted(samples, win, s, spacing)
        sg = sg[np.concatenate([[True], np.diff(sg) > 1e-9 * s[-1]])]  # samples of zero length
        angles.append((np.interp(sg, s, samples.phi[k]), s[-1]))     # tooth 0's angles
    shape = samples.shape
    if not angles:
        return ()
    x_all, n_all, kappa_all = shape.frame(np.concatenate([phi0 for phi0, _ in angles]))
    cuts = np.cumsum([len(phi0) for phi0, _ in angles])[:-1]
    out = []
    for win, probe, (phi0, length), x, n, kappa in zip(
            wins, probes, angles, np.split(x_all, cuts), np.split(n_all, cuts),
            np.split(kappa_all, cuts)):
        turn = win.tooth * shape.pitch
        xg, ng = rotate(x, turn), rotate(n, turn)
        chord = np.hypot(*np.diff(xg, axis=0).T)
        keep = np.concatenate([[True], chord > 1e-9 * max(length, 1e-12)])  # coincident points
        xg, ng, kappa, phi0 = xg[keep], ng[keep], kappa[keep], phi0[keep]
        sg = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(xg, axis=0).T))])  # exact chords
        out.append(ToothGrid(win.tooth, sg, phi0 + turn, xg, ng, kappa, shape.on_round(phi0),
                             probe, win.coarse))
    return tuple(out)


def _counted(samples: ToothSamples, win: Window, s: np.ndarray,
             rule: GridSpacing) -> np.ndarray:
    """A fine grid's arc positions (from the window's start): the points where the count of
    spacings (``rule``) from the anchor is whole, the window's two ends and the rounds' exact
    tangent points, where the curvature jumps (a whole count within half a spacing of one of
    those gives way to it)."""
    load, E_star, per_b, floor = rule.load, rule.E_star, rule.per_b, rule.floor
    k = slice(win.lo, win.hi + 1)
    relative = np.maximum(samples.kappa[k] + win.kappa2, 1e-9)
    b = np.sqrt(4.0 * load / (math.pi * E_star * relative))
    a = win.anchor - win.lo
    span = min(2.0 * math.sqrt(2.0 * rule.reach / relative[a]), samples.s[-1])
    spacing = np.clip(b / per_b, floor, max(span / MIN_POINTS, floor))
    on_round = samples.on_round[k]
    for j in np.flatnonzero(np.diff(on_round.astype(int)) != 0):
        b_round = b[j] if on_round[j] else b[j + 1]     # the round's width at its end
        fine = max(b_round / (per_b * JUNCTION_FACTOR), floor)
        graded = fine + GRADING * np.maximum(np.abs(s - s[j]) - JUNCTION * b_round, 0.0)
        spacing = np.minimum(spacing, graded)
    count = np.concatenate([[0.0], np.cumsum(np.diff(s) / (0.5 * (spacing[1:] + spacing[:-1])))])
    count -= count[a]
    marks = np.concatenate([[0.0], _tangent_points(samples, win, s), [s[-1]]])
    whole = np.arange(math.ceil(count[0]), math.floor(count[-1]) + 1)
    near = np.abs(whole[:, None] - np.interp(marks, s, count)[None, :]).min(axis=1) < 0.5
    return np.sort(np.concatenate([marks, np.interp(whole[~near], count, s)]))


def _tangent_points(samples: ToothSamples, win: Window, s: np.ndarray) -> np.ndarray:
    """Arc positions (from the window's start) of the rounds' tangent points inside the
    window."""
    shape = samples.shape
    phi = samples.phi[win.lo:win.hi + 1]
    ends = np.array([a for f in shape.fillets for a in (f.phi_a, f.phi_b)])
    if len(ends) == 0:
        return np.zeros(0)
    # the fillets' angles are the tooth's own, some pitch away from the samples' range
    ends = ends + np.round((samples.phi[len(samples.phi) // 2] - ends) / shape.pitch) \
        * shape.pitch
    inside = ends[(ends > phi[0]) & (ends < phi[-1])]
    return np.interp(np.sort(inside), phi, s)

"""A kept contact's rigid gaps for other deviations of the pair without searching gear 2's
curve: what a solve on a kept contact iterates on (:mod:`.phases`).

A contact kept for a phase is solved again and again with other deviations (a tolerance
class's samples at one position, a revolution's pitches), each point's rigid gap taken at
rotations within a few elastic approaches of the kept one, with teeth moved by a few µm. The
exact gap searches each point's foot on gear 2's curve (:meth:`~fegear.geometry.Placed.gap`),
a Newton iteration of trigonometric sums a point, at every linearisation of the rotation.
Here each point's foot is found once, at the kept rotation on the exact pair, and the curve
there replaced by its osculating circle (:func:`foot_circles`); a solve then moves the points
exactly as the deviated gap does (its rotation and each tooth's pitch turn, the centre
distance's and the runouts' offsets, the gear-2 tooth's turn), measures them to the circles,
and takes the flanks' slope and form departures at their roll fractions (:func:`circle_gaps`).

The circle matches the curve to the second order in the foot's slide: the gap is exact to
the third, about 2e-7 mm where a class-6 pair's teeth move 10 µm and turn 9 µm of arc. The
whole pair repeats over whole pitches, so the circles made at the kept pitch, in the fixed
frame, serve every pitch of its phase. A solve's last evaluation is of the exact gaps at every
point; where they differ from the circles' by more than :data:`TOLERANCE` on the points it
iterated on, its iterations go on with the exact gaps (:func:`~.contact.solve_with`).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from ...geometry import Cycloid, Placed, gear2_tooth
from ...planar import rotate, rotate_by
from .influence import RingContact
from .model import RingModel

#: the largest difference (mm) between the circles' gaps and the exact ones at a solve's
#: solution, on the points it iterated on: 0.2 nm, about a hundred-thousandth of an elastic
#: approach (a class-6 pair's teeth moved 10 µm leave about 0.17 nm)
TOLERANCE = 2e-7
#: a point whose gap to its circle, at a solve's solution, stays this far (mm) open beyond ten
#: times the circles' error bound is open whatever its exact gap (:func:`unsure`): 0.1 µm
MARGIN = 1e-4


@dataclass(frozen=True)
class FootCircles:
    """Each point's foot on gear 2's curve (fixed frame, at the rolling angle the contact was
    kept at, the exact pair turned by its kept rotation), the curve's unit gap-side normal
    and tangent there and its curvature (1/mm, > 0 where it turns towards the normal)."""

    foot: np.ndarray
    normal: np.ndarray
    tangent: np.ndarray
    kappa: np.ndarray


@dataclass(frozen=True)
class Moved:
    """What one solve's deviations do to a contact's points (:func:`moved`): the points
    turned by the kinematic angle and each by its tooth's pitch deviation (gear-1 frame to
    fixed, (n, 2)), the cosine and sine of each one's gear-2 tooth's turn (None: none
    turns), gear 1's axis and the teeth's offset from it (mm, fixed frame), gear 1's flank
    departures (mm), and the placed deviations with each point's gear-2 tooth, whose flank
    departures are taken where the point's foot slides to (None: gear 2 has none). The
    per-point turns are taken once a solve: an evaluation turns the points by one angle."""

    x: np.ndarray
    turn2: tuple[np.ndarray, np.ndarray] | None
    axis: np.ndarray
    offset: np.ndarray
    flank1: np.ndarray
    gear2: tuple | None = None


def foot_circles(model: RingModel, contact: RingContact, theta: float) -> FootCircles:
    """The :class:`FootCircles` of ``contact``'s points on the exact pair turned by ``theta``
    (rad, beyond the kinematic angle), whatever deviations it was assembled with."""
    p = model.case.params
    fixed = rotate(contact.x, p.ratio * contact.beta + theta) + np.array([0.0, p.e])
    xi = model.curve2.feet(rotate(fixed, -contact.beta), start=contact.feet.copy())
    foot, tangent, normal, kappa = model.curve2.frame(xi)
    return FootCircles(rotate(foot, contact.beta), rotate(normal, contact.beta),
                       rotate(tangent, contact.beta), kappa)


def moved(circles: FootCircles, model: RingModel, contact: RingContact) -> Moved:
    """``contact``'s deviations (:attr:`~.influence.RingContact.placed`, none: the exact
    pair) on its points, as :meth:`~fegear.geometry.Placed.gap` moves them: its teeth, and the
    gear-2 teeth its feet face as it stands (:func:`moved_by`)."""
    p = model.case.params
    if contact.placed is None:
        return Moved(rotate(contact.x, p.ratio * contact.beta), None, np.array([0.0, p.e]),
                     np.zeros(2), np.zeros(contact.npoints))
    return moved_by(contact.placed, contact.x, contact.teeth, p.ratio * contact.beta,
                    gear2_tooth(contact.feet, p.z2))


def moved_by(placed: Placed, x: np.ndarray, teeth: np.ndarray, turn, teeth2: np.ndarray,
             flanks: bool = True) -> Moved:
    """Gear 1's points ``x`` (its own frame, (n, 2)) on its ``teeth`` moved by ``placed``'s
    deviations as :meth:`~fegear.geometry.Placed.gap` moves them: turned by ``turn`` (rad,
    the kinematic angle included; scalar or a point's) and each by its tooth's pitch
    deviation, the gear-2 teeth ``teeth2`` under them turned by theirs; ``flanks``: whether
    the points are on the loaded flanks, which the slope and form deviations move."""
    dev, p = placed.deviations, placed.params
    turn2 = dev.turns(2, teeth2, p.r0) if dev.gear2 else None
    flank1 = (dev.flank_offset(1, teeth, placed.roll(1, x)) if flanks
              else np.zeros(len(x)))
    return Moved(rotate(x, turn + dev.turns(1, teeth, p.r1)),
                 None if turn2 is None else (np.cos(turn2), np.sin(turn2)), placed.axis1,
                 placed.teeth_offset, flank1,
                 (placed, teeth2) if dev.gear2 and flanks else None)


def circle_gaps(circles: FootCircles, moved: Moved, theta: float,
                idx: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """The rigid gaps (mm) of the points ``idx`` (default all) to their foot circles with gear
    1 turned by ``theta`` (rad, beyond the kinematic angle) and the points ``moved``, and the
    gaps' rate with that turn (mm/rad)."""
    return _measured(circles, moved, theta, idx)[:2]


def unsure(model: RingModel, circles: FootCircles, moved: Moved, theta: float,
           elastic: np.ndarray, loaded: np.ndarray
           ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Every point's rigid gap (mm) to its circle with gear 1 turned by ``theta`` (rad, beyond
    the kinematic angle) and the points ``moved``, its rate with the turn (mm/rad), and the
    points whose gaps the circles do not settle: those ``loaded`` (carrying pressure) and
    those whose gap with the ``elastic`` separation (mm) added comes within :data:`MARGIN`
    plus ten times the circles' error bound of closing. A circle matches gear 2's curve to the
    second order, so its gap is off by about |dκ/ds| |slide|³ / 6, the slide being the
    point's tangential offset from its foot; the bound takes the curve's largest |dκ/ds|
    (:func:`third_order`). The others are open whatever the exact gap."""
    gap, rate, slide = _measured(circles, moved, theta, None)
    bound = MARGIN + 10.0 * third_order(model.curve2) * np.abs(slide) ** 3
    return gap, rate, loaded | (gap + elastic <= bound)


@functools.lru_cache(maxsize=8)
def third_order(curve: Cycloid) -> float:
    """The third-order coefficient of a foot circle's error on ``curve`` (1/mm²): its largest
    |dκ/ds| over a lobe (sampled at 4096 points), over 6."""
    xi = np.linspace(0.0, 2.0 * math.pi / curve.z, 4097)
    return float(np.abs(curve.curvature_rate(xi)).max()) / 6.0


def _measured(circles: FootCircles, moved: Moved, theta: float, idx: np.ndarray | None
              ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """:func:`circle_gaps`, and each point's slide along its circle's tangent (mm)."""
    sel = slice(None) if idx is None else idx
    lever = rotate(moved.x[sel], theta) + moved.offset
    point = lever + moved.axis
    if moved.turn2 is not None:   # gear 2's tooth turned: the point turned back about its axis
        c, s = moved.turn2[0][sel], -moved.turn2[1][sel]
        point = rotate_by(point, c, s)
        lever = rotate_by(lever, c, s)
    u = point - circles.foot[sel]
    normal, tangent, kappa = circles.normal[sel], circles.tangent[sel], circles.kappa[sel]
    d = np.einsum("ij,ij->i", u, normal)
    s = np.einsum("ij,ij->i", u, tangent)
    bend = 1.0 - kappa * d
    q = np.sqrt(bend * bend + (kappa * s) ** 2)
    gap = (2.0 * d - kappa * (d * d + s * s)) / (1.0 + q) - moved.flank1[sel]
    if moved.gear2 is not None:   # at the roll fraction of the point's foot on its circle
        placed, k2 = moved.gear2
        slid = circles.foot[sel] + (s[:, None] * tangent + (kappa * s * s / (q + bend))[:, None]
                                    * normal) / q[:, None]
        gap -= placed.deviations.flank_offset(2, k2[sel], placed.roll(2, slid))
    grad = (bend[:, None] * normal - (kappa * s)[:, None] * tangent) / q[:, None]
    return gap, grad[:, 1] * lever[:, 0] - grad[:, 0] * lever[:, 1], s

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
point (a brief one's where the circles cannot tell a point open: :func:`unsure`); where they
differ from the circles' by more than :data:`TOLERANCE` on the points it iterated on, its
iterations go on with the exact gaps (:func:`~.contact.solve_with`). A solve projects its
points on their circles once (:class:`Projected`), and each evaluation reads the projections.
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

    @classmethod
    def at_feet(cls, curve: Cycloid, xi: np.ndarray, beta) -> FootCircles:
        """The circles at gear 2's ``curve`` parameters ``xi``, the curve turned by ``beta``
        (rad; scalar or a point's) into the fixed frame."""
        foot, tangent, normal, kappa = curve.frame(xi)
        return cls(rotate(foot, beta), rotate(normal, beta), rotate(tangent, beta), kappa)


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
    return FootCircles.at_feet(model.curve2, xi, contact.beta)


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
    return projected(circles, moved, idx).measured(theta)[:2]


@dataclass(frozen=True)
class Projected:
    """Points moved (:class:`Moved`) and measured against their foot circles at any turn of
    gear 1 (:func:`projected`): turned by θ beyond the kinematic angle, a point less its foot
    is cos θ a + sin θ b + c and its lever about gear 1's axis cos θ a + sin θ b + o (gear 2's
    tooth's turn included), so an evaluation combines the vectors' projections on the
    circle's normal (``n``, rows a, b, c, o) and tangent (``t``) with its curvature
    ``kappa``, less gear 1's flank departures ``flank1`` (mm); gear 2's flank departures are
    read at the roll fraction of the foot's slide, from the foot's projections and squared
    length (``foot``: rows n, t, |f|²) and ``gear2`` (the placed deviations and each point's
    gear-2 tooth; None: none)."""

    n: np.ndarray
    t: np.ndarray
    kappa: np.ndarray
    flank1: np.ndarray
    foot: np.ndarray | None = None
    gear2: tuple | None = None

    def take(self, idx: np.ndarray) -> Projected:
        """The points ``idx`` of these."""
        return Projected(self.n[:, idx], self.t[:, idx], self.kappa[idx], self.flank1[idx],
                         None if self.foot is None else self.foot[:, idx],
                         None if self.gear2 is None else (self.gear2[0], self.gear2[1][idx]))

    def measured(self, theta: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The points' rigid gaps (mm) and their rates with the turn (mm/rad) at gear 1 turned
        by ``theta`` (rad, beyond the kinematic angle), and each one's slide along its circle's
        tangent from its foot (mm)."""
        turn = np.array([[math.cos(theta), math.sin(theta), 1.0, 0.0],
                         [math.cos(theta), math.sin(theta), 0.0, 1.0]])
        (d, nv), (s, tv) = turn @ self.n, turn @ self.t   # a point's offsets, its lever's
        kappa = self.kappa
        bend = 1.0 - kappa * d
        ks = kappa * s
        q = np.sqrt(bend * bend + ks * ks)
        gap = (2.0 * d - kappa * (d * d + s * s)) / (1.0 + q) - self.flank1
        if self.gear2 is not None:   # the foot slid along the circle by s t + h n, over q
            placed, k2 = self.gear2
            h = ks * s / (q + bend)
            fn, ft, f2 = self.foot
            r = np.sqrt(f2 + 2.0 * (s * ft + h * fn) / q + (s * s + h * h) / (q * q))
            gap -= placed.deviations.flank_offset(2, k2, placed.roll_at(2, r))
        # the gradient (bend n − κ s t) / q on the lever turned a quarter, J v: n · J v = t · v
        # and t · J v = −n · v
        return gap, (bend * tv + ks * nv) / q, s


def projected(circles: FootCircles, moved: Moved, idx: np.ndarray | None = None) -> Projected:
    """The points ``moved`` (those of ``idx``, default all) projected on their ``circles``
    (:class:`Projected`)."""
    sel = slice(None) if idx is None else idx
    x = moved.x[sel]
    # the vectors a, b, o and the axis, each (n, 2), as one array (4, n, 2)
    v = np.stack([x, np.column_stack([-x[:, 1], x[:, 0]]),
                  *np.broadcast_arrays(moved.offset, moved.axis, x)[:2]])
    if moved.turn2 is not None:   # gear 2's tooth turned: the point turned back about its axis
        cos, sin = moved.turn2[0][sel], -moved.turn2[1][sel]
        v = rotate_by(v, cos, sin)
    foot, normal, tangent = circles.foot[sel], circles.normal[sel], circles.tangent[sel]
    v = np.stack([v[0], v[1], v[2] + v[3] - foot, v[2]])   # a, b, o + axis − foot, o
    n = v[..., 0] * normal[:, 0] + v[..., 1] * normal[:, 1]
    t = v[..., 0] * tangent[:, 0] + v[..., 1] * tangent[:, 1]
    gear2, on_foot = None, None
    if moved.gear2 is not None:
        placed, k2 = moved.gear2
        gear2 = (placed, k2[sel])
        on_foot = np.stack([np.einsum("ij,ij->i", foot, normal),
                            np.einsum("ij,ij->i", foot, tangent),
                            np.einsum("ij,ij->i", foot, foot)])
    return Projected(n, t, circles.kappa[sel], moved.flank1[sel], on_foot, gear2)


def unsure(model: RingModel, points: Projected, theta: float, elastic: np.ndarray,
           loaded: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Every point's rigid gap (mm) to its circle (the ``points`` projected on them) with gear
    1 turned by ``theta`` (rad, beyond the kinematic angle), its rate with the turn (mm/rad),
    and the points whose gaps the circles do not settle: those ``loaded`` (carrying pressure)
    and those whose gap with the ``elastic`` separation (mm) added comes within
    :data:`MARGIN` plus ten times the circles' error bound of closing. A circle matches gear
    2's curve to the second order, so its gap is off by about |dκ/ds| |slide|³ / 6, the
    slide being the point's tangential offset from its foot; the bound takes the curve's
    largest |dκ/ds| (:func:`third_order`). The others are open whatever the exact gap."""
    gap, rate, slide = points.measured(theta)
    bound = MARGIN + 10.0 * third_order(model.curve2) * np.abs(slide) ** 3
    return gap, rate, loaded | (gap + elastic <= bound)


@functools.lru_cache(maxsize=8)
def third_order(curve: Cycloid) -> float:
    """The third-order coefficient of a foot circle's error on ``curve`` (1/mm²): its largest
    |dκ/ds| over a lobe (sampled at 4096 points), over 6."""
    xi = np.linspace(0.0, 2.0 * math.pi / curve.z, 4097)
    return float(np.abs(curve.curvature_rate(xi)).max()) / 6.0

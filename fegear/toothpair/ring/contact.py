"""The contact solve at one position: grid pressures p ≥ 0 and gaps g ≥ 0, complementary, with
the contact moments balancing the torque on gear 1 (load control); no penalty.

The gap of grid point i at gear 1's rotation θ (from its kinematic position) is
g_i = g_rigid,i(θ) + Σ_j A_ij p_j, the exact rigid gap to gear 2's curve plus the elastic
separation (:mod:`.influence`). Active-set iterations (:mod:`.contact_system`) solve the
linearised rigid gap with the torque balance; the exact gap is then evaluated again at the new
rotation until the rotation settles (the rigid gap is nonlinear in θ only through the turn, a
µrad here).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from ...planar import rotate
from .circles import TOLERANCE, FootCircles, moved, projected, unsure
from .contact_system import ActiveSet, ContactSystem, RingContactError, active_set, loaded_product
from .influence import RingContact, approach_open
from .master import Gear2Master
from .model import RingModel

if TYPE_CHECKING:   # a kept contact's, made by its phases; it steps with this module's methods
    from .coarse import CoarseContact

MAX_TURNS = 30          # linearisations of the rigid gap
ARM_STEP = 1e-7         # turn (rad) of the torque arm's difference quotient
CONTRACTION = 0.01      # steps of the rotation shrinking by this at least are read as settling


@dataclass(frozen=True)
class RingContactSolution:
    """The converged contact: pressure per grid point (MPa), gap (mm), gear 1's rotation θ
    from its kinematic position (rad), active-set iterations, linearisations, torque-balance
    error (relative) and the largest overlap (mm) left where pressure acts. ``clamped``:
    each gear's clamped fields of its loaded sectors under the pressure (sector → template
    field), where the open points' check formed them (:func:`~.influence.approach_open`):
    the stresses' fields take them; not kept in a solved position's record. ``rigid``: every
    point's rigid gap (mm) at the solved rotation and its rate with the turn (mm/rad), the
    last evaluation's, which the teeth's results take (not kept either)."""

    pressure: np.ndarray
    gap: np.ndarray
    rotation: float
    iterations: int
    turns: int
    balance_error: float
    max_penetration: float
    clamped: tuple | None = field(default=None, repr=False, compare=False)
    rigid: tuple | None = field(default=None, repr=False, compare=False)


def rigid_gap(model: RingModel, contact: RingContact, turn: float,
              feet: np.ndarray | None = None, idx: np.ndarray | None = None
              ) -> tuple[np.ndarray, np.ndarray]:
    """Exact gap (mm) of the ``contact``'s points (those of ``idx``, default all) to gear 2
    (turned by its β) with gear 1 turned by ``turn`` (rad, kinematic angle included), with
    the pair's deviations where it has any (:attr:`~.influence.RingContact.placed`), and the
    gap's rate with that turn (mm/rad). ``feet``: gear 2's parameters ξ to start the points'
    foot searches from (the feet at a nearby turn, :attr:`~.influence.RingContact.feet`),
    overwritten with the feet found."""
    x = contact.x if idx is None else contact.x[idx]
    if contact.placed is not None:
        teeth = contact.teeth if idx is None else contact.teeth[idx]
        return contact.placed.gap(x, teeth, turn, feet)
    o1 = np.array([0.0, model.case.params.e])
    fixed = rotate(x, turn) + o1
    cp = Gear2Master(model.curve2, contact.beta).closest(fixed, feet)
    r = fixed - o1
    return cp.distance, np.einsum("ij,ij->i", cp.normal, np.column_stack([-r[:, 1], r[:, 0]]))


@dataclass(frozen=True)
class Iterations:
    """How a contact solve's iterations go: none of it changes the solution, only how many
    iterations reach it. They start from the points ``start`` (a mask over the contact's
    points: where the position before carried pressure, say), else from those the rigid teeth
    overlap at the rotation ``guess`` (rad), else from the point of least gap. ``within``
    (mm): on a contact with every column formed, they take only the points whose rigid gap at
    the first rotation is within that of the least (a kept contact's wide grids, most of them
    far from closing); the others are checked at the solution, and where one overlaps the
    contact is solved again on every point. ``circles``: the contact's points' foot circles
    (:mod:`.circles`), which they measure the gaps to instead of searching gear 2's curve; the
    last evaluation is exact, and where the two differ they go on with the exact gaps.
    ``coarse``: the contact's coarse level (:mod:`.coarse`), which predicts the points and
    the rotation they start from, from ``start``. ``brief``: with circles, on a contact with
    every column formed, the last evaluation is exact only where a point carries pressure or
    the circles cannot tell it open (:func:`~.circles.unsure`); the others keep the circles'
    gaps (a record that reads no open point's rigid gap: a class's brief sample)."""

    start: np.ndarray | None = None
    guess: float | None = None
    within: float | None = None
    circles: FootCircles | None = None
    coarse: CoarseContact | None = None
    brief: bool = False


def solve_ring_contact(model: RingModel, contact: RingContact, torque_nmm: float, theta: float,
                       guess: float | None = None, start: np.ndarray | None = None
                       ) -> RingContactSolution | None:
    """Solve the contact under ``torque_nmm`` (N·mm on gear 1) from the rotation ``theta``
    (rad), the iterations starting from the points ``start``, else from those the rigid teeth
    overlap at the rotation ``guess`` (:class:`Iterations`): :func:`solve_with`'s common
    call."""
    return solve_with(model, contact, torque_nmm, theta, Iterations(start=start, guess=guess))


def solve_with(model: RingModel, contact: RingContact, torque_nmm: float, theta: float,
               how: Iterations) -> RingContactSolution | None:
    """Solve the contact under ``torque_nmm`` (N·mm on gear 1) from the rotation ``theta``
    (rad), the iterations going as ``how`` says. On a contact whose probe columns are not
    formed (:func:`~.influence.assemble_contact`), the points of the formed columns are solved
    and the others kept open; that is the solution if none of them then overlaps (their
    pressures zero, their columns act on nothing), else None: the caller forms them."""
    gaps = _Gaps(model, contact, how.circles, how.brief and contact.complete)
    it = _first(gaps, theta, how, torque_nmm)
    _linearise(gaps, it, torque_nmm)
    g0, a = it.rigid   # every point's, exact at the solution
    balance = abs(-(it.w * it.pressure) @ a[it.on] - torque_nmm) / torque_nmm
    pressure = it.pressure
    if it.near is not None:   # the points left out: the pressures act on them too
        pressure = np.zeros(len(it.near))
        pressure[it.near] = it.pressure
    closed = _closed(model, contact, pressure, g0, it.elastic)
    if closed is None:
        return None
    full, gap, clamped = closed
    if it.near is not None and (gap[~it.near] < 0).any():   # every column formed: near spans all
        return solve_ring_contact(model, contact, torque_nmm, it.theta, how.guess, how.start)
    loaded = full > 0
    overlap = float(max(0.0, -gap[loaded].min())) if loaded.any() else 0.0
    return RingContactSolution(full, gap, float(it.theta), it.iterations, it.turns,
                               float(balance), overlap, clamped, (g0, a))


class _Gaps:
    """The rigid gaps a solve's iterations measure: the exact ones (:func:`rigid_gap`), or
    given foot circles the circles' until the last evaluation finds them off the exact ones
    (then ``points`` is None), the points projected on them once (:class:`~.circles.Projected`;
    the last points asked for taken once too: the linearisations ask for the same);
    ``brief`` as :class:`Iterations`'."""

    def __init__(self, model: RingModel, contact: RingContact, circles: FootCircles | None,
                 brief: bool = False):
        self.model, self.contact, self.circles, self.brief = model, contact, circles, brief
        self.alpha = model.case.params.ratio * contact.beta   # gear 1's kinematic turn (rad)
        self.points = None if circles is None else projected(circles,
                                                              moved(circles, model, contact))
        self._taken: tuple | None = None

    def __call__(self, turn: float, feet: np.ndarray, idx: np.ndarray
                 ) -> tuple[np.ndarray, np.ndarray]:
        """The gaps (mm) of the points ``idx`` with gear 1 turned by ``turn`` (rad, kinematic
        angle included) and their rates with the turn (mm/rad); ``feet`` as
        :func:`rigid_gap`'s."""
        if self.points is None:
            return rigid_gap(self.model, self.contact, turn, feet, idx)
        if self._taken is None or self._taken[0] is not idx:
            self._taken = (idx, self.points.take(idx))
        return self._taken[1].measured(turn - self.alpha)[:2]

    def settled(self, it: _Iterate) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Every point's rigid gaps (mm) and rates (mm/rad) at the rotation ``it`` settled at,
        and a mask of those measured exactly: every point, or where ``brief`` (and circles)
        those the circles do not settle, the others the circles' (:func:`~.circles.unsure`;
        the contact's every column formed, so A spans its points: the pressures' A p, which
        that reads, kept in ``it.elastic`` for the solution's gaps)."""
        contact, turn = self.contact, self.alpha + it.theta
        it.elastic = None
        if self.points is None or not self.brief:
            g0, a = rigid_gap(self.model, contact, turn, contact.feet)
            return g0, a, np.ones(len(g0), bool)
        pressure = np.zeros(contact.npoints)
        pressure[it.on] = it.pressure
        contact.ready(np.flatnonzero(pressure))
        it.elastic = loaded_product(contact.A, pressure)
        g0, a, exact = unsure(self.model, self.points, it.theta, it.elastic, pressure > 0)
        idx = np.flatnonzero(exact)
        feet = contact.feet[idx]
        g0[idx], a[idx] = rigid_gap(self.model, contact, turn, feet, idx)
        contact.feet[idx] = feet
        return g0, a, exact


@dataclass
class _Iterate:
    """Where a solve's iterations are: the points they take (``on``, indices among the
    contact's points; where they are some of the formed points, ``near`` the mask of them
    over those and ``rows`` their rows of A), each one's force per unit pressure ``w`` (mm²)
    and foot on gear 2, gear 1's rotation ``theta`` (rad), the rigid gaps ``g0`` (mm) and
    their rates ``a`` (mm/rad) there, the ``active`` set and ``pressure`` (MPa) found, the
    active-set iterations counted and each linearisation's rotation step (``steps``, rad, its
    size), the blocks of A met (:class:`~.contact_system.ContactSystem`) and, once settled,
    every point's exact rigid gaps and rates (``rigid``) and, where the last evaluation
    formed it, A p at every point (``elastic``, mm)."""

    on: np.ndarray
    w: np.ndarray
    feet: np.ndarray
    theta: float
    g0: np.ndarray
    a: np.ndarray
    active: np.ndarray
    pressure: np.ndarray
    near: np.ndarray | None = None
    rows: np.ndarray | None = None
    iterations: int = 0
    blocks: dict = field(default_factory=dict)
    rigid: tuple | None = None
    steps: list = field(default_factory=list)
    elastic: np.ndarray | None = None

    @property
    def turns(self) -> int:
        """The linearisations made."""
        return len(self.steps)


def _first(gaps: _Gaps, theta: float, how: Iterations, torque_nmm: float) -> _Iterate:
    """The points the iterations take, their rigid gaps at ``theta`` (or where the coarse
    level predicts the rotation) and the active set they start from (:class:`Iterations`)."""
    model, contact = gaps.model, gaps.contact
    on = np.flatnonzero(contact.formed)
    feet = contact.feet[on]
    if how.coarse is not None and contact.complete:   # on: every point
        pick = how.coarse.pick
        predicted = how.coarse.predict(*gaps(gaps.alpha + theta, contact.feet[pick], pick),
                                       torque_nmm, how.start, how.within)
        if predicted is not None:
            how = Iterations(predicted[0], how.guess, how.within)
            theta += predicted[1]
    g0, a = gaps(gaps.alpha + theta, feet, on)
    near, rows = None, None
    if how.within is not None and contact.complete and (g0 > g0.min() + how.within).any():
        near = g0 <= g0.min() + how.within
        rows = np.flatnonzero(near)
        on, feet, g0, a = on[near], feet[near], g0[near], a[near]
    w = contact.weight[on] * model.case.thickness
    active = g0 <= g0.min() + 1e-12
    if how.start is not None and how.start[on].any():
        active = how.start[on].copy()
    elif how.guess is not None:
        overlap = gaps(gaps.alpha + how.guess, feet.copy(), on)[0] < 0
        active = overlap if overlap.any() else active
    return _Iterate(on, w, feet, theta, g0, a, active, np.zeros(len(g0)), near, rows)


def _linearise(gaps: _Gaps, it: _Iterate, torque_nmm: float) -> None:
    """The active-set method on the rigid gap linearised at the rotation, turned by its step
    and linearised again until the rotation settles, to rounding (module docstring)."""
    while True:
        system = ContactSystem(gaps.contact.A, it.w, it.g0, it.a, it.rows, it.blocks,
                               gaps.contact.former)
        found = _set_settled(system, torque_nmm, it.active, _arm_rate(gaps, it))
        it.pressure, it.active = found.pressure, found.active
        it.iterations += found.iterations
        it.theta += found.step
        it.steps.append(abs(found.step))
        if _settled(it, gaps.model.case.params.r0, found.iterations == 1):
            if _exact(gaps, it, found.step):
                return
            continue
        it.g0, it.a = gaps(gaps.alpha + it.theta, it.feet, it.on)
        if it.turns == MAX_TURNS:
            raise RingContactError(f"the rotation did not settle in {MAX_TURNS} "
                                   "linearisations")


def _set_settled(system: ContactSystem, torque_nmm: float, active: np.ndarray,
                 arm_rate: float) -> ActiveSet:
    """:func:`active_set` with the torque arm's rate, or without it where the set does not
    settle with it (the rate only speeds the linearisations up): on a pointed tooth's few
    probe points, their compliance far from symmetric, it can leave no descent."""
    try:
        return active_set(system, torque_nmm, active, arm_rate)
    except RingContactError:
        if not arm_rate:
            raise
        return active_set(system, torque_nmm, active)


def _settled(it: _Iterate, r0: float, kept: bool) -> bool:
    """Whether the rotation has settled to 1e-12 of it or a 1e-13 mm turn at the pitch circle
    (``r0``, mm): its last step within that, or, where the steps contract (by at least
    :data:`CONTRACTION` each), the steps to come, the last times its ratio r to the one before
    over 1 − r; r is the last ratio where the linearisation kept its active set (``kept``),
    else the larger of the last two (an active set's change makes a step of its own)."""
    tol = max(1e-12 * abs(it.theta), 1e-13 / r0)
    if it.steps[-1] <= tol:
        return True
    steps = it.steps[-2:] if kept else it.steps[-3:]
    if len(steps) < (2 if kept else 3) or not all(steps[:-1]):
        return False
    ratio = max(b / a for a, b in zip(steps, steps[1:]))
    return ratio <= CONTRACTION and it.steps[-1] * ratio / (1.0 - ratio) <= tol


def _arm_rate(gaps: _Gaps, it: _Iterate) -> float:
    """The torque's rate with gear 1's turn at the last pressures, Σ w (da/dθ) p (N·mm/rad):
    the torque's arm turns with gear 1, and where gear 2 bends sharply (a pointed tip) the
    rotation converged only linearly, half a digit a linearisation, without this term. The
    loaded points' arms alone: the others carry nothing."""
    loaded = np.flatnonzero(it.pressure)
    if not len(loaded):
        return 0.0
    ahead = gaps(gaps.alpha + it.theta + ARM_STEP, it.feet[loaded], it.on[loaded])[1]
    return (it.w[loaded] * it.pressure[loaded]) @ (ahead - it.a[loaded]) / ARM_STEP


def _exact(gaps: _Gaps, it: _Iterate, step: float) -> bool:
    """The last evaluation, exact at every point or, ``brief``, at those the circles do not
    settle (:meth:`_Gaps.settled`; the open ones' gaps are checked with it): True where the
    gaps the iterations settled on are the exact ones there (always without foot circles);
    else the iterations go on with the exact gaps."""
    contact = gaps.contact
    if gaps.points is None:
        contact.feet[it.on] = it.feet
    iterated = it.g0 + it.a * step   # the gaps the iterations settled on
    g0, a, exact = gaps.settled(it)
    off = np.abs(g0[it.on] - iterated)[exact[it.on]]
    if gaps.points is None or off.max(initial=0.0) <= TOLERANCE:
        it.rigid = (g0, a)
        return True
    gaps.points = None   # the circles' gaps left the exact ones: every point's measured
    g0, a, _ = gaps.settled(it)
    it.feet, it.g0, it.a = contact.feet[it.on], g0[it.on], a[it.on]
    return False


def _closed(model: RingModel, contact: RingContact, pressure: np.ndarray, g0: np.ndarray,
            elastic: np.ndarray | None = None
            ) -> tuple[np.ndarray, np.ndarray, tuple | None] | None:
    """The formed points' ``pressure`` (MPa) spread over every point, the gaps (mm) from the
    rigid gaps ``g0`` of every point (A p added on the formed points, ``elastic`` where it was
    formed before, the fields' approach on the others: :func:`~.influence.approach_open`) and
    each gear's clamped fields that check formed (None where every column is formed); None
    where a point left out closes."""
    on = np.flatnonzero(contact.formed)
    full = np.zeros(contact.npoints)
    full[on] = pressure
    gap = g0.copy()
    contact.ready(on[pressure != 0])
    gap[on] += loaded_product(contact.A, pressure) if elastic is None else elastic
    clamped = None
    if not contact.complete:
        rest = np.flatnonzero(~contact.formed)
        approach, clamped = approach_open(model, contact, full, rest)
        gap[rest] += approach
        if (gap[rest] < 0).any():
            return None
    return full, gap, clamped

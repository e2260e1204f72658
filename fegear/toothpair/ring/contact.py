"""The contact solve at one position: grid pressures p ≥ 0 and gaps g ≥ 0, complementary, with
the contact moments balancing the torque on gear 1 (load control); no penalty.

The gap of grid point i at gear 1's rotation θ (from its kinematic position) is
g_i = g_rigid,i(θ) + Σ_j A_ij p_j, the exact rigid gap to gear 2's curve plus the elastic
separation (:mod:`.influence`). Active-set iterations solve the linearised rigid gap with the
torque balance; the exact gap is then evaluated again at the new rotation until the rotation
settles (the rigid gap is nonlinear in θ only through the turn, a µrad here).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg

from ...errors import ContactError
from ...planar import rotate
from .circles import TOLERANCE, FootCircles, circle_gaps, moved
from .influence import RingContact, approach_open
from .master import Gear2Master
from .model import RingModel

MAX_ACTIVE_SET = 80     # active-set changes per linearisation
MAX_TURNS = 30          # linearisations of the rigid gap
MAX_PRIMAL = 4          # … and, by the primal method, this many per grid point
ARM_STEP = 1e-7         # turn (rad) of the torque arm's difference quotient


class RingContactError(ContactError):
    """The ring model's contact at one position has no solution the iterations could find."""


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


@dataclass(frozen=True)
class ContactSystem:
    """The contact's linear system at one linearisation of the rigid gap, over its points:
    ``A`` (mm/MPa) how far each point separates per unit pressure of each point's hat, ``w``
    (mm²) the force (N) per unit pressure of each hat (its weight ∫φ ds times the face
    width), ``g0`` (mm) the rigid gaps and ``a`` (mm/rad) their rate with gear 1's turn. With
    pressures p and a rotation step δ the gaps are g0 + a δ + A p, and −Σ w a p is the torque
    (N·mm) the pressures carry. ``rows``: the points' rows (and columns) of ``A`` where they
    are some of its points (None: all); ``blocks``: A's blocks for the active sets met so far
    (:func:`_block`), which a contact solve's linearisations share."""

    A: np.ndarray
    w: np.ndarray
    g0: np.ndarray
    a: np.ndarray
    rows: np.ndarray | None = None
    blocks: dict = field(default_factory=dict, repr=False, compare=False)


@dataclass(frozen=True)
class ActiveSet:
    """What an active-set method settled: the pressure per point (MPa, zero off the active
    set), the rotation step (rad), the active set (a mask over the points) and the
    iterations counted so far."""

    pressure: np.ndarray
    step: float
    active: np.ndarray
    iterations: int


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


def solve_ring_contact(model: RingModel, contact: RingContact, torque_nmm: float, theta: float,
                       guess: float | None = None, start: np.ndarray | None = None,
                       within: float | None = None, circles: FootCircles | None = None
                       ) -> RingContactSolution | None:
    """Solve the contact under ``torque_nmm`` (N·mm on gear 1) from the rotation ``theta``
    (rad); the iterations start from the points ``start`` (a mask over the points: where the
    position before carried pressure, say), else from those the rigid teeth overlap at the
    rotation ``guess`` (rad), else from the point of least gap. Where they start changes how
    many iterations the solve takes, not its solution. On a contact whose probe columns are
    not formed (:func:`~.influence.assemble_contact`), the points of the formed columns are
    solved and the others kept open; that is the solution if none of them then overlaps
    (their pressures zero, their columns act on nothing), else None: the caller forms them.
    ``within`` (mm): on a contact with every column formed, the iterations take only the
    points whose rigid gap at ``theta`` is within that of the least (a kept contact's wide
    grids, most of them far from closing); the others are checked at the solution, and where
    one overlaps the contact is solved again on every point. ``circles``: this contact's
    points' foot circles (:mod:`.circles`), which the iterations measure the gaps to instead
    of searching gear 2's curve; the last evaluation is exact, and where the two differ the
    iterations go on with the exact gaps."""
    alpha = model.case.params.ratio * contact.beta
    on = np.flatnonzero(contact.formed)
    feet = contact.feet[on]
    points = None if circles is None else moved(circles, model, contact)

    def gaps(turn: float, feet: np.ndarray, idx: np.ndarray):
        if points is None:
            return rigid_gap(model, contact, turn, feet, idx)
        return circle_gaps(circles, points, turn - alpha, idx)

    g0, a = gaps(alpha + theta, feet, on)
    rows, near, blocks = None, None, {}
    if within is not None and contact.complete and (g0 > g0.min() + within).any():
        near = g0 <= g0.min() + within
        rows = np.flatnonzero(near)
        on, feet, g0, a = on[near], feet[near], g0[near], a[near]
    w = contact.weight[on] * model.case.thickness
    active = g0 <= g0.min() + 1e-12
    if start is not None and start[on].any():
        active = start[on].copy()
    elif guess is not None:
        overlap = gaps(alpha + guess, feet.copy(), on)[0] < 0
        active = overlap if overlap.any() else active
    pressure = np.zeros(len(g0))
    total = turns = 0
    while True:
        # the torque's arm turns with gear 1: where gear 2 bends sharply (a pointed tip) the
        # rotation converged only linearly, half a digit a linearisation, without this term
        # (the loaded points' arms alone: the others carry nothing)
        loaded = np.flatnonzero(pressure)
        arm_rate = 0.0 if not len(loaded) else (w[loaded] * pressure[loaded]) @ (
            gaps(alpha + theta + ARM_STEP, feet[loaded], on[loaded])[1] - a[loaded]) / ARM_STEP
        found = active_set(ContactSystem(contact.A, w, g0, a, rows, blocks), torque_nmm,
                           active, arm_rate)
        pressure, active = found.pressure, found.active
        total += found.iterations
        turns += 1
        theta += found.step
        # settled to rounding: 1e-12 of the rotation, or a 1e-13 mm turn at the pitch circle
        settled = abs(found.step) <= max(1e-12 * abs(theta), 1e-13 / model.case.params.r0)
        if settled:   # the last evaluation at every point: the open ones' gaps are checked
            if points is None:
                contact.feet[on] = feet
            iterated = g0 + a * found.step   # the gaps the iterations settled on
            g0, a = rigid_gap(model, contact, alpha + theta, contact.feet)
            if points is None or np.abs(g0[on] - iterated).max() <= TOLERANCE:
                break
            # the circles' gaps left the exact ones: on with the exact gaps
            points, feet, g0, a = None, contact.feet[on], g0[on], a[on]
            continue
        g0, a = gaps(alpha + theta, feet, on)
        if turns == MAX_TURNS:
            raise RingContactError(f"the rotation did not settle in {MAX_TURNS} "
                                   "linearisations")
    balance = abs(-(w * pressure) @ a[on] - torque_nmm) / torque_nmm
    if near is not None:   # the points left out: the pressures act on them too
        pressure = np.zeros(len(near))
        pressure[near] = found.pressure
    closed = _closed(model, contact, pressure, g0)
    if closed is None:
        return None
    full, gap, clamped = closed
    if near is not None and (gap[~near] < 0).any():   # every column formed: near spans all
        return solve_ring_contact(model, contact, torque_nmm, theta, guess, start)
    loaded = full > 0
    overlap = float(max(0.0, -gap[loaded].min())) if loaded.any() else 0.0
    return RingContactSolution(full, gap, float(theta), total, turns, float(balance), overlap,
                               clamped, (g0, a))


def _closed(model: RingModel, contact: RingContact, pressure: np.ndarray, g0: np.ndarray
            ) -> tuple[np.ndarray, np.ndarray, tuple | None] | None:
    """The formed points' ``pressure`` (MPa) spread over every point, the gaps (mm) from the
    rigid gaps ``g0`` of every point (A p added on the formed points, the fields' approach on
    the others: :func:`~.influence.approach_open`) and each gear's clamped fields that check
    formed (None where every column is formed); None where a point left out closes."""
    on = np.flatnonzero(contact.formed)
    full = np.zeros(contact.npoints)
    full[on] = pressure
    gap = g0.copy()
    idx = np.flatnonzero(pressure)   # the loaded columns alone
    gap[on] += contact.A[:, idx] @ pressure[idx]
    clamped = None
    if not contact.complete:
        rest = np.flatnonzero(~contact.formed)
        approach, clamped = approach_open(model, contact, full, rest)
        gap[rest] += approach
        if (gap[rest] < 0).any():
            return None
    return full, gap, clamped


def active_set(system: ContactSystem, torque_nmm: float, active: np.ndarray,
               arm_rate: float = 0.0) -> ActiveSet:
    """Pressures on the active points and the rotation step with the gap linear in the step:
    A p + a δ = −g0 on the active points, −Σ w a p − ``arm_rate`` δ = T (``arm_rate``: the
    torque's rate with the turn at the last pressures, Σ w (da/dθ) p); from the points
    ``active``, points join when their gap closes and leave when their pressure pulls, all at
    once; where that cycles, :func:`primal_active_set` settles it."""
    seen = set()
    pressure = np.zeros(len(system.g0))
    for k in range(1, MAX_ACTIVE_SET + 1):
        pressure, step = _on(system, torque_nmm, active, arm_rate)
        gap = _gap(system, pressure, step, active)
        new = np.where(active, pressure > 0, gap < 0)
        if not new.any():
            new = gap <= gap.min()
        if np.array_equal(new, active):
            return ActiveSet(pressure, step, active, k)
        key = new.tobytes()
        if key in seen:   # it cycles: on by the primal method, which cannot
            break
        seen.add(key)
        active = new
    return primal_active_set(system, torque_nmm, pressure, arm_rate, k)


def _gap(system: ContactSystem, pressure: np.ndarray, step: float,
         active: np.ndarray) -> np.ndarray:
    """The gaps at the ``pressure`` (zero off ``active``) and rotation ``step``: A's active
    columns alone (a tenth of them on a phase's wide grids)."""
    idx, _, columns = _block(system, active)
    return system.g0 + system.a * step + pressure[idx] @ columns


def _on(system: ContactSystem, torque_nmm: float, active: np.ndarray,
        arm_rate: float) -> tuple[np.ndarray, float]:
    """Pressure (zero off ``active``) and rotation step with every active gap closed and the
    torque balanced: the bordered system A_aa p + a δ = −g0, (w a)·p + ``arm_rate`` δ = −T
    by its Schur complement on the active points' factorised block (:func:`_block`), which
    the linearisations after the first, on the same points, use again."""
    idx, factor, _ = _block(system, active)
    a, wa = system.a[idx], system.w[idx] * system.a[idx]
    free, per_step = scipy.linalg.lu_solve(factor, np.column_stack([-system.g0[idx], a])).T
    denominator = arm_rate - wa @ per_step
    step = (-torque_nmm - wa @ free) / denominator if denominator else math.inf
    if not math.isfinite(step) or not np.isfinite(free).all():
        raise RingContactError("the contact points cannot carry the torque")
    pressure = np.zeros(len(system.g0))
    pressure[idx] = free - per_step * step
    return pressure, step


#: active sets whose blocks a contact solve keeps (the last few: a linearisation's iterations
#: and the next one's start)
BLOCKS = 4


def _block(system: ContactSystem, active: np.ndarray) -> tuple[np.ndarray, tuple, np.ndarray]:
    """The ``active`` points (indices), their block of A factorised (LU) and A's columns of
    theirs over every point, as rows (active, points), kept in ``system.blocks`` for the
    solve's later linearisations. The columns are gathered from A once a point, when it
    first joins (the active sets of one solve differ by a few points)."""
    key = active.tobytes()
    if key not in system.blocks:
        idx = np.flatnonzero(active)
        columns = _columns(system, idx)
        with warnings.catch_warnings():   # a singular block: a non-finite solution, refused
            warnings.simplefilter("ignore", scipy.linalg.LinAlgWarning)
            factor = scipy.linalg.lu_factor(columns[:, idx].T, check_finite=False)
        if len(system.blocks) >= BLOCKS + 1:
            system.blocks.pop(next(k for k in system.blocks if k != "columns"))
        system.blocks[key] = (idx, factor, columns)
    return system.blocks[key]


def _columns(system: ContactSystem, idx: np.ndarray) -> np.ndarray:
    """A's columns of the points ``idx`` over the system's points, as rows (idx, points),
    from the ones gathered before (``system.blocks["columns"]``)."""
    n = len(system.g0)
    if "columns" not in system.blocks:   # rows a point, filled as points join (np.empty:
        system.blocks["columns"] = (np.empty((n, n)), np.zeros(n, bool))   # untouched pages
    store, filled = system.blocks["columns"]                              # cost nothing)
    new = idx[~filled[idx]]
    if len(new):
        rows = np.arange(n) if system.rows is None else system.rows
        store[new] = system.A[np.ix_(rows, rows[new])].T
        filled[new] = True
    return store[idx]


def _bordered(A, w, a, idx, arm_rate) -> np.ndarray:
    """The active points' system in (pressures, rotation step): their influence matrix
    bordered by the gap's rate with the turn and the torque row."""
    n = len(idx)
    M = np.empty((n + 1, n + 1))
    M[:n, :n] = A[np.ix_(idx, idx)]
    M[:n, n] = a[idx]
    M[n, :n] = w[idx] * a[idx]
    M[n, n] = arm_rate
    return M


def primal_active_set(system: ContactSystem, torque_nmm: float, start: np.ndarray,
                      arm_rate: float = 0.0, used: int = 0) -> ActiveSet:
    """The primal active-set method (after Lawson and Hanson's, with the torque row) where
    swapping every violated point at once cycles or does not settle (large loads on sharp
    teeth, where the teeth's near fields overlap): pressures stay ≥ 0 and the torque balanced
    throughout, so the energy falls at every step and no set comes back. From ``start`` (the
    fast method's last pressures, the pulling ones dropped and the rest scaled to the torque;
    else the closing point of least gap): the point of most overlap joins, one at a time (its
    pressure then rises from zero); a pressure that would pull stops the step where it reaches
    zero and leaves. Finite for a symmetric positive definite compliance (the ring's,
    collocated at the grid points, is close to one); bounded by MAX_PRIMAL steps a point.
    ``used``: the iterations spent before (the fast method's), counted on."""
    w, g0, a = system.w, system.g0, system.a
    pressure = np.maximum(start, 0.0)
    carried = -(w * pressure) @ a
    if carried > 0:
        pressure *= torque_nmm / carried
    else:
        closing = np.flatnonzero(a < 0)
        if len(closing) == 0:
            raise RingContactError("no contact point closes under the torque")
        first = closing[np.argmin(g0[closing])]
        pressure[:] = 0.0
        pressure[first] = -torque_nmm / (w[first] * a[first])
    step = 0.0
    active = pressure > 0
    tol = 1e-12 * max(float(np.abs(g0).max()), 1e-9)
    for k in range(used + 1, used + MAX_PRIMAL * len(g0) + 1):
        trial, trial_step = _on(system, torque_nmm, active, arm_rate)
        pulls = active & (trial <= 0)
        if not pulls.any():
            pressure, step = trial, trial_step
            gap = _gap(system, pressure, step, active)
            gap[active] = np.inf
            worst = int(np.argmin(gap))
            if gap[worst] >= -tol:
                return ActiveSet(pressure, step, active, k)
            active[worst] = True
            continue
        i = np.flatnonzero(pulls)
        share = float(np.min(pressure[i] / (pressure[i] - trial[i])))
        pressure += share * (trial - pressure)
        step += share * (trial_step - step)
        active &= pressure > 1e-14 * pressure.max()
        pressure[~active] = 0.0
    raise RingContactError(f"the active set did not settle in {k} iterations")


def tangent_stiffness(model: RingModel, contact: RingContact,
                      sol: RingContactSolution) -> float:
    """The tangent mesh stiffness dT/dθ (N·m/rad of gear-1 rotation) at the solved load, the
    active points kept: the same system :func:`_on` solves, differentiated in the torque (a
    linearised dynamic model's mesh spring; the secant T/(θ − θ_touch) is the static one). It
    is the slope of θ(T) between the loads at which a point joins or leaves the contact."""
    idx, system = solved_system(model, contact, sol)
    if not len(idx):
        return float("nan")
    rhs = np.zeros(len(idx) + 1)
    rhs[-1] = -1.0                     # one N·mm more on gear 1
    rate = np.linalg.solve(system, rhs)[-1]  # rad per N·mm
    return float(1e-3 / rate)


def solved_system(model: RingModel, contact: RingContact, sol: RingContactSolution
                  ) -> tuple[np.ndarray, np.ndarray]:
    """The solved contact's active points (indices) and the bordered system over them that
    :func:`_on` solves at the solution, the torque arm's turn included: the matrix whose
    solutions are the contact's derivatives with its active set kept (in the torque:
    :func:`tangent_stiffness`; in a deviation: :mod:`.sensitivity`). ``contact`` with its
    influence matrix."""
    alpha = model.case.params.ratio * contact.beta
    w = contact.weight * model.case.thickness
    idx = np.flatnonzero(sol.pressure > 0)
    if not len(idx):
        return idx, np.zeros((1, 1))
    _, a = rigid_gap(model, contact, alpha + sol.rotation, contact.feet)
    ahead = rigid_gap(model, contact, alpha + sol.rotation + ARM_STEP, contact.feet[idx],
                      idx)[1]
    arm_rate = (w[idx] * sol.pressure[idx]) @ (ahead - a[idx]) / ARM_STEP
    rows = (np.cumsum(contact.formed) - 1)[idx]     # the active points' rows of A
    return idx, _bordered(contact.A[np.ix_(rows, rows)], w[idx], a[idx],
                          np.arange(len(idx)), arm_rate)


def touch_rotation(model: RingModel, contact: RingContact, theta: float) -> float:
    """The rotation θ (rad) at which gear 1's rigid, rounded teeth first touch: the smallest
    closure over the grid points, repeated on the exact gaps."""
    alpha = model.case.params.ratio * contact.beta
    feet = contact.feet.copy()
    for _ in range(8):
        g0, a = rigid_gap(model, contact, alpha + theta, feet)
        closing = a < 0
        step = float(np.min(g0[closing] / -a[closing]))
        theta += step
        if abs(step) < 1e-14:
            break
    return theta

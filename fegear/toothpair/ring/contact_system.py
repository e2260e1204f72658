"""The contact's linear system at one linearisation of the rigid gap (:class:`ContactSystem`)
and the two active-set methods that step on it (:func:`active_set`, :func:`primal_active_set`),
which the contact solve (:mod:`.contact`) runs at each linearisation: the pressures and rotation
step that close an active set's gaps and balance the torque, the gaps they leave, and A's
blocks for the active sets met, factorised once and kept for the solve's later
linearisations."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
from scipy.linalg.lapack import dgetrf, dgetrs

from ...errors import ContactError

#: active sets whose blocks a contact solve keeps (the last few: a linearisation's iterations
#: and the next one's start)
BLOCKS = 4
MAX_ACTIVE_SET = 80     # active-set changes per linearisation
MAX_PRIMAL = 4          # … and, by the primal method, this many per grid point


class RingContactError(ContactError):
    """The ring model's contact at one position has no solution the iterations could find."""


@dataclass(frozen=True)
class ActiveSet:
    """What an active-set method settled: the pressure per point (MPa, zero off the active
    set), the rotation step (rad), the active set (a mask over the points) and the
    iterations counted so far."""

    pressure: np.ndarray
    step: float
    active: np.ndarray
    iterations: int


@dataclass(frozen=True)
class ContactSystem:
    """The contact's linear system at one linearisation of the rigid gap, over its points:
    ``A`` (mm/MPa) how far each point separates per unit pressure of each point's hat, ``w``
    (mm²) the force (N) per unit pressure of each hat (its weight ∫φ ds times the face
    width), ``g0`` (mm) the rigid gaps and ``a`` (mm/rad) their rate with gear 1's turn. With
    pressures p and a rotation step δ the gaps are g0 + a δ + A p, and −Σ w a p is the torque
    (N·mm) the pressures carry. ``rows``: the points' rows (and columns) of ``A`` where they
    are some of its points (None: all); ``blocks``: A's blocks for the active sets met so far
    (:func:`_block`), which a contact solve's linearisations share; ``form``: where A's
    columns are formed as they are read (:mod:`.lazy`), what forms those of the points
    given (A's columns, not the system's), before a block reads them."""

    A: np.ndarray
    w: np.ndarray
    g0: np.ndarray
    a: np.ndarray
    rows: np.ndarray | None = None
    blocks: dict = field(default_factory=dict, repr=False, compare=False)
    form: Callable[[np.ndarray], None] | None = field(default=None, repr=False, compare=False)


def solve_active(system: ContactSystem, torque_nmm: float, active: np.ndarray,
                 arm_rate: float) -> tuple[np.ndarray, float]:
    """Pressure (MPa, zero off ``active``) and rotation step (rad) with every active gap
    closed and the torque balanced: the bordered system A_aa p + a δ = −g0,
    (w a)·p + ``arm_rate`` δ = −T by its Schur complement on the active points' factorised
    block (:func:`_block`), which the linearisations after the first, on the same points, use
    again."""
    idx, (lu, piv), _ = _block(system, active)
    a, wa = system.a[idx], system.w[idx] * system.a[idx]
    rhs = np.column_stack([-system.g0[idx], a])
    # no active point: the rotation alone carries the torque (an empty block, which LAPACK
    # does not take)
    free, per_step = (dgetrs(lu, piv, rhs)[0] if len(idx) else rhs).T
    denominator = arm_rate - wa @ per_step
    step = (-torque_nmm - wa @ free) / denominator if denominator else math.inf
    if not math.isfinite(step) or not np.isfinite(free).all():
        raise RingContactError("the contact points cannot carry the torque")
    pressure = np.zeros(len(system.g0))
    pressure[idx] = free - per_step * step
    return pressure, step


def gaps_at(system: ContactSystem, pressure: np.ndarray, step: float,
            active: np.ndarray) -> np.ndarray:
    """The gaps (mm) at the ``pressure`` (MPa, zero off ``active``) and rotation ``step``
    (rad): A's columns of the points gathered so far (:class:`_Columns`; a tenth of them on
    a phase's wide grids), the inactive ones at zero pressure, in one product and no copy."""
    idx, _, slots = _block(system, active)
    store = _store(system)
    at = np.zeros(store.count)
    at[slots] = pressure[idx]
    return system.g0 + system.a * step + at @ store.rows[:store.count]


def loaded_product(A: np.ndarray, pressure: np.ndarray) -> np.ndarray:
    """A p over ``A``'s columns where ``pressure`` is not zero: one product a run of
    consecutive loaded columns, each a view of A kept by columns (a tooth's loaded points are
    one run), not a gathered copy of them all."""
    out = np.zeros(A.shape[0])
    for lo, hi in true_runs(pressure != 0):
        out += A[:, lo:hi] @ pressure[lo:hi]
    return out


def true_runs(mask: np.ndarray) -> list[tuple[int, int]]:
    """The runs [lo, hi) of consecutive True in ``mask``."""
    edges = np.flatnonzero(np.diff(np.concatenate([[0], mask.astype(np.int8), [0]])))
    return list(zip(edges[0::2].tolist(), edges[1::2].tolist()))


def _block(system: ContactSystem, active: np.ndarray) -> tuple[np.ndarray, tuple, np.ndarray]:
    """The ``active`` points (indices), their block of A factorised (LU) and their rows of
    the gathered columns (:class:`_Columns`), kept in ``system.blocks`` for the solve's later
    linearisations."""
    key = active.tobytes()
    if key not in system.blocks:
        idx = np.flatnonzero(active)
        store = _store(system)
        slots = store.gather(system, idx)
        # a gathered copy: the active columns of the rows gathered so far, then the active
        # rows (two plain gathers, not one of np.ix_: a third of the time), factorised by
        # LAPACK's getrf itself, without scipy's checks around it (the block is finite and
        # its own); a singular block gives a non-finite solution, which solve_active refuses
        block = np.take(store.rows[:store.count], idx, axis=1)[slots].T
        factor = dgetrf(block, overwrite_a=True)[:2] if len(idx) else (None, None)
        if len(system.blocks) >= BLOCKS + 1:
            system.blocks.pop(next(k for k in system.blocks if k != "columns"))
        system.blocks[key] = (idx, factor, slots)
    return system.blocks[key]


def _store(system: ContactSystem) -> _Columns:
    """The solve's gathered columns of A (``system.blocks["columns"]``), made empty the
    first time."""
    if "columns" not in system.blocks:
        system.blocks["columns"] = _Columns(len(system.g0))
    return system.blocks["columns"]


class _Columns:
    """A's columns of the points that have been active in a solve, over the system's points,
    each a row (``rows[:count]``) in the order the points first joined (``slot``: each point's
    row, −1 before it joins). Gathered once a point, as it joins: a solve's active sets differ
    by a few points. Each new column is read where it lies (A is kept by columns), a run of
    the system's consecutive points at a time (``runs``: a kept contact's points near closing
    are a few runs of its grids, a third of its points), and written as a row."""

    def __init__(self, n: int) -> None:
        self.slot = np.full(n, -1)
        self.rows = np.empty((0, n))
        self.count = 0
        self.runs: list[tuple[int, int, int]] | None = None   # (A's first, last + 1, here)

    def gather(self, system: ContactSystem, idx: np.ndarray) -> np.ndarray:
        """The rows of the points ``idx``, gathered from A where they are new."""
        new = idx[self.slot[idx] < 0]
        if len(new):
            end = self.count + len(new)
            if end > len(self.rows):   # room for twice as many (np.empty: untouched pages
                grown = np.empty((max(2 * end, 64), self.slot.size))   # cost nothing)
                grown[:self.count] = self.rows[:self.count]
                self.rows = grown
            rows = np.arange(self.slot.size) if system.rows is None else system.rows
            if self.runs is None:
                breaks = np.flatnonzero(np.diff(rows) != 1) + 1
                self.runs = [(int(rows[lo]), int(rows[hi - 1]) + 1, int(lo)) for lo, hi in
                             zip(np.r_[0, breaks], np.r_[breaks, len(rows)])]
            if system.form is not None:
                system.form(rows[new])
            columns, out, at = system.A.T, self.rows[self.count:end], rows[new]
            for first, last, here in self.runs:
                out[:, here:here + last - first] = columns[at, first:last]
            self.slot[new] = np.arange(self.count, end)
            self.count = end
        return self.slot[idx]


def active_set(system: ContactSystem, torque_nmm: float, active: np.ndarray,
               arm_rate: float = 0.0, join: float = 0.0) -> ActiveSet:
    """Pressures on the active points and the rotation step with the gap linear in the step:
    A p + a δ = −g0 on the active points, −Σ w a p − ``arm_rate`` δ = T (``arm_rate``: the
    torque's rate with the turn at the last pressures, Σ w (da/dθ) p); from the points
    ``active``, points join when their gap closes and leave when their pressure pulls, all at
    once; where that cycles, :func:`primal_active_set` settles it. ``join``: where points
    overlap, only those that overlap by more than this share of the largest overlap join at
    a step (0: every one that overlaps): from a set far from the one it settles on, the method joins
    every overlapping point, twice what it keeps, and sheds the surplus a few points a step;
    the deepest overlap always joins, and once none overlaps the set is settled as before."""
    seen = set()
    pressure = np.zeros(len(system.g0))
    for k in range(1, MAX_ACTIVE_SET + 1):
        pressure, step = solve_active(system, torque_nmm, active, arm_rate)
        gap = gaps_at(system, pressure, step, active)
        least = gap.min()
        new = np.where(active, pressure > 0, gap < (join * least if least < 0 else 0.0))
        if not new.any():
            new = gap <= least
        if np.array_equal(new, active):
            return ActiveSet(pressure, step, active, k)
        key = new.tobytes()
        if key in seen:   # it cycles: on by the primal method, which cannot
            break
        seen.add(key)
        active = new
    return primal_active_set(system, torque_nmm, pressure, arm_rate, k)


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
        trial, trial_step = solve_active(system, torque_nmm, active, arm_rate)
        pulls = active & (trial <= 0)
        if not pulls.any():
            pressure, step = trial, trial_step
            gap = gaps_at(system, pressure, step, active)
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

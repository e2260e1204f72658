"""The contact's linear system at one linearisation of the rigid gap (:class:`ContactSystem`),
which both active-set methods of the contact solve (:mod:`.contact`) step on: the pressures and
rotation step that close an active set's gaps and balance the torque, the gaps they leave, and
A's blocks for the active sets met, factorised once and kept for the solve's later
linearisations."""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg

from ...errors import ContactError

#: active sets whose blocks a contact solve keeps (the last few: a linearisation's iterations
#: and the next one's start)
BLOCKS = 4


class RingContactError(ContactError):
    """The ring model's contact at one position has no solution the iterations could find."""


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


def solve_active(system: ContactSystem, torque_nmm: float, active: np.ndarray,
                 arm_rate: float) -> tuple[np.ndarray, float]:
    """Pressure (MPa, zero off ``active``) and rotation step (rad) with every active gap
    closed and the torque balanced: the bordered system A_aa p + a δ = −g0,
    (w a)·p + ``arm_rate`` δ = −T by its Schur complement on the active points' factorised
    block (:func:`_block`), which the linearisations after the first, on the same points, use
    again."""
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
        with warnings.catch_warnings():   # a singular block: a non-finite solution, refused
            warnings.simplefilter("ignore", scipy.linalg.LinAlgWarning)
            # a gathered copy: the active columns of the rows gathered so far, then the active
            # rows (two plain gathers, not one of np.ix_: a third of the time)
            block = np.take(store.rows[:store.count], idx, axis=1)[slots].T
            factor = scipy.linalg.lu_factor(block, overwrite_a=True, check_finite=False)
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
    by a few points. Gathering from A's transpose reads each column where it lies (A is kept
    by columns) and writes each row whole."""

    def __init__(self, n: int) -> None:
        self.slot = np.full(n, -1)
        self.rows = np.empty((0, n))
        self.count = 0

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
            # the new points' rows of A's transpose whole, then the system's columns of them
            # (two plain gathers, not one of np.ix_: less than half the time)
            np.take(system.A.T[rows[new]], rows, axis=1, out=self.rows[self.count:end])
            self.slot[new] = np.arange(self.count, end)
            self.count = end
        return self.slot[idx]

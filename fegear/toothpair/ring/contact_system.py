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
    (rad): A's active columns alone (a tenth of them on a phase's wide grids)."""
    idx, _, columns = _block(system, active)
    return system.g0 + system.a * step + pressure[idx] @ columns


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

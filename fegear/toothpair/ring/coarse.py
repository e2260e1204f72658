"""A kept contact's coarse level: where a solve on it starts (:class:`CoarseContact`).

A solve on a kept contact (a tolerance class's sample, a revolution's deviated pitch) started
from the points that carried pressure where the contact was kept, at its rotation. Its
deviations of a few µm move the loaded zones and load other teeth, so the active-set method's
first linearisation went through several active sets, each a new factorisation of A's block
on a few hundred points. Here every grid's every :data:`STRIDE`-th point (and its last)
carries a coarse hat, the fine hats' pressures interpolated linearly between them (``P``),
and the coarse compliance is A sampled at the coarse points under those pressures,
A_c = A[coarse] P, formed once a kept contact. The contact solved on the coarse level (one
linearisation about the kept rotation) predicts the points that carry pressure and the
rotation; the fine solve starts there and settles the same solution by its own iterations:
the prediction changes where they start, never what they settle on.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import scipy.sparse

from ...errors import ContactError
from .contact_system import ContactSystem, active_set
from .influence import RingContact

#: every this many of a grid's points carries a coarse hat (and the grid's last): coarse
#: blocks half the fine ones' size, an eighth of their factorisation
STRIDE = 2
#: A's columns a coarse level is formed from at a time (:func:`_sampled`)
CHUNK = 256
#: where the coarse points overlap, those that overlap by more than this share of the largest
#: overlap join the coarse level's active set at a step (``join`` of
#: :func:`~.contact_system.active_set`): from the exact pair's set a sample's first step
#: joined about twice the points it settles on
JOIN = 0.5
#: a kept contact forms its coarse level at its this-many-th solve (:class:`CoarseLevels`):
#: the level costs about ten solves' savings to form, and a deviated pair's revolution
#: solves a phase's contact only a few times
AFTER = 8


@dataclass(frozen=True)
class CoarseContact:
    """A kept contact's coarse level: the coarse points (``pick``: indices among the
    contact's points, every grid's every :data:`STRIDE`-th and its last), the fine hats'
    pressures per unit pressure of each coarse hat (``P``, sparse, points × coarse points:
    linear between coarse points in arc length), the gaps at the coarse points per unit
    coarse pressure (``A``, mm/MPa, A[pick] P) and each coarse hat's force per unit pressure
    (``w``, mm², Pᵀ w of the fine hats'); ``form``: where the kept contact forms its A's
    columns as they are read (:mod:`.lazy`), what forms the coarse columns given from them
    (:class:`_Columns`)."""

    pick: np.ndarray
    P: scipy.sparse.csr_matrix
    A: np.ndarray
    w: np.ndarray
    form: Callable[[np.ndarray], None] | None = None

    def predict(self, g0: np.ndarray, a: np.ndarray, torque_nmm: float,
                start: np.ndarray | None, within: float | None
                ) -> tuple[np.ndarray, float] | None:
        """The points (a mask over the contact's) that carry pressure and gear 1's rotation
        step (rad) where the contact is solved on the coarse level with the coarse points'
        rigid gaps ``g0`` (mm) and their rates ``a`` (mm/rad) linearised about one rotation,
        under ``torque_nmm`` (N·mm), from the points ``start`` (a mask over the contact's;
        None or none of the coarse ones: the point of least gap), on the coarse points within
        ``within`` (mm) of the least gap (None: all); None where the coarse points cannot
        carry the torque. The torque's arm is taken at each coarse point (its hat's force
        times the point's rate): a prediction, which the fine solve corrects."""
        near = np.arange(len(g0)) if within is None else np.flatnonzero(g0 <= g0.min() + within)
        first = None if start is None else start[self.pick][near]
        if first is None or not first.any():
            first = g0[near] <= g0[near].min()
        system = ContactSystem(self.A, self.w[near], g0[near], a[near], near, form=self.form)
        try:
            found = active_set(system, torque_nmm, first, join=JOIN)
        except ContactError:
            return None
        pressure = np.zeros(len(self.pick))
        pressure[near] = found.pressure
        return self.P @ pressure > 0, found.step


class CoarseLevels(dict):
    """The coarse levels of the contacts kept by phase (phase → :class:`CoarseContact`, or
    how many solves it has had before it forms one)."""

    def level(self, phase: int, contact: RingContact, thickness: float
              ) -> CoarseContact | None:
        """The coarse level of ``contact``, kept for ``phase`` with the face width
        ``thickness`` (mm): formed at its :data:`AFTER`-th solve, None before."""
        level = self.get(phase, 0)
        if isinstance(level, int):
            if level + 1 < AFTER:
                self[phase] = level + 1
                return None
            level = self[phase] = coarse_contact(contact, thickness)
        return level


def coarse_contact(contact: RingContact, thickness: float) -> CoarseContact:
    """The coarse level (:class:`CoarseContact`) of ``contact``, whose A spans every point (a
    kept contact), with the face width ``thickness`` (mm): its columns formed where they are
    read where the kept contact's are (:mod:`.lazy`)."""
    rows, cols, values, pick = [], [], [], []
    first = 0   # the grid's first coarse point's number
    for k, grid in enumerate(contact.grids):
        start, n = int(contact.offsets[k]), len(grid)
        local = np.unique(np.append(np.arange(0, n, STRIDE), n - 1))
        pick.append(start + local)
        if n == 1:
            rows.append([start])
            cols.append([first])
            values.append([1.0])
            first += 1
            continue
        # each fine point between the coarse points m and m + 1 (the last one's on m + 1)
        m = np.minimum(np.searchsorted(local, np.arange(n), side="right") - 1, len(local) - 2)
        s = grid.s
        t = (s - s[local[m]]) / (s[local[m + 1]] - s[local[m]])
        rows.append(np.repeat(start + np.arange(n), 2))
        cols.append(np.column_stack([first + m, first + m + 1]).ravel())
        values.append(np.column_stack([1.0 - t, t]).ravel())
        first += len(local)
    pick = np.concatenate(pick)
    P = scipy.sparse.csr_matrix((np.concatenate(values), (np.concatenate(rows),
                                                           np.concatenate(cols))),
                                shape=(contact.npoints, len(pick)))
    w = P.T @ (contact.weight * thickness)
    if contact.former is None:
        return CoarseContact(pick, P, _sampled(contact.A, pick, P), w)
    columns = _Columns(contact, pick, P)
    return CoarseContact(pick, P, columns.A, w, columns)


class _Columns:
    """A_c's columns formed where they are read, as the kept contact's A is
    (:mod:`.lazy`): a coarse hat's column from the fine columns under it, those formed
    first."""

    def __init__(self, contact: RingContact, pick: np.ndarray, P: scipy.sparse.csr_matrix):
        self.contact, self.pick, self.P = contact, pick, P.tocsc()
        self.A = np.empty((len(pick), P.shape[1]), order="F")
        self.formed = np.zeros(P.shape[1], bool)

    def __call__(self, coarse: np.ndarray) -> None:
        """Form A_c's columns of the ``coarse`` points (indices) where they are not yet."""
        new = np.unique(coarse[~self.formed[coarse]])
        if not len(new):
            return
        part = self.P[:, new]
        fine = np.unique(part.indices)
        self.contact.ready(fine)
        # the fine columns' rows at the coarse points gathered alone (not every row first),
        # times the coarse hats' few fine weights as the sparse matrix they are
        rows = self.contact.A[np.ix_(self.pick, fine)]
        self.A[:, new] = (part[fine].T @ rows.T).T
        self.formed[new] = True


def _sampled(A: np.ndarray, pick: np.ndarray, P: scipy.sparse.csr_matrix) -> np.ndarray:
    """A[pick] P, a run of :data:`CHUNK` of A's columns at a time (A is kept by columns):
    the rows gathered whole would be a large array on fresh pages."""
    out = np.zeros((len(pick), P.shape[1]), order="F")
    for lo in range(0, A.shape[1], CHUNK):
        part = P[lo:lo + CHUNK]
        first, last = part.indices.min(), part.indices.max() + 1   # the coarse hats it makes
        out[:, first:last] += (part[:, first:last].T @ A[pick, lo:lo + CHUNK].T).T
    return out

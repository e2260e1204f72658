"""A kept contact's influence matrix formed where it is read (:class:`LazyColumns`).

A contact kept for a phase (:mod:`.phases`) has grids wide enough for every deviation set
solved on it, so its A is large and most of it is never read (docs/tolerance.md): a solve
reads A's columns only at the points that join one of its active sets (or carry
pressure), over the points it iterates on. Each column of A is the same product whichever
others are formed (the finite-element part N Ψ W(t − k) ρ of every sector of points under
one hat's loads, plus its grid's half-plane near field), so A is formed a run of
:data:`CHUNK` points at a time (whole columns, every row), where a solve first asks for one
of them (:meth:`~.influence.RingContact.ready`): the same numbers as formed whole, for the
columns read. The matching points' rows of each gear's fields, which every run's products
take, are formed once.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ...contact import hat_columns
from .influence import RingContact, add_fe_part, matching_rows
from .model import RingModel
from .side import LoadBlock

#: points a run of A's columns is formed for at a time (a grid's runs do not cross its end):
#: a solve's active set grows by a few points at a time, and a whole grid is a coarser unit
#: than the columns the solves read
CHUNK = 24


class LazyColumns:
    """A's columns of a contact (every point's hat), formed a run of :data:`CHUNK` points at a
    time where they are asked for (:meth:`__call__`), into ``A`` (n × n, by columns): the
    pages of a run never formed are never touched."""

    def __init__(self, model: RingModel, contact: RingContact) -> None:
        self.model = model
        self.grids, self.loads, self.matching = contact.grids, contact.loads, contact.matching
        n = contact.npoints
        self.A = np.empty((n, n), order="F")
        starts = [np.arange(contact.offsets[k], contact.offsets[k + 1], CHUNK)
                  for k in range(len(contact.grids))]
        self.starts = np.concatenate(starts)                         # each run's first point
        self.ends = np.concatenate([np.append(s[1:], contact.offsets[k + 1])
                                    for k, s in enumerate(starts)])   # … and its end
        self.grid = np.repeat(np.arange(len(starts)), [len(s) for s in starts])   # its grid
        self.offsets = contact.offsets
        self.run = np.repeat(np.arange(len(self.starts)), self.ends - self.starts)
        self.formed = np.zeros(len(self.starts), bool)
        self.place = np.arange(n)
        self._rows: list | None = None

    def __call__(self, points: np.ndarray) -> None:
        """Form A's columns of the runs that hold ``points`` (indices) where they are not yet."""
        runs = np.unique(self.run[points])
        runs = runs[~self.formed[runs]]
        if not len(runs):
            return
        columns = np.zeros(len(self.place), bool)
        for r in runs:
            columns[self.starts[r]:self.ends[r]] = True
        self.A[:, columns] = 0.0
        if self._rows is None:
            self._rows = [matching_rows(side, m)
                          for side, m in zip(self.model.gears, self.matching)]
        for side, loads, m, fields in zip(self.model.gears, self.loads, self.matching,
                                          self._rows):
            add_fe_part(side, _restricted(loads, columns), m, self.place, self.A, fields)
        for r in runs:
            self._near_field(r)
        self.formed[runs] = True

    def _near_field(self, r: int) -> None:
        """Add the half-plane's near field of run ``r``'s hats on its grid (zero between
        grids): each hat's two intervals, over the grid's points."""
        k = self.grid[r]
        g, start = self.grids[k], int(self.offsets[k])
        lo, hi = int(self.starts[r]) - start, int(self.ends[r]) - start
        case = self.model.case
        block = slice(start, int(self.offsets[k + 1]))
        for m in self.matching:
            self.A[block, start + lo:start + hi] += hat_columns(
                g.s, m.depth[block], g.s, lo, hi, case.E, case.nu)


def _restricted(loads: dict[int, LoadBlock], columns: np.ndarray) -> dict[int, LoadBlock]:
    """The sectors' loads of the hats ``columns`` (a mask over the points) alone, each on
    the template dofs those hats load."""
    out = {}
    for t, blk in loads.items():
        sel = columns[blk.columns]
        if not sel.any():
            continue
        matrix = blk.matrix[:, sel]
        used = np.flatnonzero(np.any(matrix != 0.0, axis=1))
        out[t] = LoadBlock(blk.dofs[used], blk.columns[sel], matrix[used])
    return out


def with_lazy_columns(model: RingModel, contact: RingContact) -> RingContact:
    """``contact`` (assembled without A, every point formed) with A formed where it is read
    (:class:`LazyColumns`)."""
    former = LazyColumns(model, contact)
    return replace(contact, A=former.A, former=former)

"""The nodal flexibility of a body on a window of its nodes, formed a row at a time with the
body's one factorisation."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ..timing import timed
from .dofs import node_dofs

if TYPE_CHECKING:
    from .assembly import Body

#: right-hand sides per SuperLU solve in :class:`WindowFlexibility`: 64 ran 13.3 ms per column
#: on a 155k-dof gear body, against 17.2 ms for 16 and for 256 (2 cores)
FLEX_CHUNK = 64


class WindowFlexibility:
    """F = E K⁻¹ Eᵀ (mm/N) for the x, y dofs of a node window (2n × 2n, node-major), formed a
    row at a time: row c (= column c, F is symmetric) is the window's response to a unit load
    at dof c, one solve with the body's factor. A contact only ever asks for the dofs under
    its loaded points, so most rows are never formed. Rows of supported dofs are zero."""

    def __init__(self, body: Body, nodes: np.ndarray):
        self._body = body
        dofs = node_dofs(nodes).ravel()
        pos = np.minimum(np.searchsorted(body.free, dofs), len(body.free) - 1)
        self._is_free = body.free[pos] == dofs
        self._free_pos = np.where(self._is_free, pos, -1)
        self._F = np.empty((len(dofs), len(dofs)))  # pages are committed as rows are written
        self._have = np.zeros(len(dofs), dtype=bool)

    @property
    def size(self) -> int:
        return len(self._have)

    @property
    def formed(self) -> int:
        """Rows formed so far."""
        return int(self._have.sum())

    def rows(self, c: np.ndarray) -> np.ndarray:
        """F[c], (len(c), 2n), forming the missing rows with solves of ``FLEX_CHUNK`` loads."""
        c = np.asarray(c, dtype=np.int64)
        missing = np.unique(c[~self._have[c]])
        if len(missing):
            with timed("condense"):
                self._form(missing)
        return self._F[c]

    def _form(self, missing: np.ndarray) -> None:
        body, free = self._body, self._is_free
        self._F[missing[~free[missing]]] = 0.0
        loaded = missing[free[missing]]
        for start in range(0, len(loaded), FLEX_CHUNK):
            cols = loaded[start:start + FLEX_CHUNK]
            rhs = np.zeros((len(body.free), len(cols)))
            rhs[self._free_pos[cols], np.arange(len(cols))] = 1.0
            response = body.factor.solve(rhs)
            block = np.zeros((len(cols), self.size))
            block[:, free] = response[self._free_pos[free]].T
            self._F[cols] = block
        self._have[missing] = True

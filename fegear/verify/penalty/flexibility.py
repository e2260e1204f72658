"""The flexibility of the contact points, formed a column at a time as the active set first
reaches a point."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import scipy.sparse as sp

from ...fe import WindowFlexibility
from ...timing import timed


class PointFlexibility:
    """G = Σ_b C_b F_b C_bᵀ (n × n, mm/N), the flexibility of the contact points, with F_b the
    body's nodal flexibility on its contact boundaries (:class:`WindowFlexibility`) and C_b
    the weighted-gap rows over them.

    Only the columns of points that carry a force are ever used (G λ and G_AA on the active
    set), so a column is formed when first asked for and kept: column j needs the rows of F_b
    at the dofs of row j of C_b, and those are formed (one solve each) only then, once per
    body frame, whichever position first asks. Forming columns is the stage "condense" of a
    solve's times."""

    def __init__(self, parts: Sequence[tuple[sp.csr_matrix, WindowFlexibility]], n: int):
        self._parts = tuple(parts)  # (C_b over the window's dofs, F_b)
        self.shape = (n, n)
        self._slot = np.full(n, -1, dtype=np.int64)
        self._columns = np.empty((n, 0))

    def columns(self, idx) -> np.ndarray:
        """G[:, idx], (n, len(idx))."""
        idx = np.asarray(idx, dtype=np.int64)
        new = np.unique(idx[self._slot[idx] < 0])
        if len(new):
            with timed("condense"):
                block = np.zeros((self.shape[0], len(new)))
                for C, F in self._parts:
                    rows = C[new]
                    dofs = np.unique(rows.indices)
                    X = rows[:, dofs] @ F.rows(dofs)  # C[new] F, with F symmetric
                    block += C @ np.ascontiguousarray(X.T)
                self._slot[new] = self._columns.shape[1] + np.arange(len(new))
                self._columns = np.hstack([self._columns, block])
        return self._columns[:, self._slot[idx]]

    @property
    def formed(self) -> int:
        """Columns formed so far."""
        return int(np.count_nonzero(self._slot >= 0))

    def block(self, idx) -> np.ndarray:
        """G[idx][:, idx]."""
        return self.columns(idx)[idx]

    def toarray(self) -> np.ndarray:
        return self.columns(np.arange(self.shape[0]))

    def __matmul__(self, v: np.ndarray) -> np.ndarray:
        nz = np.flatnonzero(v)
        return self.columns(nz) @ v[nz]

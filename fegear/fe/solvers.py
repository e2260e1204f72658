"""Sparse symmetric positive-definite factorisation, and solves with many right-hand sides.

CHOLMOD (supernodal Cholesky, through the ``cholespy`` wheel) solves a block of right-hand
sides with dense kernels: on a 20k-dof P2 body it factors in about half SuperLU's time and
solves a column several times faster. SuperLU (scipy) stands in where cholespy cannot be
imported.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ..errors import FegearError

#: BLAS threads while a solve runs. The dense products and solves here are of a few thousand
#: rows: OpenBLAS's threads cost more than they give, and with a second process on the two
#: cores (a study's other worker) they spin against each other: a cycle beside another job ran
#: seven times slower with two threads than with one
BLAS_THREADS = 1
#: right-hand sides a CHOLMOD solve takes at once: its workspace, the block and the solution
#: are then a few MB that stay in cache and are allocated once, where 476 columns on gear 1's
#: 12 560-dof template made three blocks of 48 MB each, faulted in page by page: half the time
#: again in blocks of 64
CHUNK = 64


def blas_threads(limit: int = BLAS_THREADS):
    """A context in which numpy's and scipy's BLAS use at most ``limit`` threads
    (threadpoolctl: it reaches the libraries already loaded, whatever the environment said)."""
    from threadpoolctl import threadpool_limits

    return threadpool_limits(limits=limit, user_api="blas")


class SingularError(FegearError):
    """The matrix is not positive definite: the body is not held."""


class Factor:
    """A factorisation of a sparse SPD matrix: ``solve(B)`` for B of shape (n,) or (n, k)."""

    def __init__(self, K: sp.spmatrix) -> None:
        K = sp.csc_matrix(K)
        self.n = K.shape[0]
        self.backend = "cholmod"
        try:
            from cholespy import CholeskySolverD, MatrixType
        except ImportError:  # pragma: no cover - the wheel is a dependency
            self._superlu(K)
            return
        lower = sp.tril(K).tocoo()
        full = (lower + sp.triu(lower.T, 1)).tocoo()  # symmetric by construction
        try:
            self._chol = CholeskySolverD(self.n, full.row.astype(np.int32),
                                         full.col.astype(np.int32), full.data.astype(np.float64),
                                         MatrixType.COO)
        except (RuntimeError, ValueError) as exc:
            raise SingularError(f"the stiffness is not positive definite ({exc})") from None

    def _superlu(self, K: sp.csc_matrix) -> None:
        from scipy.sparse.linalg import splu

        self.backend = "superlu"
        try:
            self._lu = splu(K, permc_spec="COLAMD")
        except RuntimeError as exc:
            raise SingularError(f"the stiffness is singular ({exc})") from None

    def solve(self, B: np.ndarray) -> np.ndarray:
        B = np.asarray(B, dtype=np.float64)
        if self.backend == "superlu":
            return self._lu.solve(np.ascontiguousarray(B))
        if B.ndim == 1 or B.shape[1] <= CHUNK:
            B = np.ascontiguousarray(B)
            X = np.empty_like(B)
            self._chol.solve(B, X)
            return X
        X = np.empty(B.shape)
        out = np.empty((self.n, CHUNK))
        for start in range(0, B.shape[1], CHUNK):
            rhs = np.ascontiguousarray(B[:, start:start + CHUNK])
            if rhs.shape != out.shape:
                out = np.empty_like(rhs)
            self._chol.solve(rhs, out)
            X[:, start:start + rhs.shape[1]] = out
        return X

    def unit_solve(self, rows: np.ndarray) -> np.ndarray:
        """The solution (n, len(rows)) for a unit right-hand side at each of ``rows`` (−1: a
        zero column), in blocks of :data:`CHUNK` columns: no dense block of unit columns."""
        rows = np.asarray(rows)
        X = np.empty((self.n, len(rows)))
        for start in range(0, len(rows), CHUNK):
            part = rows[start:start + CHUNK]
            rhs = np.zeros((self.n, len(part)))
            rhs[part[part >= 0], np.flatnonzero(part >= 0)] = 1.0
            X[:, start:start + len(part)] = self.solve(rhs)
        return X

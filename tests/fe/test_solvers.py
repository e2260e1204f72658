"""The sparse factorisation (fe/solvers.py): a block of right-hand sides wider than CHUNK is
solved in pieces with the same numbers as column by column, and unit right-hand sides by row
index give the columns of the inverse."""

import numpy as np
import scipy.sparse as sp

from fegear.fe import Factor
from fegear.fe.solvers import CHUNK


def _spd(n: int = 400, seed: int = 3) -> sp.csc_matrix:
    """A sparse symmetric positive-definite matrix: a 2D Laplacian plus a random coupling."""
    side = int(np.sqrt(n))
    lap = sp.diags([-1.0, 2.0, -1.0], [-1, 0, 1], shape=(side, side))
    eye = sp.identity(side)
    K = sp.kron(lap, eye) + sp.kron(eye, lap) + 0.01 * sp.identity(side * side)
    rng = np.random.default_rng(seed)
    R = sp.random(side * side, side * side, density=0.002, random_state=rng)
    return sp.csc_matrix(K + 0.1 * (R @ R.T))


def test_a_wide_block_is_solved_in_pieces_as_column_by_column():
    K = _spd()
    factor = Factor(K)
    B = np.random.default_rng(5).normal(size=(K.shape[0], 2 * CHUNK + 7))
    X = factor.solve(B)
    one = np.column_stack([factor.solve(B[:, j]) for j in range(B.shape[1])])
    assert np.abs(X - one).max() <= 1e-12 * np.abs(one).max()
    assert np.abs(K @ X - B).max() <= 1e-9 * np.abs(B).max()


def test_unit_columns_by_row_are_the_inverse_s_columns():
    K = _spd()
    factor = Factor(K)
    rows = np.array([5, -1, 17, *range(100, 100 + CHUNK + 3)])
    X = factor.unit_solve(rows)
    E = np.zeros((K.shape[0], len(rows)))
    E[rows[rows >= 0], np.flatnonzero(rows >= 0)] = 1.0
    assert np.abs(X - factor.solve(E)).max() <= 1e-12 * np.abs(X).max()
    assert not X[:, 1].any()   # −1: a zero column

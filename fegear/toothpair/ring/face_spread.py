"""The finite-element part of the face's operator: A_fe's blocks between the contact's grids,
each spread across the face as the coupling spreads a load between their teeth
(:class:`~.face.FaceCoupling`: the tooth's own spread S on a grid's own block, ``between(d)``
on a block between teeth d apart).

The spreads between teeth are taken in a low-rank form shared by every distance,
X_d = L C_d Rᵀ (L and R orthonormal, N × r; the product's are an even load and a tilt, r = 2),
so that their part of a product with the pressures P (points × sections) is
Σ_d F_d P R C_dᵀ Lᵀ: one product of a matrix formed once per set of points (the blocks F_d
weighted by C_d, r² blocks of the points' size) with P R, instead of a product of every
block with its own spread. The tooth's own blocks take S one grid at a time.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from .face import FaceCoupling

#: singular values below this share of the largest are dropped from the spreads' common bases
RANK_TOL = 1e-12


class FaceSpread:
    """How A_fe's blocks between the grids (of gear 1's ``teeth``, z1 of them) spread across
    the face under ``coupling``: one spread for all where it sets no ``across``."""

    def __init__(self, coupling: FaceCoupling, teeth: list[int], z1: int) -> None:
        self.own = coupling.spread
        self.single = coupling.across is None
        if self.single:
            return
        apart = np.array([[min((a - b) % z1, (b - a) % z1) for b in teeth] for a in teeth])
        spreads = [coupling.between(d) for d in range(1, max(apart.max(), 1) + 1)]
        self.left = _basis(np.hstack(spreads))
        self.right = _basis(np.hstack([x.T for x in spreads]))
        # C_d: the spread between grids i and j is L C[i, j] Rᵀ (zero on the own blocks)
        small = np.stack([self.left.T @ x @ self.right for x in spreads])
        self.small = np.where((apart > 0)[:, :, None, None],
                              small[np.maximum(apart, 1) - 1], 0.0)

    def on_points(self, far: np.ndarray, grids: list[slice]) -> Callable:
        """P ↦ the finite-element part's approach (points × sections) on a set of points
        under their pressures P (points × sections): ``far`` its A_fe (points × points),
        ``grids`` each grid's slice of the points (the grids of :attr:`small` in order,
        None where a grid has no point)."""
        own = self.own
        if self.single:
            return lambda p: far @ (p @ own.T)
        blocks = [(g, np.ascontiguousarray(far[g, g])) for g in grids if g is not None]
        r_left, r_right = self.left.shape[1], self.right.shape[1]
        n = len(far)
        weighted = np.zeros((r_left, n, r_right, n))
        for i, gi in enumerate(grids):
            for j, gj in enumerate(grids):
                if gi is not None and gj is not None and i != j:
                    weighted[:, gi, :, gj] = (self.small[i, j][:, None, :, None]
                                              * far[gi, gj][None, :, None, :])
        weighted = weighted.reshape(r_left * n, r_right * n)
        left, right = self.left, self.right

        def times(p: np.ndarray) -> np.ndarray:
            u = (weighted @ (p @ right).T.ravel()).reshape(r_left, n).T @ left.T
            for g, block in blocks:
                u[g] += block @ (p[g] @ own.T)
            return u
        return times

    def approach(self, p: np.ndarray, sources: list[slice], far_rows: np.ndarray,
                 targets: list[slice]) -> np.ndarray:
        """The finite-element part's approach (sections × points) at every point under the
        pressures ``p`` (loaded points × sections): ``far_rows`` the loaded points' rows of
        A_feᵀ (loaded × every point), ``sources`` each grid's slice of the loaded points (None
        where it has none) and ``targets`` its slice of every point."""
        if self.single:
            return (self.own @ p.T) @ far_rows
        u = np.zeros((len(self.own), far_rows.shape[1]))
        reach = [None if s is None else (p[s] @ self.right).T @ far_rows[s] for s in sources]
        for s, t in zip(sources, targets):
            if s is not None:
                u[:, t] += (self.own @ p[s].T) @ far_rows[s, t]
        for i, t in enumerate(targets):
            mixed = np.zeros((self.left.shape[1], t.stop - t.start))
            for j, r in enumerate(reach):
                if r is not None and j != i:
                    mixed += self.small[i, j] @ r[:, t]
            u[:, t] += self.left @ mixed
        return u


def _basis(m: np.ndarray) -> np.ndarray:
    """An orthonormal basis of ``m``'s columns (N × r)."""
    u, s, _ = np.linalg.svd(m, full_matrices=False)
    return u[:, s > RANK_TOL * s[0]]

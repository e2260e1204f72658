"""Gear 1: the exact envelope of gear 2 in relative rolling (paper eq. 8/14), both branches.

Generating motion (fixed frame, gear-2 centre at the origin, gear-1 centre at ``A = (0, a)``):
gear 2 turns by β, gear 1 by ``α = k β`` with ``k = z2/z1``. A gear-2 point ``P(ξ)`` seen
from gear 1 is ``q = R(-α) (R(β) P - A)``. The instantaneous centre of the relative motion is
``N = (0, rN)`` with ``rN = a z2 / (z2 - z1)``; ``P(ξ)`` generates gear 1 when its normal passes
through N (Lewis / law of gearing). In gear 2's frame N sits on the circle of radius rN, so

    s² + 2 s (P·n) + |P|² - rN² = 0,   C = P + s n,   β = π/2 - arg C,

has two solutions: the near-side branch (small |s|, the working flanks) and the far-side branch
(the normal met again across the circle). Both are closed form; gear 1 is the lower envelope
(smallest radius per polar angle about its centre) of the branches that shape it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .gear2 import Cycloid

NEAR = -1
FAR = +1


@dataclass(frozen=True)
class BranchPoints:
    """Envelope points of one branch (arrays over the gear-2 parameter ξ).

    Attributes:
        xi: gear-2 (tool) parameter.
        beta: generating rolling angle of gear 2 [rad].
        q: gear-1 profile point in gear 1's frame (n, 2) [mm].
        tangent: unit tangent of gear 1, the tool tangent carried into gear 1's frame.
        normal: unit normal pointing out of gear-1 material (into the gap).
        kappa: signed curvature [1/mm], > 0 where gear 1 is convex.
        speed: signed speed dq/dξ · tangent [mm/rad]; a sign change is a cusp.
        disc: discriminant of the meshing equation (< 0: the normal misses the pitch circle).
    """

    xi: np.ndarray
    beta: np.ndarray
    q: np.ndarray
    tangent: np.ndarray
    normal: np.ndarray
    kappa: np.ndarray
    speed: np.ndarray
    disc: np.ndarray

    @property
    def radius(self) -> np.ndarray:
        """Distance from gear 1's centre [mm]."""
        return np.hypot(self.q[:, 0], self.q[:, 1])

    @property
    def polar_rate(self) -> np.ndarray:
        """dφ/dξ of the polar angle of q about gear 1's centre."""
        cross = self.q[:, 0] * self.tangent[:, 1] - self.q[:, 1] * self.tangent[:, 0]
        return self.speed * cross / (self.q[:, 0] ** 2 + self.q[:, 1] ** 2)

    @property
    def curvature_radius(self) -> np.ndarray:
        """Signed curvature radius [mm], > 0 convex (gear 1 is mostly convex)."""
        with np.errstate(divide="ignore"):
            return 1.0 / self.kappa


@dataclass(frozen=True)
class Branch:
    """One solution branch of the meshing equation.

    Attributes:
        tool: generating gear-2 curve.
        a: generating centre distance [mm].
        z2: gear-2 teeth, z1: gear-1 teeth.
        side: ``NEAR`` or ``FAR``.
    """

    tool: Cycloid
    a: float
    z2: int
    z1: int
    side: int

    @property
    def k(self) -> float:
        return self.z2 / self.z1

    @property
    def r_instant(self) -> float:
        """Radius of the instantaneous-centre circle in gear 2's frame [mm]."""
        return self.a * self.z2 / (self.z2 - self.z1)

    def evaluate(self, xi: np.ndarray) -> BranchPoints:
        """Exact envelope points, tangents, normals and curvatures at tool parameters ``xi``.
        Written on the x and y components apart: a profile's inversions call it hundreds of
        times on a point or a few, where stacking and slicing (n, 2) arrays cost more than the
        arithmetic."""
        xi = np.atleast_1d(np.asarray(xi, dtype=float))
        (px, py), (d1x, d1y), (d2x, d2y) = self.tool.components(xi, 2)
        sp2 = np.hypot(d1x, d1y)
        tx, ty = d1x / sp2, d1y / sp2                  # the tool's tangent; its normal (-ty, tx)
        kap2 = (d1x * d2y - d1y * d2x) / sp2**3
        rn = self.r_instant
        pn = px * -ty + py * tx
        pp = px * px + py * py
        pt = px * tx + py * ty
        disc = pn * pn - pp + rn * rn
        root = np.sqrt(np.maximum(disc, 0.0))
        s = -pn + self.side * root
        cx, cy = px - s * ty, py + s * tx
        # the near side meets gear 1 around β = π/2, the far side around β = -π/2
        ref = -0.5 * np.pi * self.side
        u = np.pi / 2 - np.arctan2(cy, cx) - ref
        beta = ref + np.arctan2(np.sin(u), np.cos(u))
        # derivative of β(ξ): s' from the quadratic, C' = |P'|(1 - s κ) t + s' n
        with np.errstate(divide="ignore", invalid="ignore"):
            ds = -(s * (-kap2 * sp2 * pt) + sp2 * pt) / (s + pn)
        f = sp2 * (1.0 - s * kap2)
        dbeta = -(cx * (f * ty + ds * tx) - cy * (f * tx - ds * ty)) / rn**2
        k = self.k
        alpha = k * beta
        cb, sb = np.cos(beta), np.sin(beta)
        ca, sa = np.cos(alpha), np.sin(alpha)
        fx, fy = cb * px - sb * py, sb * px + cb * py  # R(β) P, the fixed frame
        ry = fy - self.a                               # less A = (0, a)
        q = np.column_stack([ca * fx + sa * ry, -sa * fx + ca * ry])
        g = beta - alpha
        cg, sg = np.cos(g), np.sin(g)
        t1 = np.column_stack([cg * tx - sg * ty, sg * tx + cg * ty])
        n1 = np.column_stack([cg * ty + sg * tx, sg * ty - cg * tx])
        # signed speed σ = |P'| + β' (W × T2), W = (1-k) R(β)P + k A, T2 = R(β) t2
        wx, wy = (1.0 - k) * fx, (1.0 - k) * fy + k * self.a
        big_tx, big_ty = cb * tx - sb * ty, sb * tx + cb * ty
        sigma = sp2 + dbeta * (wx * big_ty - wy * big_tx)
        with np.errstate(divide="ignore", invalid="ignore"):
            kappa = (kap2 * sp2 + (1.0 - k) * dbeta) / sigma
        return BranchPoints(xi=xi, beta=beta, q=q, tangent=t1, normal=n1, kappa=kappa,
                            speed=sigma, disc=disc)

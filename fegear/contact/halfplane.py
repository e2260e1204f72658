"""The elastic half-plane under a normal pressure (Flamant), plane stress: the near field of a
contact that the finite elements need not resolve.

A line load P (N per mm of thickness) pressing on the surface z = 0 of the half-plane z > 0 at
the origin moves the point (t, z) into the body by

    u_z(t, z) = (2P / (π E)) [ −ln r + ((1 − ν)/2) cos²θ − ν sin²θ ],   r² = t² + z², cos θ = z/r

up to a rigid motion, and stresses it by σ_zz = −(2P/π) z³/r⁴, σ_tt = −(2P/π) z t²/r⁴ (σ_rr is
the only stress of the solution). The arbitrary constant drops out of what fegear uses: the
approach of a surface point relative to the point at depth d below it,

    Δ(t, d) = u_z(t, 0) − u_z(t, d) = (P / (π E)) [ ln(1 + d²/t²) − (1 + ν) d²/(t² + d²) ],

which decays like 1/t² away from the load. Pressures are piecewise linear on a grid along the
surface (one hat per grid point); every integral over a hat is in closed form, the logarithmic
singularity under the load included. Units: mm, N, MPa.
"""

from __future__ import annotations

import math

import numpy as np


def _antiderivatives(u: np.ndarray, d: np.ndarray, nu: float) -> tuple[np.ndarray, np.ndarray]:
    """F0 = ∫ K du and F1 = ∫ u K du for K(u) = ln(1 + d²/u²) − (1 + ν) d²/(u² + d²)."""
    uu, dd = u * u, d * d
    with np.errstate(divide="ignore", invalid="ignore"):
        log_ratio = np.where(u == 0.0, 0.0, u * np.log1p(dd / np.where(u == 0.0, 1.0, uu)))
        u_log = np.where(u == 0.0, 0.0, uu * np.log(np.where(u == 0.0, 1.0, uu)))
    atan = np.arctan2(u, d)
    F0 = log_ratio + 2.0 * d * atan - (1.0 + nu) * d * atan
    F1 = 0.5 * ((uu + dd) * np.log(uu + dd) - u_log - dd) - 0.5 * (1.0 + nu) * dd * np.log(uu + dd)
    return F0, F1


def _strain_antiderivatives(u: np.ndarray, d: np.ndarray, nu: float
                            ) -> tuple[np.ndarray, np.ndarray]:
    """∫ k du and ∫ u k du for k(u) = d (u² − ν d²) / (u² + d²)², the tangential strain
    kernel (σ_tt − ν σ_zz) up to the factor −2P/(π E)."""
    s = u * u + d * d
    atan = np.arctan2(u, d)
    # ∫ u²/s² = (atan/d − u/s)/2 ; ∫ 1/s² = (u/(d² s) + atan/d³)/2
    i_a = 0.5 * (atan / d - u / s)
    i_b = 0.5 * (u / (d * d * s) + atan / d ** 3)
    # ∫ u³/s² = (ln s + d²/s)/2 ; ∫ u/s² = −1/(2 s)
    i_c = 0.5 * (np.log(s) + d * d / s)
    i_d = -0.5 / s
    return d * (i_a - nu * d * d * i_b), d * (i_c - nu * d * d * i_d)


def _hat_matrix(t: np.ndarray, d: np.ndarray, s: np.ndarray, antiderivatives,
                nu: float) -> np.ndarray:
    """∫ φ_j(σ) K(t_i − σ; d_i) dσ for the hats φ_j of the grid ``s`` (sorted): (n, m)."""
    t = np.asarray(t, float)[:, None]
    d = np.broadcast_to(np.asarray(d, float), t.shape[:1])[:, None]
    s = np.asarray(s, float)
    out = np.zeros((t.shape[0], len(s)))
    a, b = s[:-1][None, :], s[1:][None, :]   # interval k: [s_k, s_k+1]
    # over an interval σ ∈ [a, b]: u = t − σ ∈ [t − b, t − a]; t − b of interval k is t − a
    # of interval k + 1, so the antiderivatives are taken once at every grid point
    F0, F1 = antiderivatives(t - s[None, :], d, nu)
    I0, I1 = F0[:, :-1] - F0[:, 1:], F1[:, :-1] - F1[:, 1:]   # ∫ K du, ∫ u K du
    width = b - a
    # falling part of hat k on [a, b]: (b − σ)/(b − a) = (b − t + u)/(b − a)
    falling = ((b - t) * I0 + I1) / width
    # rising part of hat k + 1: (σ − a)/(b − a) = (t − u − a)/(b − a)
    rising = ((t - a) * I0 - I1) / width
    out[:, :-1] += falling
    out[:, 1:] += rising
    return out


def approach_matrix(t, d, s, E: float, nu: float) -> np.ndarray:
    """Δ_ij: how far surface point i (arc position ``t_i``) approaches the point at depth
    ``d_i`` below it, per unit pressure (MPa) of hat j on the grid ``s``: mm/MPa."""
    return _hat_matrix(t, d, s, _antiderivatives, nu) / (math.pi * E)


def hat_columns(t, d, s, lo: int, hi: int, E: float, nu: float) -> np.ndarray:
    """:func:`approach_matrix`'s columns of the hats ``lo`` … ``hi`` − 1 of the grid ``s``
    alone, from the grid's points ``lo`` − 1 … ``hi``: each hat's two intervals, the same
    integrals as over the whole grid."""
    a, b = max(lo - 1, 0), min(hi + 1, len(s))
    return approach_matrix(t, d, s[a:b], E, nu)[:, lo - a:hi - a]


def strain_matrix(t, d, s, E: float, nu: float) -> np.ndarray:
    """ε_tt at depth ``d_i`` below surface point ``t_i`` (tangential strain, + stretching) per
    unit pressure of hat j on the grid ``s``: 1/MPa."""
    return -2.0 / (math.pi * E) * _hat_matrix(t, d, s, _strain_antiderivatives, nu)


def _log_antiderivatives(u: np.ndarray, d, nu: float) -> tuple[np.ndarray, np.ndarray]:
    """F0 = ∫ K du and F1 = ∫ u K du for the surface kernel K(u) = −2 ln|u| (the depth and
    ν do not enter: the surface's own approach, up to a constant)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        lg = np.where(u == 0.0, 0.0, np.log(np.abs(np.where(u == 0.0, 1.0, u))))
    return -2.0 * u * (lg - 1.0), -u * u * (lg - 0.5)


def surface_matrix(s: np.ndarray, E_star: float) -> np.ndarray:
    """How far two elastic half-planes' surfaces approach each other at the grid points ``s``
    per unit pressure of hat j (mm/MPa), up to one rigid approach: (1/(π E*)) ∫ φ_j(σ)
    (−2 ln|s_i − σ|) dσ, E* the contact modulus."""
    s = np.asarray(s, dtype=float)
    return _hat_matrix(s, np.zeros(len(s)), s, _log_antiderivatives, 0.0) / (math.pi * E_star)


def gap_contact(s: np.ndarray, gap: np.ndarray, load: float, E_star: float,
                max_iterations: int = 200, surface: np.ndarray | None = None,
                start: np.ndarray | None = None) -> np.ndarray:
    """Line contact of two elastic half-planes whose unloaded surfaces are ``gap`` (mm) apart
    at the arc positions ``s`` (mm, increasing), pressed together by ``load`` (N per mm of
    thickness): the pressure (MPa, piecewise linear on ``s``). Hertz's assumptions except one:
    the gap is the profiles' own, not the parabola of the curvatures at one point. Active set:
    where pressure acts, gap + approach(p) equals the rigid approach δ; elsewhere it is not
    less; Σ w p = load. ``surface``: :func:`surface_matrix` of ``s`` where the caller has it;
    ``start``: the points to start the active set from (a contact solved before on the same
    grid: a few iterations, not ten; else the point of least gap)."""
    s, gap = np.asarray(s, dtype=float), np.asarray(gap, dtype=float)
    A = surface_matrix(s, E_star) if surface is None else surface
    w = np.zeros(len(s))
    w[:-1] += 0.5 * np.diff(s)
    w[1:] += 0.5 * np.diff(s)
    active = (gap <= gap.min()) if start is None or not np.any(start) \
        else np.array(start, dtype=bool)
    for _ in range(max_iterations):
        ia = np.flatnonzero(active)
        n = len(ia)
        M = np.zeros((n + 1, n + 1))
        M[:n, :n] = A[np.ix_(ia, ia)]
        M[:n, n] = -1.0
        M[n, :n] = w[ia]
        x = np.linalg.solve(M, np.concatenate([-gap[ia], [load]]))
        p = np.zeros(len(s))
        p[ia] = x[:n]
        if (x[:n] < 0.0).any():
            active[ia[x[:n] < 0.0]] = False
            continue
        opened = gap + A @ p - x[n]
        closing = (opened < 0.0) & ~active
        if not closing.any():
            return p
        active |= closing
    raise ValueError(f"the half-plane contact's active set did not settle in {max_iterations} "
                     "iterations")

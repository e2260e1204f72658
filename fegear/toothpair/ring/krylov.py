"""GMRES for the face's bordered systems (:mod:`.face_contact`), left-preconditioned and
restarted, with the stopping rules of scipy's :func:`~scipy.sparse.linalg.gmres` (its
``rtol``, ``atol=0``).

It is scipy's method without its per-step Python loops: the new direction orthogonalised
against the basis in two block passes (classical Gram-Schmidt twice, as stable as the modified
one scipy runs a basis vector at a time), the Hessenberg column rotated in plain floats. The
face's systems have a few thousand unknowns and take some thirty steps, where the loops were a
fifth of the solve (docs/model.md, "Across the face").
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

Operator = Callable[[np.ndarray], np.ndarray]
#: the steps between restarts and the restarts at most
RESTART, CYCLES = 80, 20


@dataclass(frozen=True)
class Krylov:
    """A system's solution ``x``, whether it met the tolerance, and the steps taken (each one
    product with the operator and one with the preconditioner)."""

    x: np.ndarray
    converged: bool
    steps: int


def gmres(times: Operator, precondition: Operator, b: np.ndarray, x0: np.ndarray,
          rtol: float) -> Krylov:
    """x with ``times``(x) = ``b`` from ``x0``, by GMRES on precondition(times(x)) =
    precondition(b), restarted every :data:`RESTART` steps, at most :data:`CYCLES` times. As
    scipy's, a cycle ends where the preconditioned residual's estimate meets its tolerance (at
    first ``rtol`` times the preconditioned right-hand side's norm), and the solve where the
    residual itself is within ``rtol`` of the right-hand side's norm; where it is not, the
    next cycle's tolerance is set from the two. A start ``x0`` is taken as it is only where
    both residuals meet their tolerances (scipy asks it of the residual alone, which a
    bordered system's one large entry, the torque, can make loose)."""
    b_norm = np.linalg.norm(b)
    tol = rtol * b_norm
    ptol, factor = np.linalg.norm(precondition(b)) * rtol, 1.0
    x, steps = x0.copy(), 0
    r = b - times(x)
    r_norm, z = np.linalg.norm(r), precondition(r)
    if r_norm <= tol and np.linalg.norm(z) <= ptol:
        return Krylov(x, True, steps)
    for _ in range(CYCLES):
        y, basis, taken, presid = _cycle(times, precondition, z, ptol, RESTART)
        x += y @ basis[:len(y)]
        steps += taken
        r = b - times(x)
        r_norm = np.linalg.norm(r)
        if r_norm <= tol:
            return Krylov(x, True, steps)
        z = precondition(r)
        factor = max(np.finfo(float).eps, 0.25 * factor) if presid <= ptol \
            else min(1.0, 1.5 * factor)
        ptol = presid * min(factor, tol / r_norm)
    return Krylov(x, False, steps)


def _cycle(times: Operator, precondition: Operator, z: np.ndarray, tol: float,
           restart: int) -> tuple[np.ndarray, np.ndarray, int, float]:
    """One restart cycle from the preconditioned residual ``z``, until its estimate is
    within ``tol``: the basis' coefficients of the correction, the basis, the steps taken and
    the estimate."""
    beta = float(np.linalg.norm(z))
    v = np.empty((restart + 1, len(z)))
    v[0] = z / beta
    h = np.zeros((restart + 1, restart))
    rotations: list[tuple[float, float]] = []
    g = [beta]
    j = 0
    for j in range(restart):
        w = precondition(times(v[j]))
        w_norm = np.linalg.norm(w)
        c1 = v[:j + 1] @ w
        w -= c1 @ v[:j + 1]
        c2 = v[:j + 1] @ w
        w -= c2 @ v[:j + 1]
        col = [float(c) for c in c1 + c2]
        last = float(np.linalg.norm(w))
        breakdown = last <= np.finfo(float).eps * w_norm
        if not breakdown:
            v[j + 1] = w / last
        for i, (c, s) in enumerate(rotations):
            col[i], col[i + 1] = c * col[i] + s * col[i + 1], -s * col[i] + c * col[i + 1]
        top = col[j]
        mag = math.hypot(top, last)
        c, s = (top / mag, last / mag) if mag else (1.0, 0.0)
        rotations.append((c, s))
        col[j] = mag
        h[:j + 1, j] = col
        g.append(-s * g[j])
        g[j] *= c
        if abs(g[j + 1]) <= tol or breakdown:
            break
    k = j + 1
    y = _upper_solve(h[:k, :k], np.array(g[:k]))
    return y, v, k, abs(g[k])


def _upper_solve(r: np.ndarray, g: np.ndarray) -> np.ndarray:
    """y with the upper triangular r y = g, a zero pivot taking its entry as zero (scipy's
    pseudo-solve of a breakdown)."""
    y = g.copy()
    for k in range(len(y) - 1, -1, -1):
        y[k] = (y[k] - r[k, k + 1:] @ y[k + 1:]) / r[k, k] if r[k, k] else 0.0
    return y

"""The contact solve at one position: grid pressures p ≥ 0 and gaps g ≥ 0, complementary, with
the contact moments balancing the torque on gear 1 (load control); no penalty.

The gap of grid point i at gear 1's rotation θ (from its kinematic position) is
g_i = g_rigid,i(θ) + Σ_j A_ij p_j, the exact rigid gap to gear 2's curve plus the elastic
separation (:mod:`.influence`). Active-set iterations solve the linearised rigid gap with the
torque balance; the exact gap is then evaluated again at the new rotation until the rotation
settles (the rigid gap is nonlinear in θ only through the turn, a µrad here).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...errors import FegearError
from ...planar import rotate
from ..teeth import Gear2Master
from .influence import RingContact
from .model import RingModel

MAX_ACTIVE_SET = 80     # active-set changes per linearisation
MAX_TURNS = 30          # linearisations of the rigid gap


class RingContactError(FegearError):
    """The contact at one position has no solution the iterations could find."""


@dataclass(frozen=True)
class RingContactSolution:
    """The converged contact: pressure per grid point (MPa), gap (mm), gear 1's rotation θ
    from its kinematic position (rad), active-set iterations, linearisations, torque-balance
    error (relative) and the largest overlap (mm) left where pressure acts."""

    pressure: np.ndarray
    gap: np.ndarray
    rotation: float
    iterations: int
    turns: int
    balance_error: float
    max_penetration: float


def rigid_gap(model: RingModel, x: np.ndarray, beta: float, turn: float
              ) -> tuple[np.ndarray, np.ndarray]:
    """Exact gap (mm) of gear-1 points ``x`` (its frame) to gear 2 (turned by β) with gear 1
    turned by ``turn`` (rad, kinematic angle included), and the gap's rate with that turn
    (mm/rad)."""
    o1 = np.array([0.0, model.case.params.e])
    fixed = rotate(x, turn) + o1
    cp = Gear2Master(model.curve2, beta).closest(fixed)
    r = fixed - o1
    return cp.distance, np.einsum("ij,ij->i", cp.normal, np.column_stack([-r[:, 1], r[:, 0]]))


def solve_ring_contact(model: RingModel, contact: RingContact, torque_nmm: float, theta: float,
                  guess: float | None = None) -> RingContactSolution:
    """Solve the contact under ``torque_nmm`` (N·mm on gear 1) from the rotation ``theta``
    (rad); the iterations start from the points the rigid teeth overlap at the rotation
    ``guess`` (rad; else from the point of least gap)."""
    alpha = model.case.params.ratio * contact.beta
    A, w = contact.A, contact.weight * model.case.thickness
    g0, a = rigid_gap(model, contact.x, contact.beta, alpha + theta)
    active = g0 <= g0.min() + 1e-12
    if guess is not None:
        overlap = rigid_gap(model, contact.x, contact.beta, alpha + guess)[0] < 0
        active = overlap if overlap.any() else active
    pressure = np.zeros(len(g0))
    total = turns = 0
    while True:
        pressure, step, active, used = _active_set(A, w, g0, a, torque_nmm, active)
        total += used
        turns += 1
        theta += step
        g0, a = rigid_gap(model, contact.x, contact.beta, alpha + theta)
        # settled to rounding: 1e-12 of the rotation, or a 1e-13 mm turn at the pitch circle
        if abs(step) <= max(1e-12 * abs(theta), 1e-13 / model.case.params.r0):
            break
        if turns == MAX_TURNS:
            raise RingContactError(f"the rotation did not settle in {MAX_TURNS} "
                                   "linearisations")
    gap = g0 + A @ pressure
    balance = abs(-(w * pressure) @ a - torque_nmm) / torque_nmm
    loaded = pressure > 0
    overlap = float(max(0.0, -gap[loaded].min())) if loaded.any() else 0.0
    return RingContactSolution(pressure, gap, float(theta), total, turns, float(balance),
                               overlap)


def _active_set(A, w, g0, a, torque_nmm, active):
    """Pressures on the active points and the rotation step with the gap linear in the step:
    A p + a δ = −g0 on the active points, −Σ w a p = T; points join when their gap closes
    and leave when their pressure pulls. Returns pressure, step, active set, iterations."""
    seen = set()
    for k in range(1, MAX_ACTIVE_SET + 1):
        idx = np.flatnonzero(active)
        n = len(idx)
        M = np.empty((n + 1, n + 1))
        M[:n, :n] = A[np.ix_(idx, idx)]
        M[:n, n] = a[idx]
        M[n, :n] = w[idx] * a[idx]
        M[n, n] = 0.0
        try:
            sol = np.linalg.solve(M, np.concatenate([-g0[idx], [-torque_nmm]]))
        except np.linalg.LinAlgError:
            raise RingContactError("the contact points cannot carry the torque") from None
        pressure = np.zeros(len(g0))
        pressure[idx] = sol[:n]
        step = sol[n]
        gap = g0 + a * step + A @ pressure
        new = np.where(active, pressure > 0, gap < 0)
        if not new.any():
            new = gap <= gap.min()
        if np.array_equal(new, active):
            return pressure, step, active, k
        key = new.tobytes()
        if key in seen:
            raise RingContactError("the contact's active set cycles at this load")
        seen.add(key)
        active = new
    raise RingContactError(f"the active set did not settle in {MAX_ACTIVE_SET} iterations")


def touch_rotation(model: RingModel, contact: RingContact, theta: float) -> float:
    """The rotation θ (rad) at which gear 1's rigid, rounded teeth first touch: the smallest
    closure over the grid points, repeated on the exact gaps."""
    alpha = model.case.params.ratio * contact.beta
    for _ in range(8):
        g0, a = rigid_gap(model, contact.x, contact.beta, alpha + theta)
        closing = a < 0
        step = float(np.min(g0[closing] / -a[closing]))
        theta += step
        if abs(step) < 1e-14:
            break
    return theta

"""A solved contact linearised with its active set kept: the bordered system of the contact
solve (:mod:`.contact`) at its solution, whose solutions are the contact's derivatives (in
the torque: the tangent mesh stiffness; in a deviation: :mod:`.sensitivity`)."""

from __future__ import annotations

import numpy as np

from .contact import ARM_STEP, RingContactSolution, rigid_gap
from .influence import RingContact
from .model import RingModel


def tangent_stiffness(model: RingModel, contact: RingContact,
                      sol: RingContactSolution) -> float:
    """The tangent mesh stiffness dT/dθ (N·m/rad of gear-1 rotation) at the solved load, the
    active points kept: the system the contact solve's last step solves
    (:func:`~.contact_system.solve_active`), differentiated in the torque (a linearised
    dynamic model's mesh spring; the secant T/(θ − θ_touch) is the static one). It is the
    slope of θ(T) between the loads at which a point joins or leaves the contact."""
    idx, system = solved_system(model, contact, sol)
    if not len(idx):
        return float("nan")
    rhs = np.zeros(len(idx) + 1)
    rhs[-1] = -1.0                     # one N·mm more on gear 1
    rate = np.linalg.solve(system, rhs)[-1]  # rad per N·mm
    return float(1e-3 / rate)


def solved_system(model: RingModel, contact: RingContact, sol: RingContactSolution
                  ) -> tuple[np.ndarray, np.ndarray]:
    """The solved contact's active points (indices) and the bordered system over them that
    :func:`~.contact_system.solve_active` solves at the solution, the torque arm's turn
    included: the matrix whose solutions are the contact's derivatives with its active set
    kept (in the torque: :func:`tangent_stiffness`; in a deviation: :mod:`.sensitivity`).
    ``contact`` with its influence matrix."""
    alpha = model.case.params.ratio * contact.beta
    w = contact.weight * model.case.thickness
    idx = np.flatnonzero(sol.pressure > 0)
    if not len(idx):
        return idx, np.zeros((1, 1))
    _, a = rigid_gap(model, contact, alpha + sol.rotation, contact.feet)
    ahead = rigid_gap(model, contact, alpha + sol.rotation + ARM_STEP, contact.feet[idx],
                      idx)[1]
    arm_rate = (w[idx] * sol.pressure[idx]) @ (ahead - a[idx]) / ARM_STEP
    rows = (np.cumsum(contact.formed) - 1)[idx]     # the active points' rows of A
    contact.ready(idx)
    return idx, _bordered(contact.A[np.ix_(rows, rows)], w[idx], a[idx], arm_rate)


def _bordered(A: np.ndarray, w: np.ndarray, a: np.ndarray, arm_rate: float) -> np.ndarray:
    """The active points' system in (pressures, rotation step): their influence matrix ``A``
    bordered by the gap's rate with the turn ``a`` and the torque row ``w a``."""
    n = len(a)
    M = np.empty((n + 1, n + 1))
    M[:n, :n] = A
    M[:n, n] = a
    M[n, :n] = w * a
    M[n, n] = arm_rate
    return M

"""The rotation at which gear 1's rigid teeth first touch gear 2 (:func:`touch_rotation`),
from a contact's exact rigid gaps: what the secant mesh stiffness is measured from (a
solution's ``first_touch``)."""

from __future__ import annotations

import numpy as np

from .contact import rigid_gap
from .influence import RingContact
from .model import RingModel


def touch_rotation(model: RingModel, contact: RingContact, theta: float) -> float:
    """The rotation θ (rad) at which gear 1's rigid, rounded teeth first touch: the smallest
    closure over the grid points, repeated on the exact gaps. After the first step only the
    points whose closure came within :data:`TOUCH_NEAR` of the smallest (and of the step) are
    measured again: the others cannot touch first, and a kept contact has thousands."""
    alpha = model.case.params.ratio * contact.beta
    feet = contact.feet.copy()
    idx = None
    for _ in range(8):
        g0, a = rigid_gap(model, contact, alpha + theta, feet, idx)
        closing = a < 0
        closure = np.full(len(g0), np.inf)
        closure[closing] = g0[closing] / -a[closing]
        step = float(closure.min())
        theta += step
        if abs(step) < 1e-14:
            break
        near = np.flatnonzero(closure <= step + TOUCH_NEAR * max(abs(step), 1e-6))
        idx, feet = (near, feet[near]) if idx is None else (idx[near], feet[near])
    return theta


#: a point is measured again in :func:`touch_rotation` where its closure is within this many
#: times the step (or a µrad) of the smallest: the closures move by the gaps' curvature over
#: the step, a small fraction of it
TOUCH_NEAR = 1.0

"""The sector peer's gear 1 with its pitch deviations in the geometry: each deviated tooth's
outline turned about gear 1's centre before it is meshed, and gear 1's centre moved by the
centre distance's deviation where the bodies are placed. The ring model takes deviations into
its rigid gaps only (the bodies stay the exact pair's); this model meshes the material where
the deviations put it, the independent check of that.

Between two teeth the turn passes from one tooth's to the next over :data:`BLEND` of a pitch
either side of the space centre, smoothly (its slope 0 at both ends): the space bottom is
close to a circle about gear 1's centre, which a turn slides along itself, so the blend leaves
the root's shape as it is to a small fraction of the deviation."""

from __future__ import annotations

import numpy as np

from ...errors import ParameterError
from ...geometry import Deviations, RoundedProfile

#: the half-width (fraction of gear 1's pitch) of the blend at each space centre
BLEND = 0.15


def explicit_only(deviations: Deviations) -> None:
    """Refuse, by name, the deviations this model does not build into its geometry: it turns
    gear 1's teeth and moves gear 1's centre; gear 2's teeth, the flanks' slope and form and
    the runouts stay with the ring model."""
    gear1 = deviations.teeth(1).values()
    other = ("slope-deviation" if any(d.slope for d in gear1) else
             "form-deviation" if any(d.profiled for d in gear1) else
             "pitch-deviation" if deviations.gear2 else
             "runout" if deviations.runout1.fr or deviations.runout2.fr else None)
    if other is not None:
        raise ParameterError(other, "given", "gear 1's pitch deviations and the centre "
                             "distance's: the sector model builds no other deviation into "
                             "its geometry", "not built by the sector model")


def tooth_turns(shape: RoundedProfile, deviations: Deviations, r1: float, z1: int):
    """θ(φ): the turn (rad) of gear 1's outline at body polar angles φ, each tooth's pitch
    deviation over the tooth and blended across each space."""
    table = deviations.turns(1, np.arange(z1), r1)

    def theta(phi: np.ndarray) -> np.ndarray:
        u = (np.asarray(phi) - shape.tooth_center) / shape.pitch   # tooth k at u = k
        j = np.floor(u).astype(int)
        t = np.clip((u - j - 0.5) / BLEND, -1.0, 1.0)
        w = 0.5 + 0.5 * np.sin(0.5 * np.pi * t)
        a, b = table[np.mod(j, z1)], table[np.mod(j + 1, z1)]
        return a + w * (b - a)

    return theta


def turned_outline(shape: RoundedProfile, deviations: Deviations, r1: float, z1: int):
    """(point, project) of gear 1's outline by polar angle with its teeth turned
    (:func:`tooth_turns`): the material at polar angle ψ stands at ψ + θ(ψ); ``project`` snaps
    points onto it by their polar angle, as the exact profile's does."""
    theta = tooth_turns(shape, deviations, r1, z1)

    def point(phi: np.ndarray) -> np.ndarray:
        phi = np.asarray(phi, dtype=float)
        th = theta(phi)
        q = shape.point(phi - th)
        c, s = np.cos(th), np.sin(th)
        return np.column_stack([c * q[:, 0] - s * q[:, 1], s * q[:, 0] + c * q[:, 1]])

    def project(x: np.ndarray) -> np.ndarray:
        return point(np.arctan2(x[:, 1], x[:, 0]))

    return point, project

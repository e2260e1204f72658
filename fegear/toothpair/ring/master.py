"""Gear 2's exact curve placed at a rolling angle: the master the ring model's gaps are
measured to (:mod:`.contact`, :mod:`.influence`), and the sector model's master curve too
(:mod:`fegear.verify.sector`)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...contact import CurvePoints
from ...geometry import Cycloid
from ...planar import rotate


@dataclass(frozen=True)
class Gear2Master:
    """Gear 2's exact curve at rolling angle β, as an exact master curve (fixed frame)."""

    curve: Cycloid
    beta: float

    def closest(self, points: np.ndarray, feet: np.ndarray | None = None) -> CurvePoints:
        """The feet of ``points`` on the curve. ``feet``: the curve's parameters ξ to start
        each point's search from (NaN: from its polar angle), overwritten with the feet found
        (:meth:`~fegear.geometry.Cycloid.feet`)."""
        y = rotate(np.asarray(points, float), -self.beta)
        xi = self.curve.feet(y, start=feet)
        if feet is not None:
            feet[:] = xi
        foot, normal, dist = self.curve.at_feet(y, xi)
        return CurvePoints(rotate(foot, self.beta), rotate(normal, self.beta), dist)

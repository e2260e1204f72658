"""Closest points on an exact curve: what a body's exact boundary answers for points near it
(gear 2's curve placed at a rolling angle, a circle of the Hertz case), so that a gap is
measured to the curve itself, not to a mesh's facets.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

import numpy as np


@dataclass(frozen=True)
class CurvePoints:
    """Closest points on an exact curve: feet (n, 2), unit normals pointing out of the body's
    material (n, 2), signed distances (n,) in mm, positive outside the material."""

    foot: np.ndarray
    normal: np.ndarray
    distance: np.ndarray


class ExactCurve(Protocol):
    """A curve that answers the closest points (:class:`CurvePoints`) of points (n, 2)."""

    def closest(self, points: np.ndarray) -> CurvePoints: ...

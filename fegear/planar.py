"""Plane rotations and angle wrapping, shared by the geometry and the FE stages."""

from __future__ import annotations

import numpy as np


def wrap(x: np.ndarray | float) -> np.ndarray | float:
    """Angle wrapped into [-π, π], exact for angles already in range (no detour via π)."""
    x = np.asarray(x)
    return x - 2 * np.pi * np.round(x / (2 * np.pi))


def rotate(v: np.ndarray, ang) -> np.ndarray:
    """Rotate (n, 2) points counter-clockwise by ``ang`` (scalar or per point)."""
    return rotate_by(v, np.cos(ang), np.sin(ang))


def rotate_by(v: np.ndarray, c, s) -> np.ndarray:
    """Rotate (n, 2) points counter-clockwise by the angle whose cosine is ``c`` and sine
    ``s`` (scalars or per point): :func:`rotate` with the trigonometry done once, for points
    turned by the same angles again and again. Several sets of the same points, (k, n, 2),
    are turned alike."""
    return np.stack([c * v[..., 0] - s * v[..., 1], s * v[..., 0] + c * v[..., 1]], axis=-1)

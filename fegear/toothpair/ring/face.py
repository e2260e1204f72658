"""Across the face width: how the gears couple the face's sections (:class:`FaceCoupling`);
what varies across the face is :class:`~fegear.toothpair.face.Face`, the contact solved over
the sections :mod:`.face_contact`'s (docs/model.md, "Across the face").

The line load is taken linear between ``N`` sections at ζ = −½ … ½ of the face (both ends
among them), each section holding the 2D contact's points with pressures of its own. A point's
approach at section s splits as the 2D influence does (:mod:`.influence`): the half-plane's
near field, the surface relative to a depth of a few facets, stays in its section (that
depth is a tenth of a millimetre, a section a millimetre or more); the finite-element part, the
tooth's and the rim's answer below that depth, spreads along the face,

    approach_s = A_hp p_s + A_fe Σ_t S_st p_t,

by the spread S (rows summing to one: a load even across the face is the 2D pair's, to
rounding; a load linear across the face stays linear). Each section's rigid gap is the 2D
one plus what the face's inputs add there (:meth:`~fegear.toothpair.face.Face.offsets`:
misalignment, helix deviations, crowning, end relief).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

#: quadrature points per section interval for the spread's integrals over the linear load
QUADRATURE = 16


@dataclass(frozen=True)
class FaceCoupling:
    """The sections across the face and how the gears couple them. ``zeta``: each section's
    place (fraction of the face width from its middle, −½ … ½), ``share``: its share of
    the face (the trapezoid rule's weights of a load linear between sections; they sum to
    one), ``spread`` (N × N): the finite-element approach at section s is Σ_t spread[s, t]
    times that of section t's line load spread evenly over the face; each row sums to one."""

    zeta: np.ndarray
    share: np.ndarray
    spread: np.ndarray

    @property
    def sections(self) -> int:
        return len(self.zeta)


def exponential_kernel(decay: float) -> Callable[[np.ndarray], np.ndarray]:
    """A line load's finite-element approach along the face at a distance x (mm) from a load
    across a short length, per unit of that load spread evenly: exp(−|x|/λ)/(2λ), ``decay``
    λ (mm); it integrates to one over the line."""
    return lambda x: np.exp(-np.abs(x) / decay) / (2.0 * decay)


def face_coupling(sections: int, width: float,
                  kernel: Callable[[np.ndarray], np.ndarray]) -> FaceCoupling:
    """``sections`` sections over a face ``width`` (mm) wide, the spread formed from the
    ``kernel`` over the face (:func:`exponential_kernel`): w[s, t] = ∫ k(z_s − z) φ_t(z) dz
    over the face, φ_t section t's hat, by Gauss quadrature; then, row by row, the local-linear
    correction spread[s, t] = w[s, t] (c0 + c1 (z_t − z_s)) that makes each row sum to one
    (a load even across the face: the 2D pair's approach everywhere) and keep a load linear
    across the face linear to its ends (a misalignment's: the 3D tooth's approach under
    one is linear to within a few per cent at the ends, where a kernel mirrored at the free
    ends levels it off and the solve then piles the load at the closing end)."""
    if sections < 2:
        raise ValueError(f"two or more sections across the face, not {sections}")
    z = np.linspace(0.0, width, sections)
    h = width / (sections - 1)
    share = np.full(sections, 1.0 / (sections - 1))
    share[[0, -1]] *= 0.5
    u, wq = np.polynomial.legendre.leggauss(QUADRATURE)
    w = np.zeros((sections, sections))
    for t in range(sections - 1):          # the interval [z_t, z_t+1]
        x = z[t] + 0.5 * h * (u + 1.0)
        rising = (x - z[t]) / h            # section t+1's hat; section t's is 1 − it
        k = kernel(z[:, None] - x[None, :]) * (0.5 * h * wq)
        w[:, t] += k @ (1.0 - rising)
        w[:, t + 1] += k @ rising
    d = z[None, :] - z[:, None]
    m0, m1, m2 = w.sum(axis=1), (w * d).sum(axis=1), (w * d * d).sum(axis=1)
    spread = w * (m2[:, None] - m1[:, None] * d) / (m0 * m2 - m1 * m1)[:, None]
    return FaceCoupling(z / width - 0.5, share, spread)

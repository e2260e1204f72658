"""Across the face width: what varies across it (:class:`Face`) and how the gears couple the
face's sections (:class:`FaceCoupling`); the contact solved over them is
:mod:`.face_contact`'s (docs/model.md, "Across the face").

The line load is taken linear between ``N`` sections at ζ = −½ … ½ of the face (both ends
among them), each section holding the 2D contact's points with pressures of its own. A point's
approach at section s splits as the 2D influence does (:mod:`.influence`): the half-plane's
near field, the surface relative to a depth of a few facets, stays in its section (that
depth is a tenth of a millimetre, a section a millimetre or more); the finite-element part, the
tooth's and the rim's answer below that depth, spreads along the face,

    approach_s = A_hp p_s + A_fe Σ_t S_st p_t,

by the spread S (rows summing to one: a load even across the face is the 2D pair's, to
rounding). Each section's rigid gap is the 2D one plus what the face's inputs add there
(:meth:`Face.offsets`: misalignment, helix deviations, crowning, end relief).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from ...geometry import gear2_tooth
from ...planar import rotate
from .influence import RingContact

#: the spread sums the mirrored loads until the kernel has fallen below this share of its peak
#: (at most :data:`MOST_IMAGES` each side)
IMAGE_FLOOR, MOST_IMAGES = 1e-17, 100_000
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
    ``kernel`` along an unbounded face (:func:`exponential_kernel`) mirrored at the free
    ends (so a load even across the face gives an approach even across it, the 2D pair's):
    spread[s, t] = ∫ k(z_s, z) φ_t(z) dz with φ_t section t's hat over the face, by Gauss
    quadrature, its rows scaled to one (the images left out and the quadrature leave them
    off one by less than 1e-6)."""
    if sections < 2:
        raise ValueError(f"two or more sections across the face, not {sections}")
    z = np.linspace(0.0, width, sections)
    h = width / (sections - 1)
    share = np.full(sections, 1.0 / (sections - 1))
    share[[0, -1]] *= 0.5
    u, wq = np.polynomial.legendre.leggauss(QUADRATURE)
    far = 1
    while far < MOST_IMAGES and kernel(np.array([2.0 * far * width]))[0] > \
            IMAGE_FLOOR * kernel(np.zeros(1))[0]:
        far *= 2
    m = np.arange(-far, far + 1)
    spread = np.zeros((sections, sections))
    for t in range(sections - 1):          # the interval [z_t, z_t+1]
        x = z[t] + 0.5 * h * (u + 1.0)
        wx = 0.5 * h * wq
        rising = (x - z[t]) / h            # section t+1's hat; section t's is 1 − it
        for s in range(sections):
            k = sum(kernel(z[s] - (2 * width * m[:, None] + sign * x)).sum(axis=0)
                    for sign in (1, -1))
            spread[s, t] += (k * (1.0 - rising)) @ wx
            spread[s, t + 1] += (k * rising) @ wx
    spread /= spread.sum(axis=1, keepdims=True)
    return FaceCoupling(z / width - 0.5, share, spread)


@dataclass(frozen=True)
class Face:
    """What varies across the face, in µm over the face width unless named otherwise.
    ``sections``: how many sections the line load is linear between (both ends among them).
    ``misalignment``: gear 1's axis displaced against gear 2's across the line of centres,
    from the face's first end (ζ = −½) to its second, + in the direction gear 1's loaded
    flanks push gear 2's at the pitch point (−x under a positive torque), so that the second
    end closes first; ``tilt``: the same along the line of centres (+: the centre distance
    grows towards the second end). ``crowning`` C_β: gear 1's teeth thinned by a parabola
    across the face, zero at mid-face and C_β at each end; ``end_relief`` C_I over
    ``end_length`` (mm) from each end, linear. ``helix1``/``helix2``: a tooth's helix slope
    f_Hβ (+: its loaded flank towards its mate at the second end, as much away at the first)
    and helix form f_fβ (+: towards its mate at mid-face, a parabola zero at the ends), as
    (gear-1 or gear-2 tooth, f_Hβ, f_fβ)."""

    sections: int = 9
    misalignment: float = 0.0
    tilt: float = 0.0
    crowning: float = 0.0
    end_relief: float = 0.0
    end_length: float = 0.0
    helix1: tuple[tuple[int, float, float], ...] = ()
    helix2: tuple[tuple[int, float, float], ...] = ()

    def offsets(self, contact: RingContact, turn: float, zeta: np.ndarray, width: float,
                z2: int) -> np.ndarray:
        """What the face's inputs add to the rigid gap (mm) of each of ``contact``'s points
        (gear 1 turned by ``turn``, rad) at sections ``zeta`` (fractions of the face
        ``width``, mm, from its middle): points × sections. A displacement d of gear 1 moves
        a point's gap by −n · d (n its outward normal in the fixed frame)."""
        n = rotate(contact.normal, turn)
        closing = n[:, 0] * self.misalignment - n[:, 1] * self.tilt   # −n · d per unit ζ
        out = np.outer(closing, zeta)
        out += self.crowning * (2.0 * zeta) ** 2
        if self.end_relief:
            beyond = np.abs(zeta) * width - (0.5 * width - self.end_length)
            out += self.end_relief * np.clip(beyond / self.end_length, 0.0, None)
        for teeth, helix in ((contact.teeth, self.helix1),
                             (gear2_tooth(contact.feet, z2), self.helix2)):
            for tooth, slope, form in helix:
                on = teeth == tooth
                out[on] -= slope * zeta + form * (1.0 - (2.0 * zeta) ** 2)
        return 1e-3 * out

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
rounding; a load linear across the face stays linear). The product's S
(:func:`measured_coupling`) is formed from gear 1's tooth in 3D: its answer along the face
to a load at one place, tabulated in tooth heights (:data:`KERNEL_TABLE`), less the near
field's share, mirrored in the free ends, with the tooth's twist (:data:`TWIST_TABLE`). The
part of the approach that a load on one tooth gives the other teeth, through the rims,
spreads nearly evenly along the face instead, tilted as gear 1's neighbours in 3D tilt
(:data:`NEIGHBOUR_TILTS`; :meth:`FaceCoupling.between`). Each section's rigid gap is the 2D
one plus what the face's inputs add there (:meth:`~fegear.toothpair.face.Face.offsets`:
misalignment, helix deviations, crowning, end relief).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

import numpy as np
from scipy.optimize import brentq

from ...contact import approach_matrix
from ...planar import rotate

if TYPE_CHECKING:   # read, never built here
    from ...geometry import RoundedProfile
    from .model import RingModel

#: quadrature points per section interval for the spread's integrals over the linear load
QUADRATURE = 16
#: the measured kernel (:func:`measured_kernel`): gear 1's tooth in 3D under a load at one
#: place of a face 5 tooth heights wide, per unit of its answer to the load spread evenly
#: (∫ = 1), times the tooth height h, at |x| = 0, ¼, ½ … 5 h (0 beyond). Reproduce (7 min):
#: ``python -m fegear.verify.face_slices fit standard quality=standard`` (docs/model.md,
#: "Across the face: the tooth in 3D")
KERNEL_STEP = 0.25
KERNEL_TABLE = (1.9008, 0.3834, 0.1697, 0.1124, 0.0941, 0.0586, 0.0586, 0.0369,
                0.0350, 0.0248, 0.0205, 0.0154, 0.0120, 0.0085, 0.0065, 0.0041,
                0.0030, 0.0018, 0.0013, 0.0013, 0.0013)
#: the band the kernel was measured under and the 2D parts are read on: mid-height of the
#: working flank, this many modules along the profile
BAND_HEIGHT, BAND_LENGTH = 0.5, 0.1
#: points on the band for its 2D parts (its mean by the trapezoid rule)
BAND_POINTS = 41


@dataclass(frozen=True)
class FaceCoupling:
    """The sections across the face and how the gears couple them. ``zeta``: each section's
    place (fraction of the face width from its middle, −½ … ½), ``share``: its share of
    the face (the trapezoid rule's weights of a load linear between sections; they sum to
    one), ``spread`` (N × N): the finite-element approach at section s is Σ_t spread[s, t]
    times that of section t's line load spread evenly over the face; each row sums to one.
    ``across`` (N × N, rows summing to one, or None: ``spread``): the spread of the part
    of that approach that one tooth's load gives the other teeth, through the rims, where it
    is not the loaded tooth's own (gear 1's neighbours in 3D answer a load at one place
    almost evenly along the face: studies/face_neighbours.py); or (D × N × N) one for the
    teeth d = 1 … D apart, the last for those farther (:meth:`between`)."""

    zeta: np.ndarray
    share: np.ndarray
    spread: np.ndarray
    across: np.ndarray | None = None

    def between(self, apart: int) -> np.ndarray:
        """The spread of the approach that a load on one tooth gives a tooth ``apart`` teeth
        from it (0: its own)."""
        if apart == 0 or self.across is None:
            return self.spread
        if self.across.ndim == 2:
            return self.across
        return self.across[min(apart, len(self.across)) - 1]

    @property
    def sections(self) -> int:
        return len(self.zeta)


def exponential_kernel(decay: float) -> Callable[[np.ndarray], np.ndarray]:
    """A line load's finite-element approach along the face at a distance x (mm) from a load
    across a short length, per unit of that load spread evenly: exp(−|x|/λ)/(2λ), ``decay``
    λ (mm); it integrates to one over the line."""
    return lambda x: np.exp(-np.abs(x) / decay) / (2.0 * decay)


#: how :func:`face_coupling` corrects the kernel's weights row by row (every row sums to
#: one): "linear", a load linear across the face stays linear, its slope too; "slope", it
#: stays linear, its slope scaled as the kernel's own middle scales it; "scale", the rows'
#: sums alone
CORRECTIONS = ("linear", "slope", "scale")


def face_coupling(sections: int, width: float, kernel: Callable[[np.ndarray], np.ndarray],
                  mirror: bool = False, correction: str = "linear",
                  twist: float = 0.0) -> FaceCoupling:
    """``sections`` sections over a face ``width`` (mm) wide, the spread formed from the
    ``kernel`` over the face (:func:`kernel_weights`), then corrected row by row
    (:func:`correction_factors`): each row sums to one, so a load even across the face gives
    the 2D pair's approach everywhere. With ``twist`` c, the tooth's twist added:
    c P1 P1ᵀ diag(share), P1 the linear shape across the face (2ζ) less its mean, so a load
    at one end tilts the whole face: the loaded end gives more and the far end less than by
    the kernel alone, as the 3D tooth's do. Its rows sum to zero (P1's mean is zero), so the
    even load is untouched, and it is odd about mid-face, so a load at mid-face spreads as
    before (the product's: :data:`TWIST_TABLE`; docs/model.md, "The tooth's twist")."""
    z, share, w = kernel_weights(sections, width, kernel, mirror)
    spread = w * correction_factors(z, share, w, correction)
    zeta = z / width - 0.5
    if twist:
        spread = spread + twist * linear_tilt(zeta, share)
    return FaceCoupling(zeta, share, spread)


def linear_tilt(zeta: np.ndarray, share: np.ndarray) -> np.ndarray:
    """P1 P1ᵀ diag(share) (N × N): P1 the linear shape across the face (2ζ) less its mean, so
    its rows sum to zero and a load even across the face is untouched; a load at one end tilts
    the whole face by it (the tooth's twist, :func:`face_coupling`; the other teeth's tilts,
    :func:`tilted_across`)."""
    p1 = 2.0 * zeta - share @ (2.0 * zeta)
    return np.outer(p1, p1 * share)


def tilted_across(coupling: FaceCoupling, *tilts: float) -> FaceCoupling:
    """``coupling`` with the spreads between teeth ``across`` (:class:`FaceCoupling`) as
    gear 1's neighbours in 3D have them (:data:`NEIGHBOUR_TILTS`): the load even over the
    face plus each of ``tilts`` times :func:`linear_tilt`, for the teeth 1, 2, … apart (one
    tilt: one spread for all)."""
    even = np.outer(np.ones(len(coupling.share)), coupling.share)
    tilt = linear_tilt(coupling.zeta, coupling.share)
    spreads = [even + t * tilt for t in tilts]
    return replace(coupling, across=spreads[0] if len(spreads) == 1 else np.stack(spreads))


def correction_factors(z: np.ndarray, share: np.ndarray, w: np.ndarray,
                       correction: str) -> np.ndarray:
    """The factors c0 + c1 (z_t − z_s) by which row s of the weights ``w`` (sections z, mm,
    their ``share`` s of the face) is multiplied: "scale", c1 = 0 and the row sums to one;
    "linear", also Σ_t spread[s, t] z_t = z_s (a load linear across the face stays linear to
    its ends, where the kernel alone would level it off); "slope", Σ_t spread[s, t] (z_t − m)
    = α (z_s − m), m the face's middle, α the slope the rows' scales alone give a linear load
    (their least squares over the face): still linear, as the 3D tooth's answer is to within
    5 %, and less steep, as its is (0.80 of an even load's at mid-face on the baseline)."""
    if correction not in CORRECTIONS:
        raise ValueError(f"correction {correction!r}: one of {', '.join(CORRECTIONS)}")
    d = z[None, :] - z[:, None]
    m0 = w.sum(axis=1)
    if correction == "scale":
        return np.broadcast_to((1.0 / m0)[:, None], w.shape)
    e = z - 0.5 * (z[0] + z[-1])
    alpha = 1.0
    if correction == "slope":
        alpha = float(share @ (e * ((w / m0[:, None]) @ e)) / (share @ (e * e)))
    target = (alpha - 1.0) * e                 # Σ_t spread[s, t] (z_t − z_s)
    m1, m2 = (w * d).sum(axis=1), (w * d * d).sum(axis=1)
    det = m0 * m2 - m1 * m1
    c0, c1 = (m2 - m1 * target) / det, (m0 * target - m1) / det
    return c0[:, None] + c1[:, None] * d


def kernel_weights(sections: int, width: float, kernel: Callable[[np.ndarray], np.ndarray],
                   mirror: bool = False) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The sections' places z (mm from the first end), their shares of the face, and the
    ``kernel`` integrated over each section's hat φ_t: w[s, t] = ∫ k(z_s − z) φ_t(z) dz over
    the face, by Gauss quadrature; with ``mirror``, each load's images in the two free ends
    (at −z and 2b − z) added."""
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
        k = kernel(z[:, None] - x[None, :])
        if mirror:
            k = k + kernel(z[:, None] + x[None, :]) + kernel(z[:, None] + x[None, :] - 2 * width)
        k = k * (0.5 * h * wq)
        w[:, t] += k @ (1.0 - rising)
        w[:, t + 1] += k @ rising
    return z, share, w


def measured_kernel(tooth_height: float, near_share: float) -> Callable[[np.ndarray], np.ndarray]:
    """The finite-element part's kernel along the face (per mm; x in mm) from the 3D tooth's
    (:data:`KERNEL_TABLE`, scaled by the ``tooth_height`` h, mm): the 3D answer is the whole
    2D approach's, of which ``near_share`` (the half-plane's near field, which stays in its
    section) is taken off the table's first hat and the rest divided by the finite-element
    part's share, k = (τ − near_share δ) / (1 − near_share); clipped at zero."""
    table = np.array(KERNEL_TABLE) / tooth_height
    step = KERNEL_STEP * tooth_height
    table[0] = max(table[0] - near_share / step, 0.0)
    table /= 1.0 - near_share
    nodes = step * np.arange(len(table))
    return lambda x: np.interp(np.abs(x), nodes, table, right=0.0)


@dataclass(frozen=True)
class FlankBand:
    """A band on gear 1's tooth 0's loaded flank: polar angles ``lo`` … ``hi`` (rad, gear 1's
    frame) about ``centre``, at ``radius`` (mm); the working flank's top (the tip round's
    end) and the middle of the tooth space after it (rad), the tooth's height, tip less root
    radius (mm)."""

    lo: float
    hi: float
    centre: float
    radius: float
    top: float
    space: float
    tooth_height: float


def flank_band(shape: RoundedProfile, height: float, length: float) -> FlankBand:
    """The band ``length`` (mm) along the profile about ``height`` of the working flank by
    radius (0 its root, the tooth space's middle; 1 where the tip round starts) on
    ``shape``'s tooth 0."""
    def radius_at(phi):
        return float(shape.radius(np.array([phi]))[0])

    space = shape.phi_space + shape.pitch      # the tooth space after tooth 0's loaded flank
    rounds = [(c - h, c + h) for c, h, _ in shape.fillet_angles(range(-1, 2))]
    top = shape.profile.pieces[-1].phi0        # tooth 0's tip edge, or its round's end
    top = max([top] + [hi for lo, hi in rounds if lo <= top <= hi])
    root, upper = radius_at(space), radius_at(top)
    radius = root + height * (upper - root)
    centre = brentq(lambda x: radius_at(x) - radius, top, space)
    lo, hi = (_at_arc(shape, centre, s) for s in (-0.5 * length, 0.5 * length))
    return FlankBand(lo, hi, centre, radius, top, space, radius_at(shape.tooth_center) - root)


def _at_arc(shape: RoundedProfile, start: float, s: float) -> float:
    """The polar angle at arc length ``s`` (mm, signed) along the profile from ``start``."""
    def arc(x):
        q = shape.point(np.linspace(start, x, 201))
        return float(np.sum(np.hypot(*np.diff(q, axis=0).T)))

    step = 2 * abs(s) / float(shape.radius(np.array([start]))[0])  # the flank is steeper
    end = start + np.copysign(step, s)
    return brentq(lambda x: arc(x) - abs(s), start, end)


def flank_compliance(model: RingModel, band: FlankBand) -> tuple[float, float]:
    """Gear 1's 2D approach under a unit line load (N/mm) spread evenly over ``band``, the
    band's mean, µm per N/mm, as the face's sections split it: (the half-plane's near field,
    the finite-element part), each read as :mod:`.influence` forms A (the field at the
    matching depth, the half-plane's approach of the surface relative to it)."""
    side, shape, case = model.gears[0], model.shape, model.case
    phi = np.linspace(band.lo, band.hi, BAND_POINTS)
    x, normal, _ = shape.frame(phi)
    s = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(x, axis=0).T))])
    gq, gw = np.polynomial.legendre.leggauss(4)   # exact on the quadratic facets' shapes
    sq = 0.5 * (s[:-1] + s[1:])[:, None] + 0.5 * np.diff(s)[:, None] * gq
    wq = 0.5 * np.diff(s)[:, None] * gw
    xq, nq, _ = shape.frame(np.interp(sq.ravel(), s, phi))
    loads = side.nodal_loads(xq, -nq, np.zeros((len(xq), 1), dtype=int),
                             wq.reshape(-1, 1) * case.thickness)
    facet = side.facet_size(side.locate(x).local)
    depth = np.max(model.level.depth * facet[None, :] - np.abs(s[:, None] - s[None, :]),
                   axis=1)                        # the matching depth, as :mod:`.influence`'s
    at = side.locate(x - depth[:, None] * normal)
    fields = side.fields(loads, np.array([1.0]), np.unique(at.sector))
    rows = side.rows_at(side.cells(at.local), rotate(-normal, -at.turn))
    fe = np.array([(rows[i] @ fields[int(k)]).item() for i, k in enumerate(at.sector)])
    near = approach_matrix(s, depth, s, case.E, case.nu) @ np.ones(len(s))

    def mean(u):   # mm under 1 MPa → µm per N/mm of line load (1 MPa over the band)
        return 1e3 * float(np.trapezoid(u, s)) / s[-1] ** 2

    return mean(near), mean(fe)


def measured_coupling(model: RingModel, sections: int, width: float) -> FaceCoupling:
    """The face's coupling for ``model``'s pair (docs/model.md, "Across the face"):
    :func:`product_coupling` at gear 1's tooth height, with the near field's share read at
    mid-height of its working flank (:func:`flank_compliance`)."""
    band = flank_band(model.shape, BAND_HEIGHT, BAND_LENGTH * model.case.params.m)
    near, fe = flank_compliance(model, band)
    return product_coupling(sections, width, band.tooth_height, near / (near + fe))


def product_coupling(sections: int, width: float, tooth_height: float,
                     near_share: float) -> FaceCoupling:
    """The product's coupling of ``sections`` sections over a face ``width`` wide, gear 1's
    tooth ``tooth_height`` high (mm), the near field ``near_share`` of the 2D approach
    (:func:`measured_coupling` reads both off the pair): the tooth's own spread
    (:func:`tooth_coupling`, its twist read from :data:`TWIST_TABLE`), and the other teeth's
    spreads even over the face, tilted as gear 1's neighbours in 3D tilt
    (:data:`NEIGHBOUR_TILTS`, by :func:`neighbour_tilts`)."""
    own = tooth_coupling(sections, width, tooth_height, near_share,
                         twist_of(width, tooth_height))
    return tilted_across(own, *neighbour_tilts(width, tooth_height))


def tooth_coupling(sections: int, width: float, tooth_height: float, near_share: float,
                   twist: float) -> FaceCoupling:
    """A tooth's own spread as the product forms it, with the tooth's ``twist``
    (:func:`face_coupling`'s): the measured kernel mirrored in the free ends, its rows
    corrected ("slope"); no spread of its own between teeth (what the 3D tooth checks read:
    fegear.verify.face_slices)."""
    return face_coupling(sections, width, measured_kernel(tooth_height, near_share),
                         mirror=True, correction="slope", twist=twist)


#: the tooth's twist (:func:`face_coupling`'s ``twist``: c P1 P1ᵀ diag(share)) by the face
#: width in tooth heights b/h: c fitted to the end column (a load at one end) of gear 1's 3D
#: tooth at `standard`, on the baseline's tooth (docs/model.md, "The tooth's twist").
#: Reproduce (12 minutes): ``python studies/face_end_column.py --widths``
TWIST_TABLE = ((1.5, 0.3824), (2.0, 0.3523), (2.5, 0.3022), (3.3, 0.2009), (5.0, 0.0209))
#: the other teeth's tilts (:func:`tilted_across`) by the face width in tooth heights b/h:
#: the tilt c of gear 1's teeth 1, 2 and 3 apart from the loaded one (the last for all
#: farther), fitted to their answers in 3D to a load at one end of the loaded tooth, at
#: `standard`, on the baseline (docs/model.md, "The other teeth's part, in 3D"). Reproduce
#: (6 minutes): ``python studies/face_neighbours.py --widths``
NEIGHBOUR_TILTS = ((1.5, (0.11, -0.36, -0.24)), (2.0, (0.20, -0.34, -0.28)),
                   (2.5, (0.31, -0.31, -0.32)), (3.3, (0.52, -0.20, -0.34)),
                   (5.0, (0.97, 0.16, -0.18)))


def twist_of(width: float, tooth_height: float) -> float:
    """The twist coefficient of :data:`TWIST_TABLE` for a face ``width`` wide on a tooth
    ``tooth_height`` high (mm) (:func:`_by_width`)."""
    return _by_width(TWIST_TABLE, width / tooth_height)[0]


def neighbour_tilts(width: float, tooth_height: float) -> tuple[float, ...]:
    """The other teeth's tilts of :data:`NEIGHBOUR_TILTS` for a face ``width`` wide on a tooth
    ``tooth_height`` high (mm) (:func:`_by_width`)."""
    return _by_width(NEIGHBOUR_TILTS, width / tooth_height)


def _by_width(table, b_h: float) -> tuple[float, ...]:
    """A table's row ((b/h, value or values), …) at ``b_h``: each value linear in b/h between
    the table's widths, held beyond them."""
    b = np.array([w for w, _ in table])
    c = np.array([np.atleast_1d(v) for _, v in table], dtype=float)
    return tuple(float(np.interp(b_h, b, c[:, d])) for d in range(c.shape[1]))

"""Rounded tip edges of gear 1 for the stress model.

Gear 1's exact profile has a convex kink on each side of every tooth tip, where the far-side
branch (the tip trim) meets the working flank: 21° at r = 44.37 mm on the exact conjugate
baseline. Contact reaches that edge during the mesh cycle, and a kink inside a contact zone
makes the pressure logarithmically singular (p ~ E*γ/π · ln(1/x) for a slope change γ), so no
mesh converges to a peak value. Real teeth have an edge break; here every kink larger than
``KINK_DEG`` is replaced by a circular arc of radius ρ tangent to both sides. Material is only
removed, so clearances can only grow against the sharp profile's clearance table.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from ..errors import ParameterError
from .gear1 import Gear1Profile

KINK_DEG = 1.0  # tangent changes below this are left sharp (the root junction turns 0.015°)
NEWTON_STEPS = 30   # Newton steps for a round's tangent points …
NEWTON_TOL = 1e-13  # … until the two centres agree to this (mm)


@dataclass(frozen=True)
class Fillet:
    """An edge round: tangent at polar angles ``phi_a`` < ``phi_b`` (period frame, rad), centre
    (mm, gear 1's frame, tooth 0), radius (mm) and the kink angle it replaces (rad)."""

    phi_a: float
    phi_b: float
    centre: tuple[float, float]
    radius: float
    kink: float


class RoundedProfile:
    """Gear 1's profile with its tip edges rounded to radius ``radius`` (0: the exact profile).

    Offers the parts of :class:`Gear1Profile` the FE scene uses: ``radius``, ``curvature``,
    ``pitch``, ``phi_space``, ``tooth_center`` and ``pieces``.
    """

    def __init__(self, profile: Gear1Profile, radius: float) -> None:
        self.profile = profile
        self.radius_mm = float(radius)
        self.pitch = profile.pitch
        self.phi_space = profile.phi_space
        self.tooth_center = profile.tooth_center
        self.kinks = tuple(k for k in (self._kink(pc.phi0) for pc in profile.pieces[1:]) if k)
        try:
            self.fillets = _fillets_of(profile, self.radius_mm) if self.radius_mm > 0 else ()
        except _NoFit:
            largest = largest_round(profile, self.radius_mm)
            raise ParameterError("tip-round", radius, f"0 <= tip-round <= "
                                 f"{math.floor(largest * 1e4) / 1e4:.4f} mm here (the "
                                 "largest round that fits gear 1's tip edges)") from None

    def _kink(self, phi: float) -> tuple[float, float] | None:
        """The convex kink at a piece junction (its angle, rad), if larger than KINK_DEG: a
        concave one (where two relieved tops meet in the middle of a tooth, say) is a notch
        no contact reaches, and no round fits it."""
        ev = self.profile.evaluate(np.array([phi - 1e-10, phi + 1e-10]))
        t0, t1 = ev.tangent
        gamma = math.atan2(t0[0] * t1[1] - t0[1] * t1[0], t0 @ t1)   # > 0: convex
        return (phi, gamma) if math.degrees(gamma) > KINK_DEG else None

    def _centres(self, phi: np.ndarray) -> np.ndarray:
        """Centres (n, 2) of circles of the radius tangent to the profile at angles ``phi``."""
        ev = self.profile.evaluate(phi)
        return ev.q - self.radius_mm * ev.normal

    def _fillets(self) -> tuple[Fillet, ...]:
        """The round of every kink: its tangent points φa < φc < φb are where the circles
        tangent on either side have one centre, c(φa) = c(φb). Newton on the unknowns
        log(φc − φa), log(φb − φc), which keep the points on their sides (from r_c alone both
        fell onto the kink), for all kinks at once; the Jacobian by differences in one
        evaluation with the residual."""
        rho = self.radius_mm
        phi_c = np.array([phi for phi, _ in self.kinks])
        gamma = np.array([g for _, g in self.kinks])
        if len(phi_c) == 0:
            return ()
        # start: the tangent length ρ tan(γ/2) as a polar angle on each side (the flank is
        # steep: arc length per radian is several times the radius)
        eps = 1e-7
        q = self.profile.evaluate(np.concatenate([phi_c - eps, phi_c - 2 * eps, phi_c + eps,
                                                  phi_c + 2 * eps])).q.reshape(4, -1, 2)
        speed = (np.linalg.norm(q[0] - q[1], axis=1) / eps,
                 np.linalg.norm(q[3] - q[2], axis=1) / eps)
        tangent = rho * np.tan(0.5 * gamma)
        x = np.column_stack([np.log(tangent / speed[0]), np.log(tangent / speed[1])])
        step = 1e-7   # relative, in the log unknowns
        for i in range(NEWTON_STEPS + 1):
            phi = np.concatenate([phi_c - np.exp(x[:, 0]), phi_c + np.exp(x[:, 1]),
                                  phi_c - np.exp(x[:, 0] + step), phi_c + np.exp(x[:, 1] + step)])
            c = self._centres(phi).reshape(4, -1, 2)
            residual = c[0] - c[1]
            if (np.abs(residual).max() <= NEWTON_TOL or not np.all(np.isfinite(residual))
                    or i == NEWTON_STEPS):   # the residual is that of x
                break
            jac = np.stack([(c[2] - c[0]) / step, -(c[3] - c[1]) / step], axis=2)
            try:
                x = x - np.clip(np.linalg.solve(jac, residual[..., None])[..., 0], -1.0, 1.0)
            except np.linalg.LinAlgError:
                break
        out = []
        for k, (pc, g) in enumerate(zip(phi_c, gamma)):
            phi_a, phi_b = float(pc - math.exp(x[k, 0])), float(pc + math.exp(x[k, 1]))
            ev = self.profile.evaluate(np.array([phi_a, phi_b]))
            side_ok = phi_a < pc < phi_b and phi_b - phi_a < 0.25 * self.pitch
            curv_ok = np.all(ev.kappa * rho > -1.0) and np.all(ev.kappa * rho < 1.0)
            if not np.all(np.abs(residual[k]) <= 1e-9) or not side_ok or not curv_ok:
                raise _NoFit
            c = self._centres(np.array([phi_a]))[0]
            out.append(Fillet(phi_a, phi_b, (float(c[0]), float(c[1])), rho, float(g)))
        return tuple(out)

    def _on_fillet(self, phi: np.ndarray):
        """Per angle: index of the fillet it falls on (−1: none) and the local angle."""
        rel = np.mod(phi - self.phi_space, 2 * np.pi)
        local = self.phi_space + np.mod(rel, self.pitch)
        which = np.full(phi.shape, -1)
        for k, f in enumerate(self.fillets):
            which[(local >= f.phi_a) & (local <= f.phi_b)] = k
        return which, local

    def on_round(self, phi: np.ndarray) -> np.ndarray:
        """Whether each polar angle (rad, any tooth) falls on a tip-edge round."""
        return self._on_fillet(np.atleast_1d(np.asarray(phi, dtype=float)))[0] >= 0

    def radius(self, phi: np.ndarray) -> np.ndarray:
        """Polar radius (mm) of the rounded profile (the exact profile's is inverted only off
        the rounds: on a grid across an edge contact, half its points are on a round)."""
        phi = np.atleast_1d(np.asarray(phi, dtype=float))
        which, local = self._on_fillet(phi)
        r = np.empty(phi.shape)
        off = which < 0
        if off.any():
            r[off] = self.profile.radius(phi[off])
        for k, f in enumerate(self.fillets):
            sel = which == k
            if sel.any():
                e = np.column_stack([np.cos(local[sel]), np.sin(local[sel])])
                ec = e @ np.asarray(f.centre)
                r[sel] = ec + np.sqrt(ec**2 - np.dot(f.centre, f.centre) + f.radius**2)
        return r

    def curvature(self, phi: np.ndarray) -> np.ndarray:
        """Curvature (1/mm, > 0 convex) of the rounded profile."""
        phi = np.atleast_1d(np.asarray(phi, dtype=float))
        which, _ = self._on_fillet(phi)
        kappa = np.empty(phi.shape)
        off = which < 0
        if off.any():
            kappa[off] = self.profile.evaluate(phi[off]).kappa
        for k, f in enumerate(self.fillets):
            kappa[which == k] = 1.0 / f.radius
        return kappa

    def point(self, phi: np.ndarray) -> np.ndarray:
        phi = np.atleast_1d(np.asarray(phi, dtype=float))
        r = self.radius(phi)
        return np.column_stack([r * np.cos(phi), r * np.sin(phi)])

    def frame(self, phi: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Points (n, 2), unit normals out of gear 1's material and curvature (1/mm, > 0
        convex) at polar angles ``phi``, exact on the flanks and on the rounds."""
        phi = np.atleast_1d(np.asarray(phi, dtype=float))
        which, local = self._on_fillet(phi)
        points, normal = np.empty((len(phi), 2)), np.empty((len(phi), 2))
        kappa = np.empty(len(phi))
        off = which < 0
        if off.any():
            ev = self.profile.evaluate(phi[off])
            points[off], normal[off], kappa[off] = ev.q, ev.normal, ev.kappa
        for k, f in enumerate(self.fillets):
            sel = which == k
            if sel.any():
                turn = phi[sel] - local[sel]  # whole pitches back to the period frame
                q = self.point(phi[sel])
                c = np.asarray(f.centre)
                centre = np.column_stack([np.cos(turn) * c[0] - np.sin(turn) * c[1],
                                          np.sin(turn) * c[0] + np.cos(turn) * c[1]])
                points[sel] = q
                normal[sel] = (q - centre) / f.radius
                kappa[sel] = 1.0 / f.radius
        return points, normal, kappa

    def fillet_angles(self, tooth_turns: range) -> list[tuple[float, float, float]]:
        """(centre angle, half-angle, kink) of every fillet of the given tooth turns (rad)."""
        out = []
        for t in tooth_turns:
            for f in self.fillets:
                out.append((0.5 * (f.phi_a + f.phi_b) + t * self.pitch,
                            0.5 * (f.phi_b - f.phi_a), f.kink))
        return out


class _NoFit(Exception):
    """A round does not fit a tip edge (told by :class:`RoundedProfile` with its range)."""


def fits(profile: Gear1Profile, radius: float) -> bool:
    """Whether a round of ``radius`` (mm) fits every tip edge of ``profile``."""
    try:
        _fillets_of(profile, float(radius))
    except _NoFit:
        return False
    return True


@lru_cache(maxsize=64)
def _fillets_of(profile: Gear1Profile, radius: float) -> tuple[Fillet, ...]:
    """The rounds of radius ``radius`` (mm) on ``profile``'s tip edges (raises ``_NoFit``),
    kept for the last few: a solve's checks ask whether the default round fits, and its model
    then rounds the same edges."""
    shape = RoundedProfile.__new__(RoundedProfile)
    shape.profile, shape.radius_mm, shape.pitch = profile, radius, profile.pitch
    shape.kinks = tuple(k for k in (shape._kink(pc.phi0) for pc in profile.pieces[1:]) if k)
    return shape._fillets()


def largest_round(profile: Gear1Profile, upper: float) -> float:
    """The largest tip round (mm) below ``upper`` that fits every tip edge, by bisection to
    1e-5 of ``upper`` (a round fits below a radius where it fits: the tangent points only
    move apart as it grows)."""
    good, bad = 0.0, upper
    if fits(profile, bad):
        return bad
    while bad - good > 1e-5 * upper:
        mid = 0.5 * (good + bad)
        good, bad = (mid, bad) if fits(profile, mid) else (good, mid)
    return good


@lru_cache(maxsize=64)
def default_round(profile: Gear1Profile, nominal: float) -> float:
    """The tip round a solve takes when none is given: ``nominal`` (mm), or half the largest
    round that fits where ``nominal`` does not (docs/cli.md). Kept for the last few profiles
    (:func:`~.gear1.gear1_profile` keeps them): a study's cases of one pair at other torques
    each ask, and where ``nominal`` does not fit, the answer is a bisection of fillets (the
    fillets of a round that fits are kept anyway: :func:`_fillets_of`)."""
    if fits(profile, nominal):
        return nominal
    return 0.5 * largest_round(profile, nominal)

"""The penalty contact's model: pairs (a slave boundary against a master body's exact curve),
the penalty settings, and the condensed problem :class:`ContactModel` that :mod:`.solve`
solves.

The formulation is in the package docstring (:mod:`fegear.verify.penalty`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from ...contact import CurvePoints, ExactCurve
from ...errors import ContactError  # noqa: F401  (fegear.verify.penalty.ContactError)

if TYPE_CHECKING:  # the settings and curves are light; the model's parts come with the solve
    import scipy.sparse as sp

    from ...fe import Body
    from .flexibility import PointFlexibility


@dataclass(frozen=True)
class Circle:
    """A circle of ``radius`` (mm) about ``center``; ``material`` is ``"inside"`` (a disk) or
    ``"outside"`` (a bore)."""

    center: tuple[float, float]
    radius: float
    material: str = "inside"

    def closest(self, points: np.ndarray) -> CurvePoints:
        x = np.asarray(points, dtype=float)
        c = np.asarray(self.center)
        r = x - c
        rho = np.linalg.norm(r, axis=1)
        e = r / rho[:, None]
        foot = c + self.radius * e
        # ρ − R as (|x|² − 2 x·c + |c|² − R²) / (ρ + R): for a circle through the origin (the
        # Hertz cases touch there) |c|² − R² is exactly 0 and nothing cancels, whereas x − c
        # rounds a 1e-12 mm penetration against R = 48 mm to 0.4 % (1e-14 mm)
        excess = (np.einsum("ij,ij->i", x, x) - 2.0 * x @ c + (c @ c - self.radius**2)) / (
            rho + self.radius)
        if self.material == "inside":
            return CurvePoints(foot, e, excess)
        return CurvePoints(foot, -e, -excess)

    def project(self, points: np.ndarray) -> np.ndarray:
        return self.closest(points).foot


@dataclass(frozen=True)
class ContactPair:
    """Slave boundary ``slave_boundary`` of body ``slave`` against the exact curve of the master
    body ``master``, whose mesh facets ``master_boundary`` carry its displacement."""

    name: str
    slave: int
    slave_boundary: str
    master: int
    master_boundary: str
    master_curve: ExactCurve


@dataclass(frozen=True)
class ContactSettings:
    """Penalty κ_i = ``penalty_factor`` · E*/h_i (MPa/mm) at slave node i, E* the Hertz contact
    modulus of the pair, h_i the length of the slave facets around the node (a uniform κ from
    the mean length was soft on a tip round meshed 100× finer than the flank: the edge peak
    moved by 23 % between penalty factors 30 and 3000). ``gauss_points`` per half of a slave
    facet. Convergence: the active set is stable, the link motion changes by < ``link_tol``
    (relative) and the largest penetration
    is below ``penetration_tol`` times the contact half-width."""

    penalty_factor: float = 300.0
    gauss_points: int = 3
    max_iterations: int = 60
    link_tol: float = 1e-10
    penetration_tol: float = 0.01


@dataclass(frozen=True, eq=False)
class ContactModel:
    """The condensed contact problem (fixed pairing). Arrays are per contact node (the slave
    nodes carrying a weighted gap), except the ``quad_*`` arrays, per quadrature point."""

    bodies: tuple[Body, ...] = field(repr=False)
    pairs: tuple[ContactPair, ...]
    settings: ContactSettings
    pair_index: np.ndarray = field(repr=False)   # (n,) which pair
    x: np.ndarray = field(repr=False)            # (n, 2) slave nodes, slave body frame, mm
    node: np.ndarray = field(repr=False)         # (n,) their indices in the slave mesh
    weight: np.ndarray = field(repr=False)       # (n,) D_i = ∫ φ_i t ds, mm²
    arc: np.ndarray = field(repr=False)          # (n,) arc length along the slave boundary, mm
    quad_x: np.ndarray = field(repr=False)       # (nq, 2) slave quadrature points, body frame
    quad_pair: np.ndarray = field(repr=False)    # (nq,) which pair
    average: sp.csr_matrix = field(repr=False)   # (n, nq) g̃ = average @ g_q
    C: tuple[sp.csr_matrix, ...] = field(repr=False)  # per body, g̃_elastic = Σ C_b v_b
    G: PointFlexibility = field(repr=False)      # (n, n) flexibility, mm/N
    kappa: np.ndarray = field(repr=False)        # (n,) penalty, MPa/mm
    link_body: int | None
    dropped: int                                  # slave points with no master facet under them

    @property
    def npoints(self) -> int:
        return len(self.x)

    def gap0(self, value: float) -> tuple[np.ndarray, np.ndarray]:
        """Weighted gap of the undeformed bodies with the link moved by ``value``, and its
        derivative a."""
        g = np.empty(len(self.quad_x))
        a = np.zeros(len(self.quad_x))
        for k in range(len(self.pairs)):
            sel = self.quad_pair == k
            cp, a[sel] = self.exact_gap(k, self.quad_x[sel], value)
            g[sel] = cp.distance
        g, a = self.average @ g, self.average @ a
        lb = self.link_body
        if lb is not None and not self.bodies[lb].is_mechanism:
            a = self.C[lb] @ self.bodies[lb].psi
            g = g + value * a
        return g, a

    def exact_gap(self, k: int, x: np.ndarray, value: float) -> tuple[CurvePoints, np.ndarray]:
        """Closest points on pair k's master curve (fixed frame) of slave points x (slave body
        frame, (n, 2)) when a mechanism link is moved exactly by ``value``, and d(gap)/d(value)
        (0 if the link does not move either body of the pair)."""
        pair = self.pairs[k]
        slave = self.bodies[pair.slave]
        lb = self.link_body
        moves = lb is not None and self.bodies[lb].is_mechanism and lb in (pair.slave,
                                                                           pair.master)
        if not moves:
            return pair.master_curve.closest(slave.placement.to_fixed(x)), np.zeros(len(x))
        body = self.bodies[lb]
        if lb == pair.slave:
            moved = body.link.move(x, value)
            cp = pair.master_curve.closest(body.placement.to_fixed(moved))
            velocity = body.placement.vec_to_fixed(body.link.velocity(moved))
            return cp, np.sum(cp.normal * velocity, axis=1)
        # the master moves by +value: equivalently the slave point moves by −value in its frame
        y = body.link.move(body.placement.to_body(slave.placement.to_fixed(x)), -value)
        cp = pair.master_curve.closest(body.placement.to_fixed(y))
        velocity = body.placement.vec_to_fixed(body.link.velocity(y))
        return cp, -np.sum(cp.normal * velocity, axis=1)

"""Contact stage: frictionless penalty contact between linear bodies, condensed on contact points.

Small sliding (DOMAIN.md §3): every quadrature point x_q of a slave boundary is paired once, in
the reference configuration, with its closest point y_q on the master's *exact* curve and with
the master mesh facet under y_q. The gap

    g_q = g0_q(θ) + n_q · (v_slave(x_q) − v_master(y_q))

carries the rigid link motion θ exactly (``g0`` is the signed distance of the moved slave point
from the moved exact master curve) and the elastic displacements v linearly, through sparse rows
C_b (g_elastic = Σ_b C_b v_b). The penalty traction is p_q = κ·max(0, −g_q) (MPa) and the force
at the point λ_q = p_q w_q (N), w_q the quadrature weight times the thickness (mm²).

Each body is factorised once (:mod:`fegear.assembly`); condensing onto the contact points gives
the flexibility G = Σ_b C_b K_b⁻¹ C_bᵀ (mm/N), and the contact problem becomes small and dense:
on the active set A, (G_AA + W_A⁻¹/κ) λ_A + a_A θ = −h_A, with the link balance k θ − aᵀλ = F.
Active-set (semismooth Newton) iterations stop when A is stable; the link motion is then
re-evaluated exactly until it changes by less than ``link_tol``.
"""

from __future__ import annotations

import logging
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Protocol

import numpy as np
import scipy.sparse as sp

from .assembly import Body, facet_nodes
from .errors import FegearError

log = logging.getLogger(__name__)


class ContactError(FegearError):
    """The contact problem has no admissible solution or the iterations did not converge."""


@dataclass(frozen=True)
class CurvePoints:
    """Closest points on an exact curve: feet (n, 2), unit normals pointing out of the body's
    material (n, 2), signed distances (n,) in mm, positive outside the material."""

    foot: np.ndarray
    normal: np.ndarray
    distance: np.ndarray


class ExactCurve(Protocol):
    def closest(self, points: np.ndarray) -> CurvePoints: ...


@dataclass(frozen=True)
class Circle:
    """A circle of ``radius`` (mm) about ``center``; ``material`` is ``"inside"`` (a disk) or
    ``"outside"`` (a bore)."""

    center: tuple[float, float]
    radius: float
    material: str = "inside"

    def closest(self, points: np.ndarray) -> CurvePoints:
        r = np.asarray(points, dtype=float) - np.asarray(self.center)
        rho = np.linalg.norm(r, axis=1)
        e = r / rho[:, None]
        foot = np.asarray(self.center) + self.radius * e
        if self.material == "inside":
            return CurvePoints(foot, e, rho - self.radius)
        return CurvePoints(foot, -e, self.radius - rho)

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
    """Penalty κ = ``penalty_factor`` · E*/h (MPa/mm), E* the Hertz contact modulus of the pair,
    h the mean slave facet length. ``gauss_points`` per slave facet. Convergence: the active set
    is stable, the link motion changes by < ``link_tol`` (relative) and the largest penetration
    is below ``penetration_tol`` times the contact half-width."""

    penalty_factor: float = 300.0
    gauss_points: int = 3
    max_iterations: int = 60
    link_tol: float = 1e-10
    penetration_tol: float = 0.01


@dataclass(frozen=True, eq=False)
class ContactModel:
    """The condensed contact problem (fixed pairing). Arrays are per contact point."""

    bodies: tuple[Body, ...] = field(repr=False)
    pairs: tuple[ContactPair, ...]
    settings: ContactSettings
    pair_index: np.ndarray = field(repr=False)   # (nq,) which pair
    x: np.ndarray = field(repr=False)            # (nq, 2) slave points, slave body frame, mm
    weight: np.ndarray = field(repr=False)       # (nq,) w·|dx/ds|·t, mm²
    arc: np.ndarray = field(repr=False)          # (nq,) arc length along the slave boundary, mm
    C: tuple[sp.csr_matrix, ...] = field(repr=False)  # per body, gap_elastic = Σ C_b v_b
    G: np.ndarray = field(repr=False)            # (nq, nq) flexibility, mm/N
    kappa: float                                  # penalty, MPa/mm
    h: float                                      # mean slave facet length, mm
    link_body: int | None
    dropped: int                                  # slave points with no master facet under them

    @property
    def npoints(self) -> int:
        return len(self.x)

    def gap0(self, value: float) -> tuple[np.ndarray, np.ndarray]:
        """Gap of the undeformed bodies with the link moved by ``value``, and its derivative a."""
        g = np.empty(self.npoints)
        a = np.zeros(self.npoints)
        for k in range(len(self.pairs)):
            sel = self.pair_index == k
            cp, a[sel] = self.exact_gap(k, self.x[sel], value)
            g[sel] = cp.distance
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


def p2_edge_shape(s: np.ndarray) -> np.ndarray:
    """Quadratic shape functions on a facet, s ∈ [0, 1]: (n, 3) for corner 0, corner 1, mid."""
    s = np.asarray(s, dtype=float)
    return np.column_stack([(1 - s) * (1 - 2 * s), s * (2 * s - 1), 4 * s * (1 - s)])


def _p2_edge_dshape(s: np.ndarray) -> np.ndarray:
    return np.column_stack([4 * s - 3, 4 * s - 1, 4 - 8 * s])


def facet_curve(body: Body, facets: np.ndarray, s: np.ndarray):
    """Points, tangents (d/ds) and nodes of quadratic facets at local coordinates s."""
    nodes = facet_nodes(body.mesh, facets)
    X = body.mesh.doflocs.T[nodes]  # (n, 3, 2)
    return (np.einsum("nk,nkd->nd", p2_edge_shape(s), X),
            np.einsum("nk,nkd->nd", _p2_edge_dshape(s), X), nodes)


def locate_on_facets(body: Body, facets: np.ndarray,
                     y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Facet (from ``facets``) and local coordinate under each point y; s outside [0, 1] means
    the point is not covered by these facets."""
    nodes = facet_nodes(body.mesh, facets)
    a = body.mesh.doflocs.T[nodes[:, 0]]
    b = body.mesh.doflocs.T[nodes[:, 1]]
    ab = b - a
    t = np.einsum("qfd,fd->qf", y[:, None, :] - a[None], ab) / np.sum(ab * ab, axis=1)
    near = a[None] + np.clip(t, 0, 1)[..., None] * ab[None]
    best = np.argmin(np.sum((near - y[:, None, :]) ** 2, axis=2), axis=1)
    f = facets[best]
    s = t[np.arange(len(y)), best]
    for _ in range(4):  # Newton on the quadratic facet curve
        xs, dx, _ = facet_curve(body, f, s)
        d2 = np.einsum("k,nkd->nd", np.array([4.0, 4.0, -8.0]),
                       body.mesh.doflocs.T[facet_nodes(body.mesh, f)])
        r = xs - y
        s = s - np.sum(r * dx, axis=1) / (np.sum(dx * dx, axis=1) + np.sum(r * d2, axis=1))
    return f, s


def build_contact(bodies: Sequence[Body], pairs: Sequence[ContactPair],
                  settings: ContactSettings = ContactSettings()) -> ContactModel:
    """Pair the slave quadrature points, build the gap rows and condense the flexibility.

    Bodies sit at their ``placement``; slave points and rows are kept in body frames. The
    flexibility is taken from each body's nodal flexibility on its contact boundaries
    (computed once per body and boundary set, then reused for every pairing)."""
    bodies = tuple(bodies)
    links = [i for i, b in enumerate(bodies) if b.link is not None]
    if len(links) > 1:
        raise ContactError("at most one body may carry a rigid link (the load-controlled one)")
    gauss, gw = np.polynomial.legendre.leggauss(settings.gauss_points)
    gauss, gw = 0.5 * (gauss + 1.0), 0.5 * gw

    parts = {k: [] for k in ("pair", "x", "w", "arc", "rows")}
    lengths, moduli, dropped = [], [], 0
    for k, pair in enumerate(pairs):
        sb, mb = bodies[pair.slave], bodies[pair.master]
        facets, flipped = _ordered(sb, pair.slave_boundary)
        nf = len(facets)
        s = np.tile(gauss, nf)
        s_arc = np.where(np.repeat(flipped, len(gauss)), 1.0 - s, s)  # along the chain
        x, dx, nodes = facet_curve(sb, np.repeat(facets, len(gauss)), s)
        w = np.tile(gw, nf) * np.linalg.norm(dx, axis=1) * sb.material.thickness
        seg = np.linalg.norm(np.diff(sb.mesh.doflocs.T[facet_nodes(sb.mesh, facets)[:, :2]],
                                     axis=1)[:, 0], axis=1)
        arc = (np.repeat(np.concatenate([[0.0], np.cumsum(seg)[:-1]]), len(gauss))
               + s_arc * np.repeat(seg, len(gauss)))
        cp = pair.master_curve.closest(sb.placement.to_fixed(x))
        mf, ms = locate_on_facets(mb, mb.mesh.boundaries[pair.master_boundary],
                                  mb.placement.to_body(cp.foot))
        ok = (ms > -1e-9) & (ms < 1 + 1e-9)
        dropped += int(np.count_nonzero(~ok))
        _, _, mnodes = facet_curve(mb, mf[ok], ms[ok])
        n_fixed = cp.normal[ok]
        parts["rows"].append([
            (pair.slave, nodes[ok], p2_edge_shape(s[ok]), sb.placement.vec_to_body(n_fixed)),
            (pair.master, mnodes, -p2_edge_shape(np.clip(ms[ok], 0, 1)),
             mb.placement.vec_to_body(n_fixed))])
        parts["pair"].append(np.full(np.count_nonzero(ok), k))
        parts["x"].append(x[ok])
        parts["w"].append(w[ok])
        parts["arc"].append(arc[ok])
        lengths.append(seg)
        moduli.append(1.0 / (1.0 / sb.material.plane_modulus + 1.0 / mb.material.plane_modulus))

    nq = sum(len(p) for p in parts["pair"])
    if nq == 0:
        raise ContactError("no slave point has a master facet under it: check the contact pairs")
    offsets = np.cumsum([0] + [len(p) for p in parts["pair"]])
    C, G = [], np.zeros((nq, nq))
    for b, body in enumerate(bodies):
        names = sorted({p.slave_boundary for p in pairs if p.slave == b}
                       | {p.master_boundary for p in pairs if p.master == b})
        if not names:
            C.append(sp.csr_matrix((nq, body.ndofs)))
            continue
        window = np.unique(np.concatenate(
            [facet_nodes(body.mesh, body.mesh.boundaries[n]).ravel() for n in names]))
        local = np.full(body.mesh.doflocs.shape[1], -1)
        local[window] = np.arange(len(window))
        rows_, cols_, vals_ = [], [], []
        for k in range(len(pairs)):
            rows = np.arange(offsets[k], offsets[k + 1])
            for owner, nodes, shape, normal in parts["rows"][k]:
                if owner != b:
                    continue
                cols = 2 * local[nodes]  # (n, 3)
                for j in range(3):
                    for d in range(2):
                        rows_.append(rows)
                        cols_.append(cols[:, j] + d)
                        vals_.append(shape[:, j] * normal[:, d])
        Cs = sp.coo_matrix((np.concatenate(vals_), (np.concatenate(rows_),
                                                    np.concatenate(cols_))),
                           shape=(nq, 2 * len(window))).tocsr()  # duplicates summed
        F = body.flexibility(window)
        G += Cs @ (Cs @ F).T  # C F Cᵀ, F symmetric; C sparse, so no dense product
        dofs = body.node_dofs(window).ravel()  # window columns → the body's dofs
        C.append(sp.csr_matrix((Cs.data, dofs[Cs.indices], Cs.indptr), shape=(nq, body.ndofs)))
    h = float(np.mean(np.concatenate(lengths)))
    kappa = settings.penalty_factor * min(moduli) / h
    return ContactModel(bodies, tuple(pairs), settings, np.concatenate(parts["pair"]),
                        np.vstack(parts["x"]), np.concatenate(parts["w"]),
                        np.concatenate(parts["arc"]), tuple(C), G,
                        kappa, h, links[0] if links else None, dropped)


def _ordered(body: Body, name: str) -> tuple[np.ndarray, np.ndarray]:
    """Facets of a boundary chained end to end (so that arc length is meaningful), and whether
    each runs against the chain (its second corner comes first)."""
    facets = np.asarray(body.mesh.boundaries[name])
    ends = body.mesh.facets[:, facets].T
    count = np.bincount(ends.ravel(), minlength=body.mesh.nvertices)
    start = [n for n in ends.ravel() if count[n] == 1]
    node = start[0] if start else ends[0, 0]
    order, flipped, used = [], [], np.zeros(len(facets), bool)
    for _ in range(len(facets)):
        hit = np.flatnonzero(~used & ((ends[:, 0] == node) | (ends[:, 1] == node)))
        if len(hit) == 0:
            raise ContactError(f"boundary {name!r} of {body.name!r} is not one connected curve")
        i = hit[0]
        used[i] = True
        order.append(i)
        flipped.append(bool(ends[i, 0] != node))
        node = ends[i, 1] if ends[i, 0] == node else ends[i, 0]
    return facets[np.array(order)], np.array(flipped)

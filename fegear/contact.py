"""Contact stage: frictionless penalty contact between linear bodies, condensed on contact nodes.

Small sliding (DOMAIN.md §3): every quadrature point x_q of a slave boundary is paired once, in
the reference configuration, with its closest point y_q on the master's *exact* curve and with
the master mesh facet under y_q. The pointwise gap

    g_q = g0_q(θ) + n_q · (v_slave(x_q) − v_master(y_q))

carries the rigid link motion θ exactly (``g0`` is the signed distance of the moved slave point
from the moved exact master curve) and the elastic displacements v linearly.

The penalty acts on *weighted* gaps at the slave corner nodes (a mortar-type,
segment-to-segment discretisation): with φ_i the linear hat of corner node i on the slave chain,
D_i = ∫ φ_i t ds (mm²) and g̃_i = ∫ φ_i g t ds / D_i, the node force is λ_i = κ_i D_i max(0, −g̃_i)
(N) and the pressure κ_i max(0, −g̃_i) (MPa). One constraint per facet, not one per quadrature
point or per node: with quadratic displacements, pointwise penalties (3 per facet) and hats on
corner and midside nodes (2 per facet) both over-constrain the interface, and on a tip round
a few elements wide their tractions oscillated from point to point by up to ±40 % and grew
with the penalty. The hats are non-negative and sum to one, so a uniform pressure is
integrated exactly (patch test). Elastically, g̃ = Σ_b C_b v_b through sparse rows C_b.

Each body is factorised once (:mod:`fegear.assembly`); condensing onto the contact nodes gives
the flexibility G = Σ_b C_b K_b⁻¹ C_bᵀ (mm/N; a column is formed when the active set first
reaches its point, :class:`PointFlexibility`), and the contact problem becomes small and dense:
on the active set A, (G_AA + W_A⁻¹/κ) λ_A + a_A θ = −h_A, with the link balance k θ − aᵀλ = F.
Active-set (semismooth Newton) iterations stop when A is stable; the link motion is then
re-evaluated exactly until it changes by less than ``link_tol``.
"""

from __future__ import annotations

import logging
import time
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Protocol

import numpy as np
import scipy.sparse as sp
from scipy.spatial import cKDTree

from .assembly import Body, WindowFlexibility, facet_nodes
from .errors import FegearError
from .hertz import contact_modulus

log = logging.getLogger(__name__)

LOCATE_CANDIDATES = 16  # chord pieces tried per point first (then 8×, 64×, … up to all)


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


class PointFlexibility:
    """G = Σ_b C_b F_b C_bᵀ (n × n, mm/N), the flexibility of the contact points, with F_b the
    body's nodal flexibility on its contact boundaries (:class:`WindowFlexibility`) and C_b
    the weighted-gap rows over them.

    Only the columns of points that carry a force are ever used (G λ and G_AA on the active
    set), so a column is formed when first asked for and kept: column j needs the rows of F_b
    at the dofs of row j of C_b, and those are formed (one solve each) only then, once per
    body frame, whichever position first asks. ``seconds`` is the time spent forming columns."""

    def __init__(self, parts: Sequence[tuple[sp.csr_matrix, WindowFlexibility]], n: int):
        self._parts = tuple(parts)  # (C_b over the window's dofs, F_b)
        self.shape = (n, n)
        self._slot = np.full(n, -1, dtype=np.int64)
        self._columns = np.empty((n, 0))
        self.seconds = 0.0

    def columns(self, idx) -> np.ndarray:
        """G[:, idx], (n, len(idx))."""
        idx = np.asarray(idx, dtype=np.int64)
        new = np.unique(idx[self._slot[idx] < 0])
        if len(new):
            t0 = time.perf_counter()
            block = np.zeros((self.shape[0], len(new)))
            for C, F in self._parts:
                rows = C[new]
                dofs = np.unique(rows.indices)
                X = rows[:, dofs] @ F.rows(dofs)  # C[new] F, with F symmetric
                block += C @ np.ascontiguousarray(X.T)
            self._slot[new] = self._columns.shape[1] + np.arange(len(new))
            self._columns = np.hstack([self._columns, block])
            self.seconds += time.perf_counter() - t0
        return self._columns[:, self._slot[idx]]

    @property
    def formed(self) -> int:
        """Columns formed so far."""
        return int(np.count_nonzero(self._slot >= 0))

    def block(self, idx) -> np.ndarray:
        """G[idx][:, idx]."""
        return self.columns(idx)[idx]

    def toarray(self) -> np.ndarray:
        return self.columns(np.arange(self.shape[0]))

    def __matmul__(self, v: np.ndarray) -> np.ndarray:
        nz = np.flatnonzero(v)
        return self.columns(nz) @ v[nz]


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


def nearest_chords(a: np.ndarray, ab: np.ndarray, y: np.ndarray
                   ) -> tuple[np.ndarray, np.ndarray]:
    """Per point y (n, 2): the chord a + t·ab (t ∈ [0, 1]) nearest to it and the unclipped
    t of its foot.

    Chords longer than the mean are cut into pieces no longer than it, and the nearest chord is
    searched among the owners of the ``LOCATE_CANDIDATES`` pieces with the nearest midpoints.
    The result is sure when the farthest of those midpoints is at least the best distance plus
    half the longest piece away (the foot on the nearest chord lies on some piece, whose
    midpoint is then no farther); the other points are searched again among eight times as
    many pieces, up to all of them."""
    length = np.sqrt(np.sum(ab * ab, axis=1))
    count = np.ceil(length / max(length.mean(), 1e-300)).astype(np.int64).clip(1)
    owner = np.repeat(np.arange(len(a)), count)
    within = np.arange(len(owner)) - np.repeat(np.cumsum(count) - count, count)
    mid = a[owner] + ((within + 0.5) / count[owner])[:, None] * ab[owner]
    half = 0.5 * np.max(length / count)
    tree = cKDTree(mid)
    best = np.empty(len(y), dtype=np.int64)
    todo, k = np.arange(len(y)), LOCATE_CANDIDATES
    while len(todo):
        k = min(k, len(owner))
        reach, cand = tree.query(y[todo], k=k)
        reach, cand = reach.reshape(len(todo), k), cand.reshape(len(todo), k)
        best[todo], dist = _nearest_chord(a, ab, y[todo], owner[cand])
        if k == len(owner):
            break
        todo, k = todo[reach[:, -1] < dist + half], 8 * k
    t = np.einsum("qd,qd->q", y - a[best], ab[best]) / np.sum(ab[best] ** 2, axis=1)
    return best, t


def _nearest_chord(a: np.ndarray, ab: np.ndarray, y: np.ndarray,
                   cand: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Per point y_q, the chord (a + t·ab, t ∈ [0, 1]) among its candidates ``cand[q]``
    nearest to it, and the distance."""
    t = np.einsum("qcd,qcd->qc", y[:, None, :] - a[cand], ab[cand]) / np.sum(ab[cand] ** 2,
                                                                           axis=2)
    near = a[cand] + np.clip(t, 0, 1)[..., None] * ab[cand]
    d2 = np.sum((near - y[:, None, :]) ** 2, axis=2)
    j = np.argmin(d2, axis=1)
    rows = np.arange(len(y))
    return cand[rows, j], np.sqrt(d2[rows, j])


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
    best, s = nearest_chords(a, body.mesh.doflocs.T[nodes[:, 1]] - a, np.asarray(y, float))
    f = facets[best]
    for _ in range(4):  # Newton on the quadratic facet curve
        xs, dx, _ = facet_curve(body, f, s)
        d2 = np.einsum("k,nkd->nd", np.array([4.0, 4.0, -8.0]),
                       body.mesh.doflocs.T[facet_nodes(body.mesh, f)])
        r = xs - y
        s = s - np.sum(r * dx, axis=1) / (np.sum(dx * dx, axis=1) + np.sum(r * d2, axis=1))
    return f, s


def build_contact(bodies: Sequence[Body], pairs: Sequence[ContactPair],
                  settings: ContactSettings = ContactSettings()) -> ContactModel:
    """Pair the slave quadrature points and build the weighted-gap rows; the flexibility of
    the slave nodes is formed from them as the solve needs it (:class:`PointFlexibility`).

    Bodies sit at their ``placement``; slave points and rows are kept in body frames. The
    flexibility is taken from each body's nodal flexibility on its contact boundaries (one per
    body and boundary set, its rows kept for every later pairing)."""
    bodies = tuple(bodies)
    links = [i for i, b in enumerate(bodies) if b.link is not None]
    if len(links) > 1:
        raise ContactError("at most one body may carry a rigid link (the load-controlled one)")
    gauss, gw = np.polynomial.legendre.leggauss(settings.gauss_points)
    gauss = np.concatenate([0.25 * (gauss + 1.0), 0.5 + 0.25 * (gauss + 1.0)])  # two halves
    gw = np.concatenate([0.25 * gw, 0.25 * gw])
    ng = len(gauss)

    parts = {k: [] for k in ("pair", "x", "node", "w", "arc", "rows", "avg", "qpair", "qx",
                             "kappa")}
    dropped = 0
    for k, pair in enumerate(pairs):
        sb, mb = bodies[pair.slave], bodies[pair.master]
        facets, flipped = _ordered(sb, pair.slave_boundary)
        nf = len(facets)
        s = np.tile(gauss, nf)
        x, dx, nodes = facet_curve(sb, np.repeat(facets, ng), s)
        w = np.tile(gw, nf) * np.linalg.norm(dx, axis=1) * sb.material.thickness
        fnodes = facet_nodes(sb.mesh, facets)
        seg = np.linalg.norm(np.diff(sb.mesh.doflocs.T[fnodes[:, :2]], axis=1)[:, 0], axis=1)
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
        # linear hats of the corner nodes: M_iq = φ_i(x_q) w_q (midside nodes carry none)
        hats = np.column_stack([1 - s, s])[ok]
        q = np.flatnonzero(ok)
        M = sp.coo_matrix(((hats * w[ok, None]).ravel(),
                           (nodes[ok, :2].ravel(), np.repeat(np.arange(len(q)), 2))),
                          shape=(sb.mesh.doflocs.shape[1], len(q))).tocsr()
        D = np.asarray(M.sum(axis=1)).ravel()
        used = np.flatnonzero(D > 0)
        parts["avg"].append(sp.diags(1.0 / D[used]) @ M[used])
        start = np.concatenate([[0.0], np.cumsum(seg)[:-1]])
        corner_arc = np.column_stack([np.where(flipped, start + seg, start),
                                      np.where(flipped, start, start + seg)])
        arc = np.zeros(sb.mesh.doflocs.shape[1])
        arc[fnodes[:, :2].ravel()] = corner_arc.ravel()
        parts["pair"].append(np.full(len(used), k))
        parts["x"].append(sb.mesh.doflocs.T[used])
        parts["node"].append(used)
        parts["w"].append(D[used])
        modulus = contact_modulus(sb.material.plane_modulus, mb.material.plane_modulus)
        h_node = D[used] / sb.material.thickness  # ∫φ_i ds: the mean of the two facets
        parts["kappa"].append(settings.penalty_factor * modulus / h_node)
        parts["arc"].append(arc[used])
        parts["qpair"].append(np.full(len(q), k))
        parts["qx"].append(x[ok])

    n_nodes = sum(len(p) for p in parts["pair"])
    if n_nodes == 0:
        raise ContactError("no slave point has a master facet under it: check the contact pairs")
    average = sp.block_diag(parts["avg"], format="csr")
    q_offsets = np.cumsum([0] + [len(p) for p in parts["qpair"]])
    n_quad = int(q_offsets[-1])
    C, flex = [], []
    for b, body in enumerate(bodies):
        names = sorted({p.slave_boundary for p in pairs if p.slave == b}
                       | {p.master_boundary for p in pairs if p.master == b})
        if not names:
            C.append(sp.csr_matrix((n_nodes, body.ndofs)))
            continue
        window = np.unique(np.concatenate(
            [facet_nodes(body.mesh, body.mesh.boundaries[n]).ravel() for n in names]))
        local = np.full(body.mesh.doflocs.shape[1], -1)
        local[window] = np.arange(len(window))
        rows_, cols_, vals_ = [], [], []
        for k in range(len(pairs)):
            rows = np.arange(q_offsets[k], q_offsets[k + 1])
            for owner, nodes, shape, normal in parts["rows"][k]:
                if owner != b:
                    continue
                cols = 2 * local[nodes]  # (n, 3)
                for j in range(3):
                    for d in range(2):
                        rows_.append(rows)
                        cols_.append(cols[:, j] + d)
                        vals_.append(shape[:, j] * normal[:, d])
        Cq = sp.coo_matrix((np.concatenate(vals_), (np.concatenate(rows_),
                                                    np.concatenate(cols_))),
                           shape=(n_quad, 2 * len(window))).tocsr()  # duplicates summed
        Cs = (average @ Cq).tocsr()
        flex.append((Cs, body.flexibility(window)))
        dofs = body.node_dofs(window).ravel()  # window columns → the body's dofs
        C.append(sp.csr_matrix((Cs.data, dofs[Cs.indices], Cs.indptr),
                               shape=(n_nodes, body.ndofs)))
    return ContactModel(bodies, tuple(pairs), settings, np.concatenate(parts["pair"]),
                        np.vstack(parts["x"]), np.concatenate(parts["node"]),
                        np.concatenate(parts["w"]),
                        np.concatenate(parts["arc"]), np.vstack(parts["qx"]),
                        np.concatenate(parts["qpair"]), average, tuple(C),
                        PointFlexibility(flex, n_nodes),
                        np.concatenate(parts["kappa"]), links[0] if links else None, dropped)


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

"""Building the condensed contact problem: slave points paired with the master, weighted gaps,
and their rows over each body's displacements.

Each pair's slave boundary is chained end to end; its quadrature points (``gauss_points`` per
half facet) are paired once with their closest point on the master's exact curve and the master
facet under it (:mod:`fegear.contact.search`). The weighted gap of slave corner node i averages
the pointwise gaps with the linear hat φ_i; its elastic part is a row over the slave facet's and
the master facet's P2 nodes along the normal at the point.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from ...contact import facet_curve, locate_on_facets, ordered_boundary, p2_edge_shape
from ...fe import Body, contact_modulus, facet_nodes
from .flexibility import PointFlexibility
from .model import ContactError, ContactModel, ContactPair, ContactSettings


@dataclass(frozen=True)
class GapRows:
    """The elastic gap of one body at a pair's quadrature points: per point the body's three
    facet nodes, the P2 shape values (with the sign of the body's side) and the normal in the
    body's frame."""

    body: int
    nodes: np.ndarray    # (nq, 3)
    shape: np.ndarray    # (nq, 3)
    normal: np.ndarray   # (nq, 2)


@dataclass(frozen=True)
class PairPoints:
    """One pair's contact nodes (the slave corner nodes carrying a weighted gap) and its
    quadrature points: node indices, positions (slave body frame, mm), weights D_i (mm²), arc
    length along the boundary (mm), penalty κ_i (MPa/mm), the averaging g̃ = average @ g_q,
    the quadrature points (slave body frame) and their elastic gap rows on both bodies;
    ``dropped``: points with no master facet under them."""

    node: np.ndarray
    x: np.ndarray
    weight: np.ndarray
    arc: np.ndarray
    kappa: np.ndarray
    average: sp.csr_matrix
    quad_x: np.ndarray
    rows: tuple[GapRows, GapRows]
    dropped: int


def gauss_halves(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Gauss points (facet coordinate in [0, 1]) and weights of ``n`` points on each half of a
    facet: the weighted gaps' hats have a kink at the midside node."""
    s, w = np.polynomial.legendre.leggauss(n)
    return (np.concatenate([0.25 * (s + 1.0), 0.5 + 0.25 * (s + 1.0)]),
            np.concatenate([0.25 * w, 0.25 * w]))


def pair_points(bodies: Sequence[Body], pair: ContactPair, settings: ContactSettings
                ) -> PairPoints:
    """Pair the slave quadrature points of ``pair`` with the master and weight them onto the
    slave corner nodes (see the module docstring)."""
    sb, mb = bodies[pair.slave], bodies[pair.master]
    gauss, gw = gauss_halves(settings.gauss_points)
    facets, flipped = ordered_boundary(sb, pair.slave_boundary)
    nf, ng = len(facets), len(gauss)
    s = np.tile(gauss, nf)
    x, dx, nodes = facet_curve(sb, np.repeat(facets, ng), s)
    w = np.tile(gw, nf) * np.linalg.norm(dx, axis=1) * sb.material.thickness
    cp = pair.master_curve.closest(sb.placement.to_fixed(x))
    mf, ms = locate_on_facets(mb, mb.mesh.boundaries[pair.master_boundary],
                              mb.placement.to_body(cp.foot))
    ok = (ms > -1e-9) & (ms < 1 + 1e-9)
    _, _, mnodes = facet_curve(mb, mf[ok], ms[ok])
    n_fixed = cp.normal[ok]
    rows = (GapRows(pair.slave, nodes[ok], p2_edge_shape(s[ok]),
                    sb.placement.vec_to_body(n_fixed)),
            GapRows(pair.master, mnodes, -p2_edge_shape(np.clip(ms[ok], 0, 1)),
                    mb.placement.vec_to_body(n_fixed)))
    # linear hats of the corner nodes: M_iq = φ_i(x_q) w_q (midside nodes carry none)
    hats = np.column_stack([1 - s, s])[ok]
    q = np.flatnonzero(ok)
    M = sp.coo_matrix(((hats * w[ok, None]).ravel(),
                       (nodes[ok, :2].ravel(), np.repeat(np.arange(len(q)), 2))),
                      shape=(sb.mesh.doflocs.shape[1], len(q))).tocsr()
    D = np.asarray(M.sum(axis=1)).ravel()
    used = np.flatnonzero(D > 0)
    modulus = contact_modulus(sb.material.plane_modulus, mb.material.plane_modulus)
    h_node = D[used] / sb.material.thickness  # ∫φ_i ds: the mean of the two facets
    return PairPoints(
        node=used, x=sb.mesh.doflocs.T[used], weight=D[used],
        arc=_corner_arc(sb, facets, flipped)[used],
        kappa=settings.penalty_factor * modulus / h_node,
        average=sp.diags(1.0 / D[used]) @ M[used], quad_x=x[ok], rows=rows,
        dropped=int(np.count_nonzero(~ok)))


def _corner_arc(body: Body, facets: np.ndarray, flipped: np.ndarray) -> np.ndarray:
    """Arc length (mm) of every corner node of a chained boundary, from its first end, along
    the chords (0 for the body's other nodes)."""
    fnodes = facet_nodes(body.mesh, facets)
    seg = np.linalg.norm(np.diff(body.mesh.doflocs.T[fnodes[:, :2]], axis=1)[:, 0], axis=1)
    start = np.concatenate([[0.0], np.cumsum(seg)[:-1]])
    corner_arc = np.column_stack([np.where(flipped, start + seg, start),
                                  np.where(flipped, start, start + seg)])
    arc = np.zeros(body.mesh.doflocs.shape[1])
    arc[fnodes[:, :2].ravel()] = corner_arc.ravel()
    return arc


def body_rows(body: Body, b: int, pairs: Sequence[ContactPair],
              points: Sequence[PairPoints], average: sp.csr_matrix):
    """Body ``b``'s weighted-gap rows: over its contact windows' dofs (for its flexibility,
    None if it has no window) and over all its dofs (``C_b``)."""
    n_nodes = average.shape[0]
    names = sorted({p.slave_boundary for p in pairs if p.slave == b}
                   | {p.master_boundary for p in pairs if p.master == b})
    if not names:
        return None, sp.csr_matrix((n_nodes, body.ndofs))
    window = np.unique(np.concatenate(
        [facet_nodes(body.mesh, body.mesh.boundaries[n]).ravel() for n in names]))
    local = np.full(body.mesh.doflocs.shape[1], -1)
    local[window] = np.arange(len(window))
    rows_, cols_, vals_ = [], [], []
    start = 0
    for pp in points:
        rows = np.arange(start, start + len(pp.quad_x))
        start += len(pp.quad_x)
        for r in pp.rows:
            if r.body != b:
                continue
            cols = 2 * local[r.nodes]  # (n, 3)
            for j in range(3):
                for d in range(2):
                    rows_.append(rows)
                    cols_.append(cols[:, j] + d)
                    vals_.append(r.shape[:, j] * r.normal[:, d])
    Cq = sp.coo_matrix((np.concatenate(vals_), (np.concatenate(rows_), np.concatenate(cols_))),
                       shape=(start, 2 * len(window))).tocsr()  # duplicates summed
    Cs = (average @ Cq).tocsr()
    dofs = body.node_dofs(window).ravel()  # window columns → the body's dofs
    C = sp.csr_matrix((Cs.data, dofs[Cs.indices], Cs.indptr), shape=(n_nodes, body.ndofs))
    return (Cs, body.flexibility(window)), C


def build_contact(bodies: Sequence[Body], pairs: Sequence[ContactPair],
                  settings: ContactSettings | None = None) -> ContactModel:
    """Pair the slave quadrature points and build the weighted-gap rows; the flexibility of
    the slave nodes is formed from them as the solve needs it (:class:`PointFlexibility`).

    Bodies sit at their ``placement``; slave points and rows are kept in body frames. The
    flexibility is taken from each body's nodal flexibility on its contact boundaries (one per
    body and boundary set, its rows kept for every later pairing)."""
    settings = ContactSettings() if settings is None else settings
    bodies = tuple(bodies)
    links = [i for i, b in enumerate(bodies) if b.link is not None]
    if len(links) > 1:
        raise ContactError("at most one body may carry a rigid link (the load-controlled one)")
    points = [pair_points(bodies, pair, settings) for pair in pairs]
    n_nodes = sum(len(pp.node) for pp in points)
    if n_nodes == 0:
        raise ContactError("no slave point has a master facet under it: check the contact pairs")
    average = sp.block_diag([pp.average for pp in points], format="csr")
    rows = [body_rows(body, b, pairs, points, average) for b, body in enumerate(bodies)]
    return ContactModel(
        bodies=bodies, pairs=tuple(pairs), settings=settings,
        pair_index=np.concatenate([np.full(len(pp.node), k) for k, pp in enumerate(points)]),
        x=np.vstack([pp.x for pp in points]), node=np.concatenate([pp.node for pp in points]),
        weight=np.concatenate([pp.weight for pp in points]),
        arc=np.concatenate([pp.arc for pp in points]),
        quad_x=np.vstack([pp.quad_x for pp in points]),
        quad_pair=np.concatenate([np.full(len(pp.quad_x), k) for k, pp in enumerate(points)]),
        average=average, C=tuple(C for _, C in rows),
        G=PointFlexibility([f for f, _ in rows if f is not None], n_nodes),
        kappa=np.concatenate([pp.kappa for pp in points]),
        link_body=links[0] if links else None, dropped=sum(pp.dropped for pp in points))

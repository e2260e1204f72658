"""Contact search: which master facet lies under a point, where on it, and the slave
boundary chained end to end.

scikit-fem's ``MeshTri2`` has no element finder, so the closest point on a chain of quadratic
facets is found here: the nearest chord first (a k-d tree over chord pieces), then Newton on
the quadratic facet curve.
"""

from __future__ import annotations

import numpy as np
from scipy.spatial import cKDTree

from ..errors import ContactError
from ..fe import Body, facet_nodes

LOCATE_CANDIDATES = 16  # chord pieces tried per point first (then 8×, 64×, … up to all)


class Chords:
    """Chords a + t·ab (t ∈ [0, 1]) and a k-d tree over their pieces, for :meth:`nearest`:
    chords longer than the mean are cut into pieces no longer than it, and the nearest chord
    is searched among the owners of the ``LOCATE_CANDIDATES`` pieces with the nearest
    midpoints. The result is sure when the farthest of those midpoints is at least the best
    distance plus half the longest piece away (the foot on the nearest chord lies on some
    piece, whose midpoint is then no farther); the other points are searched again among
    eight times as many pieces, up to all of them. A caller that searches the same chords
    again and again (a template's profile, at every position) keeps one.

    Chords that chain around the origin by polar angle (a gear template's profile about the
    gear's centre) are first searched by angle: the chord whose angles hold the point's and
    its two neighbours. That is sure when the best of them is nearer than any point outside
    their angles can be, |y| sin Δ for the angle Δ from the point to their ends; the other
    points go to the tree (the same chord as the tree finds, in a sixth of the time for points
    on the profile)."""

    def __init__(self, a: np.ndarray, ab: np.ndarray) -> None:
        self.a, self.ab = a, ab
        length = np.sqrt(np.sum(ab * ab, axis=1))
        count = np.ceil(length / max(length.mean(), 1e-300)).astype(np.int64).clip(1)
        self.owner = np.repeat(np.arange(len(a)), count)
        within = np.arange(len(self.owner)) - np.repeat(np.cumsum(count) - count, count)
        mid = a[self.owner] + ((within + 0.5) / count[self.owner])[:, None] * ab[self.owner]
        self.half = 0.5 * np.max(length / count)
        self.tree = cKDTree(mid)
        self.polar = _polar_chain(a, ab)

    def nearest(self, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Per point y (n, 2): the nearest chord and the unclipped t of its foot."""
        a, ab, owner = self.a, self.ab, self.owner
        best = np.empty(len(y), dtype=np.int64)
        todo, k = np.arange(len(y)), LOCATE_CANDIDATES
        if self.polar is not None and len(y):
            best[:], sure = self._by_angle(y)
            todo = np.flatnonzero(~sure)
        while len(todo):
            k = min(k, len(owner))
            reach, cand = self.tree.query(y[todo], k=k)
            reach, cand = reach.reshape(len(todo), k), cand.reshape(len(todo), k)
            best[todo], dist = _nearest_chord(a, ab, y[todo], owner[cand])
            if k == len(owner):
                break
            todo, k = todo[reach[:, -1] < dist + self.half], 8 * k
        t = np.einsum("qd,qd->q", y - a[best], ab[best]) / np.sum(ab[best] ** 2, axis=1)
        return best, t

    def _by_angle(self, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The nearest of the three chords about each point's polar angle, and whether it is
        sure (class docstring)."""
        order, start, end, mid = self.polar
        theta = mid + np.angle(np.exp(1j * (np.arctan2(y[:, 1], y[:, 0]) - mid)))
        i = np.clip(np.searchsorted(start, theta, side="right") - 1, 0, len(order) - 1)
        lo, hi = np.maximum(i - 1, 0), np.minimum(i + 1, len(order) - 1)
        cand = order[np.column_stack([lo, i, hi])]
        d2 = _chord_distances(self.a, self.ab, y, cand)
        j = np.argmin(d2, axis=1)
        rows = np.arange(len(y))
        best, dist = cand[rows, j], np.sqrt(d2[rows, j])
        # a point on a node between two chords is as near to both: the tree's choice stands
        tied = ((d2 == d2[rows, j][:, None]) & (cand != best[:, None])).any(axis=1)
        # points outside the three chords' angles lie at least |y| sin Δ from y (none beyond
        # the chain's own ends: no chord is there)
        below = np.where(lo > 0, theta - start[lo], np.pi / 2)
        above = np.where(hi < len(order) - 1, end[hi] - theta, np.pi / 2)
        gap = np.clip(np.minimum(below, above), 0.0, np.pi / 2)
        sure = (dist < np.hypot(y[:, 0], y[:, 1]) * np.sin(gap)) & ~tied
        return best, sure


def _polar_chain(a: np.ndarray, ab: np.ndarray):
    """The chords' order by polar angle, their start and end angles (continuous about the
    chain's middle) and that middle, if they chain around the origin within less than a half
    turn: each spanning less than a quarter turn and starting where the one before ends, so
    that no two overlap in angle; else None."""
    if len(a) < 3:
        return None
    b = a + ab
    phi_a, phi_b = np.arctan2(a[:, 1], a[:, 0]), np.arctan2(b[:, 1], b[:, 0])
    mid = float(np.angle(np.exp(1j * phi_a).mean()))
    phi_a = mid + np.angle(np.exp(1j * (phi_a - mid)))
    phi_b = mid + np.angle(np.exp(1j * (phi_b - mid)))
    start, end = np.minimum(phi_a, phi_b), np.maximum(phi_a, phi_b)
    order = np.argsort(start)
    start, end = start[order], end[order]
    span = end - start
    if (span <= 0).any() or (span >= np.pi / 2).any() or end[-1] - start[0] >= np.pi:
        return None
    if np.abs(start[1:] - end[:-1]).max() > 1e-9 * max(span.max(), 1e-300):
        return None
    return order, start, end, mid


def _nearest_chord(a: np.ndarray, ab: np.ndarray, y: np.ndarray,
                   cand: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Per point y_q, the chord (a + t·ab, t ∈ [0, 1]) among its candidates ``cand[q]``
    nearest to it, and the distance."""
    d2 = _chord_distances(a, ab, y, cand)
    j = np.argmin(d2, axis=1)
    rows = np.arange(len(y))
    return cand[rows, j], np.sqrt(d2[rows, j])


def _chord_distances(a: np.ndarray, ab: np.ndarray, y: np.ndarray,
                     cand: np.ndarray) -> np.ndarray:
    """Squared distance of each point y_q to each of its candidate chords ``cand[q]``."""
    t = np.einsum("qcd,qcd->qc", y[:, None, :] - a[cand], ab[cand]) / np.sum(ab[cand] ** 2,
                                                                           axis=2)
    near = a[cand] + np.clip(t, 0, 1)[..., None] * ab[cand]
    return np.sum((near - y[:, None, :]) ** 2, axis=2)


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
    the point is not covered by these facets (:class:`FacetLocator`, for facets searched
    once)."""
    return FacetLocator(body.mesh, facets).locate(y)


class FacetLocator:
    """Quadratic ``facets`` of ``mesh`` and their chords' search tree, formed once: the
    nearest chord first, then Newton on the quadratic facet curve."""

    def __init__(self, mesh, facets: np.ndarray) -> None:
        self.mesh, self.facets = mesh, np.asarray(facets)
        nodes = facet_nodes(mesh, self.facets)
        a = mesh.doflocs.T[nodes[:, 0]]
        self.chords = Chords(a, mesh.doflocs.T[nodes[:, 1]] - a)

    def locate(self, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Facet and local coordinate under each point y (see :func:`locate_on_facets`)."""
        y = np.asarray(y, float)
        best, s = self.chords.nearest(y)
        f = self.facets[best]
        X = self.mesh.doflocs.T[facet_nodes(self.mesh, f)]     # (n, 3, 2)
        d2 = np.einsum("k,nkd->nd", np.array([4.0, 4.0, -8.0]), X)
        for _ in range(4):  # Newton on the quadratic facet curve
            xs = np.einsum("nk,nkd->nd", p2_edge_shape(s), X)
            dx = np.einsum("nk,nkd->nd", _p2_edge_dshape(s), X)
            r = xs - y
            s = s - np.sum(r * dx, axis=1) / (np.sum(dx * dx, axis=1) + np.sum(r * d2, axis=1))
        return f, s


def ordered_boundary(body: Body, name: str) -> tuple[np.ndarray, np.ndarray]:
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

"""Points in a quadratic triangle mesh: which element holds each, where in it, and the rows that
evaluate a P2 field, its component along a direction or its strain there.

scikit-fem's ``MeshTri2`` has no element finder, and the corner-triangle finder of ``MeshTri1``
misses points near a curved boundary (docs/model.md, "Library notes"). Here the candidate
elements come from a k-d tree over element centres and each point's reference coordinates from
Newton's method on the element's quadratic (isoparametric) map, so points between a curved
edge and its chord are found too.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp

from ..errors import FegearError

CANDIDATES = 8      # nearest element centres tried per point
NEWTON = 6          # iterations at most on the quadratic map (close to affine in each element)
TOLERANCE = 0.05    # how far outside its element a point may fall (reference units): a point
                    # on the exact boundary lies outside the quadratic edges by ~(hκ)² of an
                    # element, up to 0.016 where elements are an eighth of the curvature radius
                    # (gear 2's sharp tips, gear 1's rounds); at 1e-3, points a submodel's cut
                    # takes on the exact curve there fell outside


@dataclass(frozen=True)
class Cells:
    """Element of each point and its reference coordinates (ξ, η) there."""

    element: np.ndarray
    xi: np.ndarray
    eta: np.ndarray

    def take(self, index: np.ndarray) -> Cells:
        """The points ``index`` of these."""
        return Cells(self.element[index], self.xi[index], self.eta[index])


@dataclass(eq=False)
class Probe:
    """Locates points (n, 2) in ``mesh`` (a ``MeshTri2``) and evaluates P2 vector fields there
    (dofs 2k, 2k + 1 at node k)."""

    mesh: object
    _tree: object = field(init=False, repr=False)
    _nodes: np.ndarray = field(init=False, repr=False)

    def __post_init__(self) -> None:
        from scipy.spatial import cKDTree

        self._nodes = self.mesh.dofs.element_dofs.T          # (nelem, 6)
        centres = self.mesh.p[:, self.mesh.t].mean(axis=1).T
        self._tree = cKDTree(centres)

    @property
    def ndofs(self) -> int:
        return 2 * self.mesh.doflocs.shape[1]

    def locate(self, points: np.ndarray) -> Cells:
        """The element holding each point and the point's reference coordinates; raises
        :class:`~fegear.errors.FegearError` for a point outside the mesh."""
        points = np.atleast_2d(np.asarray(points, dtype=float))
        k = min(CANDIDATES, self._nodes.shape[0])
        _, cand = self._tree.query(points, k=k)
        cand = cand.reshape(len(points), k)
        X = self.mesh.doflocs.T[self._nodes[cand]]             # (n, k, 6, 2)
        rows = np.arange(len(points))
        # Newton on the candidate whose corner triangle holds the point best; on all
        # candidates only for the points it leaves outside (near curved edges)
        best = np.argmin(_outside(_affine(X, points[:, None, :])), axis=1)
        ref = _invert(X[rows, best], points)                   # (n, 2)
        out = _outside(ref)
        redo = np.flatnonzero(out > 0.0)
        if len(redo):
            every = _invert(X[redo], points[redo, None, :])     # (m, k, 2)
            pick = np.argmin(_outside(every), axis=1)
            better = _outside(every[np.arange(len(redo)), pick]) < out[redo]
            redo, pick = redo[better], pick[better]
            best[redo] = pick
            ref[redo] = every[better][np.arange(len(redo)), pick]
            out[redo] = _outside(ref[redo])
        if out.max() > TOLERANCE:
            i = int(np.argmax(out))
            raise FegearError(f"point {points[i].tolist()} lies outside the mesh")
        return Cells(cand[rows, best], ref[:, 0], ref[:, 1])

    def rows(self, points: np.ndarray, direction: np.ndarray | None = None,
             strain: bool = False) -> sp.csr_matrix:
        """Sparse rows (n × ndofs): at each point, the field's component along ``direction``
        (n, 2) or, with ``strain``, the strain along it, d·∇u·d."""
        return self.rows_at(self.locate(points), direction, strain)

    def rows_at(self, at: Cells, direction: np.ndarray | None = None,
                strain: bool = False) -> sp.csr_matrix:
        """:meth:`rows` at points located before (:meth:`locate`): a caller that reads a
        field at the same points more than once finds them once."""
        nodes = self._nodes[at.element]                          # (n, 6)
        n = len(nodes)
        d = np.asarray(direction, dtype=float)
        if not strain:
            N = p2_shape(at.xi, at.eta)                            # (n, 6)
            vx, vy = N * d[:, :1], N * d[:, 1:]
        else:
            X = self.mesh.doflocs.T[nodes]                       # (n, 6, 2)
            dN = p2_grad(at.xi, at.eta)                            # (n, 6, 2) reference
            J = np.einsum("nkd,nkr->ndr", X, dN)                 # dx_d/dξ_r
            G = np.einsum("nkr,nrd->nkd", dN, np.linalg.inv(J))  # ∂N/∂x
            dNd = np.einsum("nkd,nd->nk", G, d)
            vx, vy = dNd * d[:, :1], dNd * d[:, 1:]
        cols = np.stack([2 * nodes, 2 * nodes + 1], axis=-1).reshape(n, 12)
        vals = np.stack([vx, vy], axis=-1).reshape(n, 12)
        return sp.csr_matrix((vals.ravel(), (np.repeat(np.arange(n), 12), cols.ravel())),
                             shape=(n, self.ndofs))

    def displacement(self, points: np.ndarray, u: np.ndarray) -> np.ndarray:
        """The field ``u`` (ndofs,) at the points: (n, 2)."""
        points = np.atleast_2d(points)
        ones = np.ones(len(points))
        zeros = np.zeros(len(points))
        return np.column_stack([self.rows(points, np.column_stack([ones, zeros])) @ u,
                                self.rows(points, np.column_stack([zeros, ones])) @ u])


def p2_shape(xi: np.ndarray, eta: np.ndarray) -> np.ndarray:
    """P2 shape functions (…, 6) at reference coordinates ``xi``, ``eta``: corners 0, 1, 2 then
    the midside nodes of edges 01, 12, 02 (the order of ``mesh.dofs.element_dofs``)."""
    l0 = 1.0 - xi - eta
    return np.stack([l0 * (2 * l0 - 1), xi * (2 * xi - 1), eta * (2 * eta - 1),
                     4 * xi * l0, 4 * xi * eta, 4 * eta * l0], axis=-1)


def p2_grad(xi: np.ndarray, eta: np.ndarray) -> np.ndarray:
    """Reference gradients (…, 6, 2) of :func:`p2_shape`."""
    l0 = 1.0 - xi - eta
    z = np.zeros_like(xi)
    g = [(-(4 * l0 - 1), -(4 * l0 - 1)), (4 * xi - 1, z), (z, 4 * eta - 1),
         (4 * (l0 - xi), -4 * xi), (4 * eta, 4 * xi), (-4 * eta, 4 * (l0 - eta))]
    return np.stack([np.stack(c, axis=-1) for c in g], axis=-2)


def _outside(ref: np.ndarray) -> np.ndarray:
    """How far reference coordinates (…, 2) lie outside the reference triangle (0 inside)."""
    xi, eta = ref[..., 0], ref[..., 1]
    out = np.maximum.reduce([-xi, -eta, xi + eta - 1.0, np.zeros_like(xi)])
    return np.where(np.isnan(out), np.inf, out)


def _affine(X: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Reference coordinates (…, 2) of points y under the affine maps of the corners of
    elements with nodes X (…, 6, 2)."""
    a, b, c = X[..., 0, :], X[..., 1, :], X[..., 2, :]
    (p, q), (r, s), (v, w) = np.moveaxis(b - a, -1, 0), np.moveaxis(c - a, -1, 0), \
        np.moveaxis(y - a, -1, 0)
    det = p * s - r * q                 # the corners' 2 × 2 map [b − a, c − a], by Cramer
    det = np.where(det != 0.0, det, np.nan)   # no element is flat: NaN, never chosen
    return np.stack([(s * v - r * w) / det, (p * w - q * v) / det], axis=-1)


def _invert(X: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Reference coordinates (…, 2) of points y under the quadratic maps of elements with nodes
    X (…, 6, 2): the affine map of the corners first, then Newton on the quadratic one."""
    ref = _affine(X, y)
    # done once every step is below 1e-10 of an element: Newton's error after it is of its
    # square, below the rounding of the coordinates (1e-12 of an element at 40 mm from the
    # centre); two or three steps, not six
    for _ in range(NEWTON):
        N = p2_shape(ref[..., 0], ref[..., 1])
        dN = p2_grad(ref[..., 0], ref[..., 1])
        r = np.einsum("...k,...kd->...d", N, X) - y
        J = np.einsum("...kd,...kr->...dr", X, dN)
        det = J[..., 0, 0] * J[..., 1, 1] - J[..., 0, 1] * J[..., 1, 0]
        ok = np.abs(det) > 1e-300
        det = np.where(ok, det, 1.0)
        step = np.stack([(J[..., 1, 1] * r[..., 0] - J[..., 0, 1] * r[..., 1]) / det,
                         (-J[..., 1, 0] * r[..., 0] + J[..., 0, 0] * r[..., 1]) / det], axis=-1)
        step = np.where(ok[..., None], step, 0.0)
        ref = ref - step
        if np.abs(step).max(initial=0.0) <= 1e-10:
            break
    return ref

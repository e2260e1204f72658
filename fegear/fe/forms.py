"""The three forms fegear assembles, on quadratic (P2, curved) triangles, in whole-array numpy.

* the plane stiffness t ∫ σ(u):ε(v), σ = λ tr(ε) I + 2 μ ε (:func:`stiffness`);
* the stress projection's scalar P2 mass ∫ φ q and mixed matrices ∫ q σ_ij(u)
  (:func:`projection`).

scikit-fem's ``asm`` gives the same matrices (to 1e-12, tested on curved meshes) by calling the
form once per pair of basis functions (144 calls for the stiffness), each over every element:
on a contact submodel of 1 700 nodes that is 20 ms of Python for 2 ms of arithmetic, and a
solve assembles a few dozen. Here each element's matrix is a batched product over the
quadrature points, with scikit-fem's own rule (order 4, six points: exact for the mass and for
the stiffness on straight elements). The dof numbering is fegear's (:mod:`.dofs`): node k of
``mesh.doflocs`` carries the displacement dofs 2k, 2k+1 and the scalar dof k; an element's six
nodes are ``mesh.dofs.element_dofs``, corners first, then the edges 01, 12, 02.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from .dofs import node_dofs
from .probe import p2_grad, p2_shape

#: the quadrature order (scikit-fem's default for P2: twice the degree)
ORDER = 4


def _rule() -> tuple[np.ndarray, np.ndarray]:
    """scikit-fem's points (2, nq) and weights (nq,) of order :data:`ORDER` on the reference
    triangle."""
    from skfem.quadrature import get_quadrature
    from skfem.refdom import RefTri

    return get_quadrature(RefTri, ORDER)


def _geometry(mesh) -> tuple[np.ndarray, ...]:
    """Per element and quadrature point: the weight times the map's Jacobian determinant
    (nel, nq), the shape functions' x and y gradients (nel, nq, 6) each; the shape values
    (6, nq); the elements' nodes (nel, 6)."""
    (x_ref, y_ref), weights = _rule()
    values, grads = p2_shape(x_ref, y_ref).T, p2_grad(x_ref, y_ref)   # (6, nq), (nq, 6, 2)
    nodes = mesh.dofs.element_dofs.T                      # (nel, 6)
    x = mesh.doflocs.T[nodes]                             # (nel, 6, 2)
    jac = np.einsum("ekd,qkj->eqdj", x, grads)            # dx_d / dξ_j
    det = jac[..., 0, 0] * jac[..., 1, 1] - jac[..., 0, 1] * jac[..., 1, 0]
    # ∇φ = J⁻ᵀ ∇̂φ
    gx = (grads[None, :, :, 0] * jac[..., 1, 1, None]
          - grads[None, :, :, 1] * jac[..., 1, 0, None]) / det[..., None]
    gy = (grads[None, :, :, 1] * jac[..., 0, 0, None]
          - grads[None, :, :, 0] * jac[..., 0, 1, None]) / det[..., None]
    return np.abs(det) * weights, gx, gy, values, nodes


def _pair(wd: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Σ_q wd a_k b_l per element: (nel, k, l)."""
    return np.matmul((wd[..., None] * a).transpose(0, 2, 1), b)


def _sparse(blocks: np.ndarray, rows: np.ndarray, cols: np.ndarray, shape) -> sp.csr_matrix:
    """The element blocks (nel, r, c) summed into a sparse matrix at ``rows`` (nel, r) and
    ``cols`` (nel, c)."""
    nel, r, c = blocks.shape
    i = np.broadcast_to(rows[:, :, None], (nel, r, c)).ravel()
    j = np.broadcast_to(cols[:, None, :], (nel, r, c)).ravel()
    return sp.coo_matrix((blocks.ravel(), (i, j)), shape=shape).tocsr()


def _element_dofs(nodes: np.ndarray) -> np.ndarray:
    """Each element's 12 displacement dofs (nel, 12), node by node, x then y."""
    return node_dofs(nodes).reshape(len(nodes), 12)


def stiffness(mesh, lam: float, mu: float, thickness: float = 1.0) -> sp.csr_matrix:
    """t ∫ σ(u):ε(v) on the P2 ``mesh`` with Lamé's ``lam`` and ``mu`` (the plane
    assumption's), (2 n, 2 n) for the n nodes."""
    wd, gx, gy, _, nodes = _geometry(mesh)
    xx, yy, xy = _pair(wd, gx, gx), _pair(wd, gy, gy), _pair(wd, gx, gy)
    nel = len(nodes)
    k = np.empty((nel, 6, 2, 6, 2))
    k[:, :, 0, :, 0] = (lam + 2 * mu) * xx + mu * yy
    k[:, :, 1, :, 1] = (lam + 2 * mu) * yy + mu * xx
    k[:, :, 0, :, 1] = lam * xy + mu * xy.transpose(0, 2, 1)
    k[:, :, 1, :, 0] = k[:, :, 0, :, 1].transpose(0, 2, 1)
    dofs = _element_dofs(nodes)
    n = 2 * mesh.doflocs.shape[1]
    return _sparse(thickness * k.reshape(nel, 12, 12), dofs, dofs, (n, n))


def projection(mesh, lam: float, mu: float) -> tuple[sp.csr_matrix, tuple]:
    """The stress projection's matrices on ``mesh``: the scalar P2 mass ∫ φ q (n, n), and
    C_xx, C_yy, C_xy, ∫ q σ_ij(u) for the scalar test q and the displacement dofs, each
    (n, 2 n)."""
    wd, gx, gy, values, nodes = _geometry(mesh)
    v = np.broadcast_to(values.T, wd.shape + (6,))
    n = mesh.doflocs.shape[1]
    mass = _sparse(_pair(wd, v, v), nodes, nodes, (n, n))
    vx, vy = _pair(wd, v, gx), _pair(wd, v, gy)           # (nel, 6 test, 6 trial)
    nel = len(nodes)
    dofs = _element_dofs(nodes)
    parts = []
    for ax, ay in (((lam + 2 * mu) * vx, lam * vy),       # σxx of u = ψ ex, ψ ey
                   (lam * vx, (lam + 2 * mu) * vy),       # σyy
                   (mu * vy, mu * vx)):                   # σxy
        c = np.stack([ax, ay], axis=-1).reshape(nel, 6, 12)
        parts.append(_sparse(c, nodes, dofs, (n, 2 * n)))
    return mass, tuple(parts)

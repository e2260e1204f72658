"""Stress recovery: nodal stresses recovered from a P2 displacement field.

The stress at the quadrature points, σ = λ tr(ε) I + 2 μ ε with the plane assumption's λ, is
L2-projected onto the continuous P2 space of the same mesh (one mass matrix, factorised once per
body and cached on it). σzz = 0 in plane stress and ν(σxx + σyy) in plane strain; von Mises and
the principal stresses use that σzz. Units MPa.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.sparse.linalg import splu

from . import forms
from .assembly import Body
from .solvers import Factor


@dataclass(frozen=True)
class StressField:
    """Nodal stresses (MPa) at ``mesh.doflocs`` of one body: components, σzz, von Mises, in-plane
    principal σ1 ≥ σ2, and the first (largest) principal of the 3D state ``max_principal``."""

    sxx: np.ndarray
    syy: np.ndarray
    sxy: np.ndarray
    szz: np.ndarray
    plane: str

    @property
    def von_mises(self) -> np.ndarray:
        sx, sy, sz, t = self.sxx, self.syy, self.szz, self.sxy
        return np.sqrt(0.5 * ((sx - sy) ** 2 + (sy - sz) ** 2 + (sz - sx) ** 2) + 3.0 * t * t)

    @property
    def s1(self) -> np.ndarray:
        return 0.5 * (self.sxx + self.syy) + self._radius

    @property
    def s2(self) -> np.ndarray:
        return 0.5 * (self.sxx + self.syy) - self._radius

    @property
    def max_principal(self) -> np.ndarray:
        return np.maximum(self.s1, self.szz)

    @property
    def _radius(self) -> np.ndarray:
        return np.hypot(0.5 * (self.sxx - self.syy), self.sxy)

    def turned(self, angle: float) -> dict[str, np.ndarray]:
        """The in-plane components once the body is turned by ``angle`` (rad), R σ Rᵀ:
        ``sxx``, ``syy``, ``sxy`` (a body's stresses in the fixed frame)."""
        c, s = np.cos(angle), np.sin(angle)
        return {"sxx": c * c * self.sxx + s * s * self.syy - 2 * c * s * self.sxy,
                "syy": s * s * self.sxx + c * c * self.syy + 2 * c * s * self.sxy,
                "sxy": c * s * (self.sxx - self.syy) + (c * c - s * s) * self.sxy}

    def normal_stress(self, nodes: np.ndarray, normal: np.ndarray) -> np.ndarray:
        """n·σ·n at nodes for unit normals (n, 2)."""
        nx, ny = normal[:, 0], normal[:, 1]
        return (self.sxx[nodes] * nx * nx + 2 * self.sxy[nodes] * nx * ny
                + self.syy[nodes] * ny * ny)


def quadrature_stress(body: Body, u: np.ndarray) -> np.ndarray:
    """σ at the quadrature points: (3, nelem, nqp) for xx, yy, xy (MPa)."""
    lam, mu = body.material.lame
    grad = body.basis.interpolate(u).grad  # (2, 2, nelem, nqp): du_i/dx_j
    exx, eyy = grad[0, 0], grad[1, 1]
    exy = 0.5 * (grad[0, 1] + grad[1, 0])
    tr = exx + eyy
    return np.stack([lam * tr + 2 * mu * exx, lam * tr + 2 * mu * eyy, 2 * mu * exy])


def recover(body: Body, u: np.ndarray) -> StressField:
    """Nodal stresses of displacement ``u`` (ndofs,) by L2 projection onto continuous P2.

    The projection is linear in u: M s = C u per component, with M the scalar P2 mass matrix
    and C the mixed matrix ∫ φ σ(ψ). Both are assembled and M factorised once per mesh (kept in
    ``body.cache``, shared by placed copies; the matrices also as ``"projector matrices"``,
    which pickle: a model cache puts them back and only M is factorised again); each call is
    then a sparse product and a solve (:func:`recover_many` for several fields)."""
    return recover_many(body, np.asarray(u)[:, None])[0]


def recover_many(body: Body, U: np.ndarray, reused: bool = False) -> list[StressField]:
    """:func:`recover` of each column of ``U`` (ndofs, k), in one solve of 3k right-hand sides
    (a ring position's sectors: a third of the time of one solve a field). ``reused``: the
    body's projection will be solved again and again (a ring template's, at every position of
    a cycle), so its mass matrix is factorised by CHOLMOD, which solves six sectors in 2.2 ms
    against SuperLU's 4.7 ms; else by SuperLU, which factorises it in half CHOLMOD's time
    (13 against 26 ms on gear 1's template, 3 against 5 ms on a submodel)."""
    factor, parts = projector(body, reused)
    k = U.shape[1]
    nodal = factor.solve(np.hstack([C @ U for C in parts]))
    return [stress_field(*(np.ascontiguousarray(nodal[:, c * k + j]) for c in range(3)),
                         body.material) for j in range(k)]


def stress_field(sxx: np.ndarray, syy: np.ndarray, sxy: np.ndarray, material) -> StressField:
    """The :class:`StressField` of in-plane components (MPa) in ``material`` (its plane
    assumption gives σzz)."""
    szz = np.zeros_like(sxx) if material.plane == "stress" else material.nu * (sxx + syy)
    return StressField(sxx, syy, sxy, szz, material.plane)


def projector(body: Body, reused: bool = True):
    """The projection's factorised mass matrix and mixed matrices of ``body``, factorised here
    the first time (kept in ``body.cache``; ``reused``: by CHOLMOD, :func:`recover_many`): a
    model factorises it with the rest of what its positions share."""
    if "projector" not in body.cache:
        mass, parts = projection_matrices(body)
        body.cache["projector"] = (Factor(mass) if reused else splu(mass), parts)
    return body.cache["projector"]


def pickled_cache(cache: dict) -> dict:
    """The entries of a body's ``cache`` that pickle: all but the projector's factorisation
    (its matrices stay, :func:`recover` factorises them again)."""
    return {k: v for k, v in cache.items() if k != "projector"}


def projection_matrices(body: Body):
    """The projection's mass matrix (CSC) and its three mixed matrices C_xx, C_yy, C_xy (nodes
    × dofs), assembled once per mesh and kept in ``body.cache`` (:func:`recover`)."""
    if "projector matrices" not in body.cache:
        body.cache["projector matrices"] = _projector(body)
    return body.cache["projector matrices"]


def _projector(body: Body):
    """The mass matrix (CSC) and the three mixed matrices C_xx, C_yy, C_xy (nodes × dofs)."""
    mass, parts = forms.projection(body.mesh, *body.material.lame)
    return mass.tocsc(), parts

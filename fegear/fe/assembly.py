"""Assembly: P2 plane elasticity of one body, its supports, rigid link and one factorisation.

A :class:`Body` is a meshed plane body with a material, named boundaries held fixed (u = 0) and at
most one :class:`RigidLink`: a named boundary tied to one rigid-motion unknown (a rotation θ about
a centre, u = θ ẑ × (x − c), or a translation δ along a direction). The stiffness of the
unsupported block is factorised once; every later solve (contact condensation, load steps, mesh
positions) reuses that factor.

Displacements are split as u = θ ψ + v: ψ is the response to a unit link motion with no other
load (a rigid field when the link is the body's only support: a mechanism), v vanishes on the
link and fixed boundaries and solves K v = f. The two parts decouple exactly, so the link
equation is k θ = F + ψ·f with k = ψᵀKψ (0 for a mechanism) and F the applied generalised force
(torque in N·mm or force in N).

Units: mm, N, MPa. Thickness enters the stiffness and every force per thickness.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import splu
from skfem import Basis, ElementTriP2, ElementVector

from ..errors import FegearError
from ..planar import rotate
from .dofs import facet_nodes, node_dofs
from .flexibility import WindowFlexibility
from .forms import stiffness
from .material import ElasticMaterial
from .mesh import BodyMesh


@dataclass(frozen=True)
class RigidLink:
    """A boundary tied to one rigid-motion unknown.

    ``kind == "rotation"``: u = θ ẑ × (x − center), θ in rad, generalised force a torque (N·mm).
    ``kind == "translation"``: u = δ·direction, δ in mm, generalised force in N.
    """

    boundary: str
    kind: str
    center: tuple[float, float] = (0.0, 0.0)
    direction: tuple[float, float] = (0.0, 1.0)

    def __post_init__(self) -> None:
        if self.kind not in ("rotation", "translation"):
            raise ValueError(f"RigidLink.kind must be 'rotation' or 'translation': {self.kind!r}")
        d = np.asarray(self.direction, dtype=float)
        object.__setattr__(self, "direction", tuple(d / np.linalg.norm(d)))

    def velocity(self, x: np.ndarray) -> np.ndarray:
        """Displacement per unit link motion at points (n, 2): ẑ × (x − c), or the direction."""
        x = np.asarray(x, dtype=float)
        if self.kind == "rotation":
            r = x - np.asarray(self.center)
            return np.column_stack([-r[:, 1], r[:, 0]])
        return np.broadcast_to(np.asarray(self.direction), x.shape).copy()

    def move(self, x: np.ndarray, value: float) -> np.ndarray:
        """Exact rigid motion of points (n, 2) by ``value`` (finite rotation or translation)."""
        x = np.asarray(x, dtype=float)
        if self.kind == "rotation":
            c = np.asarray(self.center)
            return c + rotate(x - c, value)
        return x + value * np.asarray(self.direction)


@dataclass(frozen=True)
class BodyPlacement:
    """Where a body sits in the fixed frame: x_fixed = R(angle) x_body + offset (rad, mm).

    Meshes, stiffness and factors live in the body frame, so a body can be placed at any
    rolling position without re-assembly; contact rows turn their normals into the body frame.
    """

    angle: float = 0.0
    offset: tuple[float, float] = (0.0, 0.0)

    def vec_to_fixed(self, v: np.ndarray) -> np.ndarray:
        return rotate(np.asarray(v, dtype=float), self.angle)

    def vec_to_body(self, v: np.ndarray) -> np.ndarray:
        return rotate(np.asarray(v, dtype=float), -self.angle)

    def to_fixed(self, x: np.ndarray) -> np.ndarray:
        return self.vec_to_fixed(x) + np.asarray(self.offset)

    def to_body(self, x: np.ndarray) -> np.ndarray:
        return self.vec_to_body(np.asarray(x, dtype=float) - np.asarray(self.offset))


class SupportError(FegearError):
    """A body is not held: its stiffness is singular with the given supports."""


@dataclass(frozen=True, eq=False)
class Body:
    """An assembled, supported and factorised body (see module docstring).

    ``K`` is the full stiffness (N/mm, thickness included); ``free`` the dofs not on fixed or
    link boundaries; ``psi`` the unit-link response; ``link_stiffness`` k = ψᵀKψ.
    """

    name: str
    mesh_data: BodyMesh
    material: ElasticMaterial
    basis: Basis = field(repr=False)
    K: sp.csr_matrix = field(repr=False)
    free: np.ndarray = field(repr=False)
    fixed_boundaries: tuple[str, ...]
    link: RigidLink | None
    psi: np.ndarray = field(repr=False)
    link_stiffness: float
    factor: object = field(repr=False)
    placement: BodyPlacement = BodyPlacement()
    cache: dict = field(default_factory=dict, repr=False)  # shared by placed copies

    @property
    def mesh(self):
        return self.mesh_data.mesh

    @property
    def ndofs(self) -> int:
        return self.K.shape[0]

    @property
    def is_mechanism(self) -> bool:
        """True when the link is the only support: ψ is then a rigid motion and k = 0."""
        return self.link is not None and not self.fixed_boundaries

    def node_dofs(self, nodes: np.ndarray) -> np.ndarray:
        """(n, 2) global dofs (x, y) of mesh nodes (indices into ``mesh.doflocs``)."""
        return node_dofs(nodes)

    def facet_nodes(self, facets: np.ndarray) -> np.ndarray:
        """(n, 3) nodes of facets: first corner, second corner, midside."""
        return facet_nodes(self.mesh, facets)

    def solve(self, f: np.ndarray) -> np.ndarray:
        """v with v = 0 on fixed and link dofs and K v = f on the free dofs; f is (ndofs, k)."""
        f = np.asarray(f, dtype=float)
        v = np.zeros(f.shape)
        v[self.free] = self.factor.solve(np.ascontiguousarray(f[self.free]))
        return v

    def flexibility(self, nodes: np.ndarray) -> WindowFlexibility:
        """The nodal flexibility of ``nodes`` (formed lazily, see :class:`WindowFlexibility`).
        Cached per node set: it depends only on the body frame, not on the placement."""
        nodes = np.asarray(nodes, dtype=np.int64)
        key = ("flexibility", nodes.tobytes())
        if key not in self.cache:
            self.cache[key] = WindowFlexibility(self, nodes)
        return self.cache[key]

    def displacement(self, v: np.ndarray, link_value: float) -> np.ndarray:
        """Total displacement u = θψ + v (linear in the link motion), (ndofs,)."""
        return v + link_value * self.psi

    def residual(self, u: np.ndarray, f: np.ndarray) -> float:
        """Relative equilibrium residual ‖(K u − f)_free‖ / ‖f_free‖ (0 if f = 0 and u = 0)."""
        r = (self.K @ u - f)[self.free]
        scale = max(np.linalg.norm(f[self.free]), 1e-300)
        return float(np.linalg.norm(r) / scale)


def assemble_body(body_mesh: BodyMesh, material: ElasticMaterial, fixed: tuple[str, ...] = (),
                  link: RigidLink | None = None) -> Body:
    """Assemble K = t ∫ σ(u):ε(v), apply supports, factorise the free block once."""
    mesh = body_mesh.mesh
    basis = Basis(mesh, ElementVector(ElementTriP2()))
    nnodes = mesh.doflocs.shape[1]
    if basis.N != 2 * nnodes or not np.array_equal(basis.nodal_dofs[:, :2],
                                                   np.array([[0, 2], [1, 3]])):
        raise FegearError("unexpected scikit-fem dof numbering (expected node k ↔ dofs 2k, 2k+1)")
    K = stiffness(mesh, *material.lame, material.thickness)

    def boundary_dofs(name: str) -> np.ndarray:
        if name not in mesh.boundaries:
            raise FegearError(f"body {body_mesh.name!r} has no boundary {name!r}")
        return node_dofs(np.unique(facet_nodes(mesh, mesh.boundaries[name]))).ravel()

    if not fixed and link is None:
        raise SupportError(f"body {body_mesh.name!r} has no support (fixed boundary or link)")
    held = [boundary_dofs(n) for n in fixed]
    link_dofs = boundary_dofs(link.boundary) if link is not None else np.zeros(0, dtype=np.int64)
    free = np.setdiff1d(np.arange(basis.N), np.concatenate([*held, link_dofs]))
    Kff = K[free][:, free].tocsc()
    try:
        factor = splu(Kff, permc_spec="COLAMD")  # more fill than MMD, but solves ~2x faster
    except RuntimeError as exc:
        raise SupportError(f"body {body_mesh.name!r}: stiffness is singular ({exc})") from None

    psi = np.zeros(basis.N)
    k_link = 0.0
    if link is not None:
        locs = mesh.doflocs.T
        vel = link.velocity(locs).ravel()  # node k → (2k, 2k+1), matching the dof numbering
        if not fixed:
            psi = vel  # rigid: strain-free, K ψ = 0 exactly
        else:
            psi[link_dofs] = vel[link_dofs]
            psi[free] = -factor.solve(K[free][:, link_dofs] @ psi[link_dofs])
            k_link = float(psi @ (K @ psi))
    return Body(body_mesh.name, body_mesh, material, basis, K, free, tuple(fixed), link, psi,
                k_link, factor)

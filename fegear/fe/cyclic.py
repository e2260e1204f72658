"""A cyclic body: ``count`` identical sectors of one template mesh, condensed onto the cut faces.

Every tooth of a gear has the same shape, so one sector one pitch wide, meshed once with
matching nodes on its two cut faces (:class:`~fegear.fe.mesh.Periodic`), gives the whole ring
by rotation. The template's interior is factorised once; its static modes Ψ = −K_ii⁻¹ K_iI map
the cut-face displacements into it and S = K_II + K_Ii Ψ is its stiffness condensed onto them.
The ring of condensed sectors is block-circulant in the cut faces, so its flexibility comes
from ``count`` small complex inversions (a discrete Fourier transform over the sectors), not
from a ring-sized system.

Sector k is the template turned by k·pitch. Displacements of sector k are written in its own
frame (the template's), so that every sector has the same matrices. The face between sectors
k − 1 and k is unknown U_k, in sector k's frame at its ``a`` cut; sector k's ``b`` cut then
moves by R U_{k+1}, R the rotation by one pitch. A load f on sector t (template dofs) gives the
displacement of sector s

    u_s = δ_st K⁻¹_clamped f + Ψ_full W(t − s) ρ(f),   ρ = f_I + Ψᵀ f_i

with W the ring's flexibility between the two sectors' cut faces. Fixed dofs (a held rim, or a
bore whose elastic part vanishes) stay zero. Units: mm, N.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp

from ..errors import FegearError
from .dofs import facet_nodes, node_dofs
from .forms import stiffness
from .material import ElasticMaterial
from .mesh import BodyMesh
from .solvers import Factor
from .stress import pickled_cache

LOW_RANK_TOL = 1e-12  # a far coupling W(Δ) is kept as a product of thin factors within this
                      # fraction of the norm of W(0) (rounding leaves about 1e-16) …
LOW_RANK_PROBES = 48  # … found from this many random probes, where its rank is at most a
LOW_RANK_SHARE = 0.25  # this share of its size (Δ ≥ 2 on gear templates: 3-17 of 176)


@dataclass(eq=False)
class CyclicBody:
    """The ring of ``count`` sectors of the template ``mesh`` (see the module docstring).

    ``interior``, ``face_a``, ``face_b`` are template dof indices (the a and b cut faces in
    matching order); ``fixed`` the held dofs. ``ring`` holds W(Δ) for Δ = 0 … count − 1, each
    (2 n_f × 2 n_f), mapping the equivalent cut loads ρ of a sector to the cut displacements of
    the sector Δ before it."""

    name: str
    mesh_data: BodyMesh
    material: ElasticMaterial
    count: int
    pitch: float
    K: sp.csr_matrix = field(repr=False)
    interior: np.ndarray = field(repr=False)
    face_a: np.ndarray = field(repr=False)
    face_b: np.ndarray = field(repr=False)
    fixed: np.ndarray = field(repr=False)
    factor: Factor = field(repr=False)
    psi: np.ndarray = field(repr=False)       # (n_interior, 2 n_f): interior per unit cut motion
    ring: np.ndarray = field(repr=False)      # (count, 2 n_f, 2 n_f)
    cache: dict = field(default_factory=dict, repr=False)

    @property
    def mesh(self):
        """The template's scikit-fem mesh."""
        return self.mesh_data.mesh

    @property
    def ndofs(self) -> int:
        return self.K.shape[0]

    @property
    def interface(self) -> np.ndarray:
        return np.concatenate([self.face_a, self.face_b])

    def clamped(self, f: np.ndarray) -> np.ndarray:
        """Template field (ndofs, k) of loads ``f`` (ndofs, k) with both cuts held."""
        f = np.asarray(f, dtype=float)
        u = np.zeros(f.shape)
        u[self.interior] = self.factor.solve(f[self.interior])
        return u

    def cut_loads(self, f: np.ndarray) -> np.ndarray:
        """ρ = f_I + Ψᵀ f_i (2 n_f, k): the loads ``f`` carried to the sector's cut faces."""
        f = np.asarray(f, dtype=float)
        return f[self.interface] + self.psi.T @ f[self.interior]

    def unit_clamped(self, dofs: np.ndarray, interior: bool = False) -> np.ndarray:
        """:meth:`clamped` of a unit load at each of template ``dofs`` (ndofs, len(dofs)),
        its interior right-hand sides set directly rather than cut from a full block of unit
        columns: the same solve of the same numbers. ``interior``: only the interior dofs'
        rows (the others are zero; :meth:`interior_place`), not copied into a full block (the
        baseline's first position forms 500 of them on gear 1: 50 MB fewer written)."""
        inner, _ = self._places()
        x = self.factor.unit_solve(inner[np.asarray(dofs)])
        if interior:
            return x
        u = np.zeros((self.ndofs, x.shape[1]))
        u[self.interior] = x
        return u

    def interior_place(self, dofs: np.ndarray) -> np.ndarray:
        """Each template dof's place among the interior dofs (−1: a cut or held dof)."""
        return self._places()[0][np.asarray(dofs)]

    def _places(self) -> tuple[np.ndarray, np.ndarray]:
        """Per template dof, its place among the interior dofs and among the cut dofs (−1
        where it is not one)."""
        if "dof places" not in self.cache:
            inner = np.full(self.ndofs, -1)
            inner[self.interior] = np.arange(len(self.interior))
            cut = np.full(self.ndofs, -1)
            cut[self.interface] = np.arange(len(self.interface))
            self.cache["dof places"] = (inner, cut)
        return self.cache["dof places"]

    def unit_cut_loads(self, dofs: np.ndarray) -> np.ndarray:
        """:meth:`cut_loads` of a unit load at each of template ``dofs`` (2 n_f, len(dofs)):
        a cut dof's own unit vector, an interior dof's row of Ψ, a held dof's zeros; gathered,
        not multiplied out (Ψᵀ times unit columns was a 1 GFlop product for the baseline's
        first position), the same numbers."""
        dofs = np.asarray(dofs)
        inner, cut = self._places()
        out = np.zeros((len(self.interface), len(dofs)))
        q, r = inner[dofs], cut[dofs]
        out[:, q >= 0] = self.psi[q[q >= 0]].T
        out[r[r >= 0], np.flatnonzero(r >= 0)] = 1.0
        return out

    def from_cuts(self, u_cut: np.ndarray) -> np.ndarray:
        """Template field (ndofs, k) of cut-face displacements (2 n_f, k), interior by Ψ."""
        u = np.zeros((self.ndofs,) + u_cut.shape[1:])
        u[self.interior] = self.psi @ u_cut
        u[self.interface] = u_cut
        return u

    def cut_motions(self, rho: dict[int, np.ndarray], sectors) -> np.ndarray:
        """Cut-face displacements (2 n_f, len(sectors), …) of the ``sectors`` under the cut
        loads ``rho`` (loaded sector → its loads carried to the cuts, :meth:`cut_loads`:
        (2 n_f, …), a column each of several load cases): a far sector's through the
        coupling's thin factors (:meth:`coupling_factors`)."""
        tail = next(iter(rho.values())).shape[1:] if rho else ()
        cuts = np.zeros((len(self.interface), len(sectors)) + tail)
        for j, s in enumerate(sectors):
            for t, r in rho.items():
                factors = self.coupling_factors(t - s)
                cuts[:, j] += (self.coupling(t - s) @ r if factors is None
                               else factors[0] @ (factors[1] @ r))
        return cuts

    def coupling(self, delta: int) -> np.ndarray:
        """W(Δ): cut displacements of sector s per unit cut loads ρ of sector s + Δ."""
        return self.ring[delta % self.count]

    def coupling_factors(self, delta: int) -> tuple[np.ndarray, np.ndarray] | None:
        """W(Δ) ≈ U V with thin U (2 n_f, r) and V (r, 2 n_f), within LOW_RANK_TOL of W(0)'s
        norm, or None where W(Δ) is not of low rank (the sector itself and its neighbours).
        Distant sectors couple through a few smooth modes, so products through W(Δ) cost r/n_f
        of the full ones. Formed once per Δ."""
        d = delta % self.count
        key = ("coupling factors", d)
        if key not in self.cache:
            tol = LOW_RANK_TOL * float(np.linalg.norm(self.ring[0]))
            self.cache[key] = _low_rank(self.ring[d], tol)
        return self.cache[key]

    def displacement(self, loads: dict[int, np.ndarray], sectors,
                     rho: dict[int, np.ndarray] | None = None,
                     clamped: dict[int, np.ndarray] | None = None) -> dict[int, np.ndarray]:
        """Template-frame fields (ndofs,) of the ``sectors`` under ``loads`` (sector → template
        load vector): the sectors' cut motions and the loaded ones' clamped fields each in one
        block (a solve and a product for all, not one a sector). ``rho``: the loads' cut loads
        (:meth:`cut_loads`) where the caller has them; ``clamped``: the clamped fields
        (:meth:`clamped`) of some loaded sectors, formed before."""
        sectors = list(sectors)
        loaded = list(loads)
        if not loaded:
            return {s: np.zeros(self.ndofs) for s in sectors}
        if rho is None:
            block = self.cut_loads(np.column_stack([loads[t] for t in loaded]))
            rho = {t: block[:, i] for i, t in enumerate(loaded)}
        U = self.from_cuts(self.cut_motions({t: rho[t] for t in loaded}, sectors))
        kept = clamped or {}
        for j, s in enumerate(sectors):
            if s in loads and s in kept:
                U[:, j] += kept[s]
        own = [j for j, s in enumerate(sectors) if s in loads and s not in kept]
        if own:
            U[:, own] += self.clamped(np.column_stack([loads[sectors[j]] for j in own]))
        U = np.ascontiguousarray(U.T)
        return {s: U[j] for j, s in enumerate(sectors)}

    def residual(self, loads: dict[int, np.ndarray], fields: dict[int, np.ndarray]) -> float:
        """Largest equilibrium residual of the sectors in ``fields`` at their interior dofs (the
        cut faces balance through the ring), relative to the largest load."""
        scale = max((float(np.linalg.norm(f)) for f in loads.values()), default=0.0)
        worst = 0.0
        for s, u in fields.items():
            f = loads.get(s, np.zeros(self.ndofs))
            worst = max(worst, float(np.linalg.norm((self.K @ u - f)[self.interior])))
        return worst / max(scale, 1e-300)


#: what :func:`cyclic_parts` gives and :func:`restore_cyclic` takes back: the arrays of a
#: cyclic body that cost a factorisation to form (its factor is formed again from them)
PARTS = ("count", "pitch", "K", "interior", "face_a", "face_b", "fixed", "psi", "ring")


def cyclic_parts(body: CyclicBody) -> dict:
    """The arrays of ``body`` :func:`restore_cyclic` rebuilds it from (a model cache's), with
    what its ``cache`` holds that pickles (the stress projector's matrices, the far
    couplings' factors; not a factorisation)."""
    return {**{k: getattr(body, k) for k in PARTS}, "cache": pickled_cache(body.cache)}


def restore_cyclic(mesh: BodyMesh, material: ElasticMaterial, parts: dict) -> CyclicBody:
    """The cyclic body of template ``mesh`` from its :func:`cyclic_parts`: its interior
    factorised again (the static modes and the ring's flexibility, which cost the solves,
    come from ``parts``)."""
    K, interior = parts["K"], parts["interior"]
    return CyclicBody(mesh.name, mesh, material, parts["count"], parts["pitch"], K,
                      interior, parts["face_a"], parts["face_b"], parts["fixed"],
                      Factor(K[interior][:, interior]), parts["psi"], parts["ring"],
                      dict(parts.get("cache", {})))


def assemble_cyclic(mesh: BodyMesh, material: ElasticMaterial, count: int, cut: str,
                    fixed: tuple[str, ...]) -> CyclicBody:
    """Assemble the template ``mesh`` (one sector; its periodic pair named by the slave segment
    ``cut``), hold the ``fixed`` boundaries, factorise the interior once, condense onto the
    cuts and form the ring's flexibility between cut faces for ``count`` sectors."""
    if cut not in mesh.periodic:
        raise FegearError(f"body {mesh.name!r} has no periodic segment {cut!r}")
    m = mesh.mesh
    K = stiffness(m, *material.lame, material.thickness)
    held = np.unique(np.concatenate([facet_nodes(m, m.boundaries[n]).ravel() for n in fixed]))
    pairs = mesh.periodic[cut]
    keep = ~(np.isin(pairs[:, 0], held) | np.isin(pairs[:, 1], held))
    b_nodes, a_nodes = pairs[keep, 0], pairs[keep, 1]
    face_a, face_b = node_dofs(a_nodes).ravel(), node_dofs(b_nodes).ravel()
    fixed_dofs = node_dofs(held).ravel()
    interior = np.setdiff1d(np.arange(K.shape[0]), np.concatenate([fixed_dofs, face_a, face_b]))
    interface = np.concatenate([face_a, face_b])
    factor = Factor(K[interior][:, interior])
    K_iI = K[interior][:, interface].toarray()
    psi = -factor.solve(K_iI)
    S = K[interface][:, interface].toarray() + K_iI.T @ psi
    S = 0.5 * (S + S.T)
    # the b cut moves by R U_{k+1}: rotate its dofs into the next sector's frame
    pitch = _pitch(mesh, cut)
    c, s = math.cos(pitch), math.sin(pitch)
    R = np.kron(np.eye(len(b_nodes)), np.array([[c, -s], [s, c]]))
    nf = len(face_a)
    T = np.block([[np.eye(nf), np.zeros((nf, nf))], [np.zeros((nf, nf)), R]])
    St = T.T @ S @ T
    saa, sab, sba, sbb = St[:nf, :nf], St[:nf, nf:], St[nf:, :nf], St[nf:, nf:]
    ring = _ring_flexibility(saa + sbb, sab, sba, count)
    # W(Δ) between a sector's cut dofs [u_a; u_b] and the cut loads [ρ_a; ρ_b] of sector s + Δ
    W = np.empty((count, 2 * nf, 2 * nf))
    for d in range(count):
        g0, gp, gm = ring[d % count], ring[(d + 1) % count], ring[(d - 1) % count]
        W[d] = np.block([[g0, gp @ R.T], [R @ gm, R @ g0 @ R.T]])
    return CyclicBody(mesh.name, mesh, material, count, pitch, K, interior, face_a, face_b,
                      fixed_dofs, factor, psi, W)


def _low_rank(W: np.ndarray, tol: float) -> tuple[np.ndarray, np.ndarray] | None:
    """Thin factors U V of ``W`` within ``tol`` (Frobenius), or None if its rank is above
    LOW_RANK_SHARE of its size: a randomised range (fixed seed) checked by its residual, then
    truncated by the singular values of the small projection."""
    n = W.shape[1]
    probes = min(LOW_RANK_PROBES, n)
    Q, _ = np.linalg.qr(W @ np.random.default_rng(0).standard_normal((n, probes)))
    B = Q.T @ W
    left = float(np.linalg.norm(W - Q @ B))
    if left > 0.5 * tol:
        return None
    u, s, vt = np.linalg.svd(B, full_matrices=False)
    tail = np.sqrt(np.cumsum((s**2)[::-1]))[::-1]            # norm of what dropping s[r:] loses
    r = int(np.count_nonzero(tail > 0.5 * tol))
    if r > LOW_RANK_SHARE * min(W.shape):
        return None
    return (Q @ u[:, :r]) * s[:r], vt[:r].copy()


def _pitch(mesh: BodyMesh, cut: str) -> float:
    """The angle that turns the master cut onto the slave cut (from the matched nodes)."""
    pairs = mesh.periodic[cut]
    x = mesh.mesh.doflocs.T
    far = np.argmax(np.linalg.norm(x[pairs[:, 1]], axis=1))
    a, b = x[pairs[far, 1]], x[pairs[far, 0]]
    return math.atan2(a[0] * b[1] - a[1] * b[0], a @ b)


def _ring_flexibility(D: np.ndarray, B: np.ndarray, Bt: np.ndarray, count: int) -> np.ndarray:
    """G(Δ) = (K_ring⁻¹)[s, s + Δ] for the block-circulant ring K[s, s] = D, K[s, s + 1] = B,
    K[s + 1, s] = Bᵀ: the inverse of each Fourier block D + B ωᵏ + Bᵀ ω⁻ᵏ, transformed back."""
    k = np.arange(count)
    omega = np.exp(2j * np.pi * k / count)
    blocks = D[None] + B[None] * omega[:, None, None] + Bt[None] * np.conj(omega)[:, None, None]
    inv = np.linalg.inv(blocks)
    # G(Δ) = (1/n) Σ_k inv_k ω^(−kΔ): a forward FFT over k (a dense sum over all Δ and k is
    # quadratic in the teeth)
    return (np.fft.fft(inv, axis=0) / count).real

"""A cyclic body (one template sector condensed onto its cut faces, the ring through a discrete
Fourier transform over the sectors) against the same ring assembled whole from turned copies of
the template: the same displacements to rounding."""

import math

import numpy as np
import pytest
import scipy.sparse as sp
from scipy.sparse.linalg import spsolve

from fegear.fe import BodyGeometry, ElasticMaterial, Periodic, Refinement, Segment, mesh_bodies
from fegear.fe.cyclic import assemble_cyclic
from fegear.fe.dofs import facet_nodes

MAT = ElasticMaterial(thickness=2.0)


def sector(count, a0=0.3, r_in=6.0, r_out=10.0, size=0.9):
    pitch = 2 * math.pi / count

    def ring(r, lo, hi, n=30):
        t = np.linspace(lo, hi, n)
        return r * np.column_stack([np.cos(t), np.sin(t)])

    def snap(r):
        return lambda x: r * x / np.linalg.norm(x, axis=1)[:, None]

    outer, inner = ring(r_out, a0, a0 + pitch), ring(r_in, a0 + pitch, a0)
    segs = (Segment("cut_a", np.array([inner[-1], outer[0]])),
            Segment("outside", outer, snap(r_out)),
            Segment("cut_b", np.array([outer[-1], inner[0]])),
            Segment("inside", inner, snap(r_in)))
    geo = BodyGeometry("sector", segs, size=size, refinements=(Refinement(("outside",), 0.3),),
                       periodic=(Periodic("cut_b", "cut_a", pitch),))
    return mesh_bodies([geo])[0]


def whole_ring(body):
    """K of all sectors assembled in the global frame, and each sector's node numbers."""
    n = body.mesh.doflocs.shape[1]
    pairs = body.mesh_data.periodic["cut_b"]
    z = body.count
    ids = []
    next_id = 0
    first = None
    for k in range(z):
        g = np.full(n, -1)
        if k > 0:
            g[pairs[:, 1]] = ids[-1][pairs[:, 0]]  # a cut = the last sector's b cut
        fresh = g < 0
        if k == z - 1:
            g[pairs[:, 0]] = first[pairs[:, 1]]  # the last b cut closes on the first a cut
            fresh = g < 0
        g[fresh] = next_id + np.arange(fresh.sum())
        next_id += fresh.sum()
        ids.append(g)
        if k == 0:
            first = g
    rows, cols, vals = [], [], []
    for k, g in enumerate(ids):
        c, s = math.cos(k * body.pitch), math.sin(k * body.pitch)
        Q = sp.kron(sp.eye(n), sp.csr_matrix([[c, -s], [s, c]]))  # template → global frame
        Kk = (Q @ body.K @ Q.T).tocoo()
        dof = np.stack([2 * g, 2 * g + 1], -1).ravel()
        rows.append(dof[Kk.row])
        cols.append(dof[Kk.col])
        vals.append(Kk.data)
    N = 2 * next_id
    return sp.coo_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                         shape=(N, N)).tocsc(), ids


@pytest.mark.parametrize("count", [2, 3, 8])
def test_cyclic_ring_equals_the_ring_assembled_whole(count):
    m = sector(count)
    body = assemble_cyclic(m, MAT, count, "cut_b", fixed=("inside",))
    K, ids = whole_ring(body)
    held = np.unique(facet_nodes(m.mesh, m.mesh.boundaries["inside"]).ravel())
    fixed = np.unique(np.concatenate([np.stack([2 * g[held], 2 * g[held] + 1], -1).ravel()
                                      for g in ids]))
    free = np.setdiff1d(np.arange(K.shape[0]), fixed)
    # a load on the outside of sector 1 (template frame), radial and tangential parts
    rng = np.random.default_rng(3)
    outside = np.unique(facet_nodes(m.mesh, m.mesh.boundaries["outside"]).ravel())
    f = np.zeros(body.ndofs)
    f[2 * outside] = rng.standard_normal(len(outside))
    f[2 * outside + 1] = rng.standard_normal(len(outside))
    t = 1 % count
    # and another on sector 0 where that is another sector: the loaded sectors' fields in one
    # block (CyclicBody.displacement)
    loads = {t: f} | ({0: np.roll(f, 7)} if t != 0 else {})
    fields = body.displacement(loads, range(count))
    F = np.zeros(K.shape[0])
    for j, fj in loads.items():
        c, s = math.cos(j * body.pitch), math.sin(j * body.pitch)
        fg = (np.array([[c, -s], [s, c]]) @ fj.reshape(-1, 2).T).T.ravel()
        dof_j = np.stack([2 * ids[j], 2 * ids[j] + 1], -1).ravel()
        np.add.at(F, dof_j, fg)
    u = np.zeros(K.shape[0])
    u[free] = spsolve(K[free][:, free], F[free])
    scale = np.abs(u).max()
    for k in range(count):
        c, s = math.cos(k * body.pitch), math.sin(k * body.pitch)
        mine = (np.array([[c, -s], [s, c]]) @ fields[k].reshape(-1, 2).T).T
        theirs = u[np.stack([2 * ids[k], 2 * ids[k] + 1], -1)]
        assert np.abs(mine - theirs).max() < 1e-9 * scale, k
    assert body.residual(loads, fields) < 1e-9


def test_far_couplings_are_thin_products_within_their_tolerance():
    """Sectors two or more apart couple through a few smooth modes: W(Δ) = U V within
    LOW_RANK_TOL of W(0), U and V thin; the sector itself and its neighbours are kept whole."""
    from fegear.fe.cyclic import LOW_RANK_SHARE, LOW_RANK_TOL

    count = 24
    body = assemble_cyclic(sector(count, size=0.5), MAT, count, "cut_b", fixed=("inside",))
    n = len(body.interface)
    scale = np.linalg.norm(body.ring[0])
    assert body.coupling_factors(0) is None
    assert body.coupling_factors(1) is None and body.coupling_factors(-1) is None
    thin = []
    for delta in range(2, count - 1):
        factors = body.coupling_factors(delta)
        if factors is None:
            continue
        thin.append(delta)
        U, V = factors
        assert U.shape[1] == V.shape[0] <= LOW_RANK_SHARE * n
        err = np.linalg.norm(body.coupling(delta) - U @ V)
        assert err <= LOW_RANK_TOL * scale, delta
    assert set(range(4, count - 3)) <= set(thin)   # this coarse, narrow ring: from Δ = 4
    assert body.coupling_factors(count + 5) is body.coupling_factors(5)   # by Δ mod count


def test_unit_loads_reach_the_cuts_as_the_product_says_and_the_body_comes_back_whole():
    """The cut loads of unit loads, gathered from Ψ's rows, are those of ρ = f_I + Ψᵀ f_i to
    the bit (interior, cut and held dofs alike), and so are their clamped fields solved from
    the interior right-hand sides alone; and a body rebuilt from its parts (a model cache's)
    gives the same fields."""
    from fegear.fe import cyclic_parts, restore_cyclic

    count = 12
    body = assemble_cyclic(sector(count), MAT, count, "cut_b", fixed=("inside",))
    dofs = np.concatenate([body.interior[::7], body.interface[::3], body.fixed[:4]])
    E = np.zeros((body.ndofs, len(dofs)))
    E[dofs, np.arange(len(dofs))] = 1.0
    assert np.array_equal(body.unit_cut_loads(dofs), body.cut_loads(E))
    assert np.array_equal(body.unit_clamped(dofs), body.clamped(E))
    again = restore_cyclic(body.mesh_data, MAT, cyclic_parts(body))
    f = {0: E[:, 5], 3: E[:, 9]}
    for s in (0, 1, 3, 7):
        assert np.array_equal(again.displacement(f, [s])[s], body.displacement(f, [s])[s])

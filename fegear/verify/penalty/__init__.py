"""The peers' contact: frictionless penalty contact between linear bodies, condensed on the
contact nodes. The Hertz case (:mod:`fegear.verify.disks`), the sector model
(:mod:`fegear.verify.sector`) and the CalculiX decks (:mod:`fegear.verify.calculix_pair`)
solve with it; the product's contact solve is the ring model's
(:mod:`fegear.toothpair.ring.contact`, on the kernels of :mod:`fegear.contact`).

Small sliding (docs/model.md, "Contact"): every quadrature point x_q of a slave boundary is
paired once, in the reference configuration, with its closest point y_q on the master's
*exact* curve and with the master mesh facet under y_q. The pointwise gap

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

Each body is factorised once (:mod:`fegear.fe`); condensing onto the contact nodes gives
the flexibility G = Σ_b C_b K_b⁻¹ C_bᵀ (mm/N; a column is formed when the active set first
reaches its point, :class:`PointFlexibility`), and the contact problem becomes small and dense:
on the active set A, (G_AA + W_A⁻¹/κ) λ_A + a_A θ = −h_A, with the link balance k θ − aᵀλ = F.
Active-set (semismooth Newton) iterations stop when A is stable; the link motion is then
re-evaluated exactly until it changes by less than ``link_tol``.

The Hertz case: two 10 mm disks pressed together by 1000 N over 5 mm, coarse (4 elements across
the Hertz half-width):

>>> from fegear.fe import ElasticMaterial, RigidLink, assemble_body, mesh_bodies
>>> from fegear.verify import DiskCase, disk_geometries
>>> from fegear.verify.penalty import ContactPair, build_contact, solve_contact
>>> case = DiskCase(quality="coarse")
>>> g1, g2, _, circle2 = disk_geometries(case)   # named windows, disk 2's exact circle
>>> m1, m2 = mesh_bodies([g1, g2])
>>> b1 = assemble_body(m1, ElasticMaterial(), link=RigidLink("cut", "translation",
...                                                    direction=(0.0, -1.0)))
>>> b2 = assemble_body(m2, ElasticMaterial(), fixed=("cut",))
>>> model = build_contact([b1, b2], [ContactPair("disks", 0, "contact", 1, "contact", circle2)])
>>> solution = solve_contact(model, load=1000.0)
>>> zone = solution.zones[0]                    # the pair's contact zone
>>> round(zone.p_max, 1), round(case.hertz.p0, 1)   # FE against Hertz, MPa
(1147.3, 1145.2)
>>> round(zone.half_width, 4), round(case.hertz.b, 4)
(0.1094, 0.1112)
>>> solution.balance_error < 1e-9
True
"""

from ...exports import lazy

__getattr__, __dir__, __all__ = lazy(__name__, {
    "model": ("ContactError", "Circle", "ContactPair", "ContactSettings", "ContactModel"),
    "flexibility": ("PointFlexibility",),
    "build": ("build_contact",),
    "solve": ("ContactSolution", "PairZone", "solve_contact", "first_touch",
              "nodal_pressure", "forces_from_body"),
})

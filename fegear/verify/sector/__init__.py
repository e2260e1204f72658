"""The sector model of a tooth pair (fegear's first model, now the product's full-FE peer): a meshed
sector of each gear over the teeth that can touch, refined to resolve every contact width,
penalty contact between the sectors (:mod:`fegear.contact`).

:mod:`.scene` decides which teeth to mesh and pair and cuts both gears' sectors into refined
segments; :mod:`.solve` meshes, factorises, places the bodies at each rolling angle and solves
the contact (gear 1's bore turned by one rotation unknown under the torque, gear 2's rim fixed);
:mod:`.recovery` reads the root and contact stresses per tooth. It resolves the contact with
the mesh, so it costs 36-102 s a position at 1 % (docs/benchmark.md); ``fegear bench
--sector-levels`` runs it beside the ring model on any design (docs/validation.md). It solves
through the product's driver (:mod:`fegear.toothpair.positions`): the same teeth, attempts and
reports; its case (:class:`SectorCase`) adds its own two inputs.

A light pair (25/24 teeth) at 20 N·m, coarse:

>>> from fegear.geometry import PairParameters
>>> from fegear.verify.sector import SectorCase, solve_pair
>>> pair = PairParameters(m=2, z2=25, z1=24, shift=0.016, rotation=0.002)
>>> sol = solve_pair(SectorCase(pair, torque=20.0, quality="coarse"))
>>> {name: round(value, 1) for name, value in sol.headline().items()}  # MPa
... # doctest: +NORMALIZE_WHITESPACE
{'root_stress_gear1_MPa': 72.3, 'root_stress_gear2_MPa': 54.7,
 'contact_pressure_MPa': 809.1, 'flank_contact_pressure_MPa': 311.8,
 'von_mises_max_MPa': 801.3}
>>> [(t.tooth, round(t.load_share, 3)) for t in sol.teeth if t.load_N > 0]
[(5, 0.444), (6, 0.556)]
>>> sol.checks.balance_error < 1e-6       # the torque is carried by the contact forces
True
"""

from ...exports import lazy

__getattr__, __dir__, __all__ = lazy(__name__, {
    "scene": ("Scene", "build_scene", "QUALITY"),
    "case": ("SectorCase",),
    "compare": ("cross_check", "cross_table"),
    "recovery": ("contact_split",),
    "solve": ("solve_pair", "solve_positions", "SectorSolver", "SectorDetail", "mesh_ratio"),
})

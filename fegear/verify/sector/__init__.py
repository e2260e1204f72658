"""The sector model of a tooth pair (fegear's first model, now the product's full-FE peer): a meshed
sector of each gear over the teeth that can touch, refined to resolve every contact width,
penalty contact between the sectors (:mod:`fegear.verify.penalty`).

:mod:`.scene` decides which teeth to mesh and pair and cuts both gears' sectors into refined
segments; :mod:`.solve` meshes, factorises, places the bodies at each rolling angle and solves
the contact (gear 1's bore turned by one rotation unknown under the torque, gear 2's rim fixed);
:mod:`.recovery` reads the root and contact stresses per tooth. It resolves the contact with
the mesh, so it costs 36-102 s a position at 1 % (docs/benchmark.md); ``fegear bench
--sector-levels`` runs it beside the ring model on any design (docs/validation.md). It solves
through the product's driver (:mod:`fegear.toothpair.positions`): the same teeth, attempts and
reports; its case (:class:`SectorCase`) adds its own two inputs.

A light pair (25/24 teeth) at 20 N·m, coarse, by both models: the sector model's difference
from the ring model's headline stresses (%), the loaded teeth and their shares:

>>> from fegear.geometry import PairParameters
>>> from fegear.toothpair import HEADLINE, SolveCase
>>> from fegear.verify.sector import cross_check
>>> pair = PairParameters(m=2, z2=25, z1=24, shift=0.016, rotation=0.002)
>>> ring, sector = cross_check(SolveCase(pair, torque=20.0, quality="coarse"))
>>> [round(100 * (sector.headline()[k] / ring.headline()[k] - 1), 1) for k in HEADLINE]
[-3.0, -0.8, 0.5, 0.5, 0.3]
>>> [(t.tooth, round(t.load_share, 3)) for t in sector.teeth if t.load_N > 0]
[(5, 0.444), (6, 0.556)]
>>> sector.checks.balance_error < 1e-6    # the torque is carried by the contact forces
True

(Its free cut faces, two teeth beyond the paired ones, cost the gear-1 root 3 % on a pair this
small; docs/validation.md.)
"""

from ...exports import lazy

__getattr__, __dir__, __all__ = lazy(__name__, {
    "scene": ("Scene", "build_scene", "SECTOR_LEVELS"),
    "case": ("SectorCase",),
    "compare": ("cross_check", "cross_table"),
    "recovery": ("contact_split",),
    "solve": ("solve_pair", "solve_positions", "SectorSolver", "SectorDetail"),
})

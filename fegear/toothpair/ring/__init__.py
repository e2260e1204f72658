"""The ring model of a tooth pair: both gears whole, each from one template sector meshed,
factorised and condensed once per geometry, and the contact's near field from the elastic
half-plane (docs/model.md, "The ring model").

:mod:`.template` meshes one tooth pitch of each gear with matching cut faces; :mod:`.model`
assembles them as cyclic bodies (:class:`~fegear.fe.cyclic.CyclicBody`) for a quality level;
:mod:`.side` carries points and loads between a gear and its template; :mod:`.grid` makes the
pressure grids and :mod:`.placement` places them on the teeth that can touch (and starts a
cycle's later position from the one before); :mod:`.master` places gear 2's exact curve at a
rolling angle and :mod:`.influence` assembles how each grid point approaches it under each
pressure hat; :mod:`.contact` solves the contact under the torque, stepping on its linear
system (:mod:`.contact_system`), and :mod:`.tangent` linearises the solved contact;
:mod:`.stresses` reads the root stresses from the templates and the contact stresses from a
submodel at each peak, which :mod:`.peaks` solves where a cycle's stresses peak;
:mod:`.results` gives per-tooth results and the rings' fields; :mod:`.solver` is the model's
part of a position (:class:`RingSolver`; :mod:`.modes`' :class:`SolverModes`: what it gives
and keeps) for the driver of :mod:`fegear.toothpair.positions`, which loops over the
positions.

The baseline pair at 200 N·m, coarse:

>>> from fegear.geometry import PairParameters
>>> from fegear.toothpair import SolveCase, solve_pair
>>> from fegear.toothpair.ring import build_ring
>>> case = SolveCase(PairParameters(shift=0.016, rotation=0.002), quality="coarse")
>>> model = build_ring(case)        # both templates meshed and condensed, for any torque and β
>>> [side.count for side in model.gears]     # sectors in each ring: the teeth of each gear
[44, 45]
>>> sol = solve_pair(case, model=model)
>>> round(sol.root_stress[0]), round(sol.contact_pressure)   # MPa
(288, 1888)
>>> [(t.tooth, round(t.load_share, 2)) for t in sol.teeth if t.load_N > 0]
[(9, 0.03), (10, 0.43), (11, 0.42), (12, 0.12)]

The same model serves another torque without meshing again; at 20 N·m the contacts stay on
the flanks, beside Hertz (MPa):

>>> from dataclasses import replace
>>> light = solve_pair(replace(case, torque=20.0), model=model)
>>> [(t.tooth, round(t.p_max_MPa), round(t.hertz_p0_MPa)) for t in light.teeth if t.load_N > 0]
[(10, 172, 170), (11, 181, 178)]
"""

from ...exports import lazy

__getattr__, __dir__, __all__ = lazy(__name__, {
    "model": ("RingModel", "RingLevel", "LEVELS", "build_ring", "build_templates"),
    "solver": ("RingSolver", "RingAttempt"),
    "modes": ("SolverModes",),
    "results": ("RingDetail",),
})

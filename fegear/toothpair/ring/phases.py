"""The ring's symmetry, used: a contact assembled at one rolling angle serves every angle whole
gear-2 pitches away.

Both gears are rings of identical sectors, so the pair at β + k·p2 (gear 2 turned k of its
pitches, gear 1 k of its own) is the pair at β with every tooth and sector renumbered: the
grids, the influence matrix A, the loads per unit hat pressure and the matching points are the
same numbers (:func:`turned` renumbers them and turns the gear-frame points). Only the rigid
gaps differ, where the pair's deviations differ from tooth to tooth. So a revolution, whose
z1 pitches repeat each position of one pitch, assembles each of those positions once
(:class:`Phases`) and solves the others as gap vectors on it: a contact solve, not a placement
and an assembly. Where the kept contact does not hold a pitch's contact (a deviated tooth loads
a grid's end, a probe, or a tooth without a grid), the pitch is placed and assembled as any
position, and its contact is kept instead.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ...errors import ContactError
from ...geometry import Placed
from ...planar import rotate
from ..case import PairSolution, SolveCase
from ..teeth import choose_teeth
from .contact import RingContactSolution, rigid_gap, solve_ring_contact
from .grid import ToothGrid
from .influence import ColumnRule, Matching, RingContact, assemble_contact
from .model import RingModel
from .placement import PLACEMENT
from .results import RingDetail
from .side import Located
from .stresses import RingStresses, RootZone

#: the resolution (a fraction of a gear-2 pitch) at which two rolling angles count as one phase
PHASE_STEPS = 2 ** 20
#: rigid gaps (mm) that differ by less than this anywhere are the same contact problem: 0.1 nm,
#: a ten-thousandth of the smallest deviation given in whole µm, far above the turned
#: points' rounding (1e-15 mm)
SAME_GAP = 1e-7


@dataclass(frozen=True)
class Solved:
    """A position's solution kept for the pitches of its phase whose rigid gaps, at its solved
    rotation, are its ``gaps`` (mm): solved ``pitch`` gear-2 pitches from zero."""

    pitch: int
    gaps: np.ndarray
    solution: PairSolution


@dataclass(frozen=True)
class Kept:
    """A position's contact kept for the positions whole pitches away: assembled at the rolling
    angle ``pitch`` gear-2 pitches from zero, every fine grid's columns formed, with its
    solved rotation (rad), the points that carried pressure (where a solve at another pitch
    starts from), the rotation's elastic part (µm of arc at r0), and the teeth the driver
    paired there with the deviations' reach on each (µm; a paired tooth that nothing of
    brought within reach of gear 2 has no grid)."""

    pitch: int
    contact: RingContact
    rotation: float
    active: np.ndarray
    elastic_um: float
    reach_um: dict[int, float]


def phase_of(case: SolveCase, beta: float) -> tuple[int, int]:
    """(phase, pitch) of the rolling angle ``beta`` (rad): its place within a gear-2 pitch, in
    :data:`PHASE_STEPS`, and how many whole pitches it lies from zero."""
    steps = round(beta / (2 * math.pi / case.params.z2) * PHASE_STEPS)
    return steps % PHASE_STEPS, steps // PHASE_STEPS


class Phases:
    """The contacts kept by phase (:class:`Kept`), for one model."""

    def __init__(self) -> None:
        self._kept: dict[int, Kept] = {}
        self._solved: dict[int, Solved] = {}

    def repeat(self, model: RingModel, case: SolveCase, state) -> PairSolution | None:
        """The solution at ``case.beta`` (clearance ``state``) as the last one solved in its
        phase, renumbered, where their rigid gaps are the same (module docstring); else
        None."""
        phase, pitch = phase_of(case, case.beta)
        last = self._solved.get(phase)
        if last is None:
            return None
        pitches = pitch - last.pitch
        sol = last.solution
        placed = Placed(case.deviations, case.params, case.beta) if case.deviations else None
        contact = turned(model, sol.detail.contact, pitches, case.beta, placed)
        gaps = rigid_gap(model, contact, case.params.ratio * case.beta + sol.rotation,
                         contact.feet.copy())[0]
        if np.abs(gaps - last.gaps).max() > SAME_GAP:
            return None
        return _renumbered(sol, pitches, case, state, contact)

    def solved(self, model: RingModel, sol: PairSolution) -> None:
        """Keep ``sol``, solved, for the pitches of its phase with its rigid gaps."""
        detail, case = sol.detail, sol.case
        phase, pitch = phase_of(case, case.beta)
        contact = detail.contact
        gaps = rigid_gap(model, contact, case.params.ratio * case.beta + sol.rotation,
                         contact.feet.copy())[0]
        self._solved[phase] = Solved(pitch, gaps, sol)

    def solve(self, model: RingModel, case: SolveCase, state
              ) -> tuple[RingContact, RingContactSolution] | None:
        """The contact at ``case.beta`` on the contact kept for its phase, turned to it, and its
        solution; None where none is kept or the kept grids do not hold this contact: the
        driver's rule at the solved rotation (``state``) chooses a tooth without a grid, a
        grid carries pressure at an end, a probe carries any, or a point whose column is not
        formed closes."""
        phase, pitch = phase_of(case, case.beta)
        kept = self._kept.get(phase)
        if kept is None:
            return None
        placed = Placed(case.deviations, case.params, case.beta) if case.deviations else None
        contact = turned(model, kept.contact, pitch - kept.pitch, case.beta, placed)
        try:
            sol = solve_ring_contact(model, contact, case.torque * 1e3, kept.rotation,
                                     start=kept.active)
        except ContactError:
            return None
        if sol is None or not _holds(case, state, kept, pitch - kept.pitch, contact, sol):
            return None
        return contact, sol

    def keep(self, model: RingModel, case: SolveCase, teeth, contact: RingContact,
             sol: RingContactSolution, elastic_um: float) -> None:
        """Keep the settled ``contact`` at ``case.beta`` on the paired ``teeth`` for its phase,
        assembled again with every fine grid's columns (the settled one has only those that
        could carry pressure at its own gaps); ``elastic_um``: its rotation's elastic part."""
        phase, pitch = phase_of(case, case.beta)
        full = contact if contact.formed.all() else assemble_contact(
            model, contact.grids, contact.beta, contact.turn, ColumnRule(probes=False),
            contact.placed)
        self._kept[phase] = Kept(pitch, replace(full, feet=contact.feet.copy()),
                                 sol.rotation, sol.pressure > 0, elastic_um,
                                 {t: case.deviations.reach_um(t) for t in teeth})


def _holds(case: SolveCase, state, kept: Kept, pitches: int, contact: RingContact,
           sol: RingContactSolution) -> bool:
    """Whether the ``kept`` grids, turned by ``pitches`` (``contact``), hold its solution
    ``sol`` (:meth:`Phases.solve`). A tooth the driver's rule pairs at the solved rotation
    needs a grid, unless it was paired where the contact was kept, had no grid there, and
    neither the deviations nor the elastic rotation reach further now (its gap is then
    beyond the reach its window was sought within)."""
    p = case.params
    gridded = {g.tooth for g in contact.grids}
    elastic_um = p.arc_um(sol.rotation) - state.closest(+1).plus_um
    for t in set(choose_teeth(state, p.arc_um(sol.rotation), case.extra_pairs)) - gridded:
        then = (t + pitches) % p.z1
        if (then not in kept.reach_um or case.deviations.reach_um(t) > kept.reach_um[then]
                or elastic_um > (1.0 + PLACEMENT) * kept.elastic_um):
            return False
    for k, g in enumerate(contact.grids):
        pressure = sol.pressure[contact.block(k)]
        if pressure[[0, -1]].max() > 0 or (g.probe and pressure.max() > 0):
            return False
    return True


def _renumbered(sol: PairSolution, pitches: int, case: SolveCase, state,
                contact: RingContact) -> PairSolution:
    """``sol`` at ``case`` ``pitches`` gear-2 pitches later, on its ``contact`` turned there:
    the teeth and sectors renumbered, each tooth's clearance from ``state``."""
    p = case.params
    clearance = {c.tooth: c.plus_um for c in state.teeth}
    teeth = tuple(replace(t, tooth=(t.tooth - pitches) % p.z1,
                          tooth2=None if t.tooth2 is None else (t.tooth2 - pitches) % p.z2,
                          clearance_um=clearance.get((t.tooth - pitches) % p.z1))
                  for t in sol.teeth)
    d = sol.detail
    stresses = None if d.stresses is None else _turned_stresses(d.model, d.stresses, pitches)
    detail = RingDetail(d.model, case, contact, d.solution, stresses)
    return replace(sol, case=case, teeth=teeth, timings_s={}, detail=detail)


def _turned_stresses(model: RingModel, stresses: RingStresses, pitches: int) -> RingStresses:
    """``stresses`` renumbered ``pitches`` sectors back on each gear (the fields' arrays are
    shared)."""
    fields, roots, subs = [], [], []
    for g, side in enumerate(model.gears):
        fields.append({(k - pitches) % side.count: u for k, u in stresses.fields[g].items()})
        root = stresses.roots[g]
        roots.append(RootZone(root.angle - pitches * side.pitch, root.s1))
    subs = tuple((g, turn - pitches * model.gears[g].pitch, sm)
                 for g, turn, sm in stresses.submodels)
    return replace(stresses, fields=tuple(fields), roots=tuple(roots), submodels=subs)


def turned(model: RingModel, contact: RingContact, pitches: int, beta: float,
           placed: Placed | None) -> RingContact:
    """``contact`` at the rolling angle ``beta``, ``pitches`` gear-2 pitches after the one it
    was assembled at (module docstring): gear 1 has turned ``pitches`` of its pitches, so the
    tooth that stood at a place is the one ``pitches`` before it, and gear 2's likewise; the
    gear-frame points turn back by as much, the template-frame numbers stay. ``placed``: the
    pair's deviations at ``beta``."""
    g1, g2 = model.gears
    turn1, turn2 = pitches * g1.pitch, pitches * g2.pitch
    grids = tuple(_turned_grid(g, pitches, g1.count, g1.pitch) for g in contact.grids)
    return RingContact(
        beta, contact.turn + turn1, grids, contact.offsets, rotate(contact.x, -turn1),
        rotate(contact.normal, -turn1), contact.weight,
        ({(s - pitches) % g1.count: b for s, b in contact.loads[0].items()},
         {(s - pitches) % g2.count: b for s, b in contact.loads[1].items()}),
        (_turned_matching(contact.matching[0], pitches, g1.count, turn1),
         _turned_matching(contact.matching[1], pitches, g2.count, turn2)),
        (rotate(contact.facing[0], -turn2), rotate(contact.facing[1], -turn2)),
        contact.A, contact.formed, contact.feet - turn2, placed)


def _turned_grid(grid: ToothGrid, pitches: int, count: int, pitch: float) -> ToothGrid:
    """``grid`` on the tooth ``pitches`` before its own (its points turned back by as many
    pitches, the tooth numbered within the gear)."""
    tooth = (grid.tooth - pitches) % count
    angle = (tooth - grid.tooth) * pitch
    return replace(grid, tooth=tooth, phi=grid.phi + angle, x=rotate(grid.x, angle),
                   normal=rotate(grid.normal, angle), coarse=None)


def _turned_matching(m: Matching, pitches: int, count: int, turn: float) -> Matching:
    """Matching points of sectors ``pitches`` before their own: the same template points."""
    at = Located(np.mod(m.at.sector - pitches, count), m.at.local, m.at.turn - turn)
    return replace(m, at=at)

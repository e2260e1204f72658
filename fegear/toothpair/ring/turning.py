"""A contact, and a solution on it, turned by whole pitches (:mod:`.phases`): both gears are
rings of identical sectors, so the pair at β + k·p2 is the pair at β with every tooth and
sector renumbered and the gear-frame points turned; the template-frame numbers (A, the loads,
the matching points' places in their sectors, the fields) stay."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ...geometry import Placed
from ...planar import rotate
from ..case import PairSolution, SolveCase
from ..teeth import candidate_data
from .grid import ToothGrid
from .influence import Matching, RingContact
from .model import RingModel
from .results import RingDetail, tooth_result
from .side import Located
from .stresses import RingStresses, RootZone
from .touch import touch_rotation


def turned(model: RingModel, contact: RingContact, pitches: int, beta: float,
           placed: Placed | None) -> RingContact:
    """``contact`` at the rolling angle ``beta``, ``pitches`` gear-2 pitches after the one it
    was assembled at (:mod:`.phases`): gear 1 has turned ``pitches`` of its pitches, so the
    tooth that stood at a place is the one ``pitches`` before it, and gear 2's likewise; the
    gear-frame points turn back by as much, the template-frame numbers stay. ``placed``: the
    pair's deviations at ``beta``."""
    if pitches == 0:   # its own pitch (a class's samples at a position): its own numbers
        return replace(contact, beta=beta, feet=contact.feet.copy(), placed=placed,
                       grids=tuple(replace(g, coarse=None) for g in contact.grids))
    g1, g2 = model.gears
    turn1, turn2 = pitches * g1.pitch, pitches * g2.pitch
    grids = tuple(turned_grid(g, pitches, g1.count, g1.pitch) for g in contact.grids)
    return RingContact(
        beta, contact.turn + turn1, grids, contact.offsets, rotate(contact.x, -turn1),
        rotate(contact.normal, -turn1), contact.weight,
        ({(s - pitches) % g1.count: b for s, b in contact.loads[0].items()},
         {(s - pitches) % g2.count: b for s, b in contact.loads[1].items()}),
        (_turned_matching(contact.matching[0], pitches, g1.count, turn1),
         _turned_matching(contact.matching[1], pitches, g2.count, turn2)),
        (rotate(contact.facing[0], -turn2), rotate(contact.facing[1], -turn2)),
        contact.A, contact.formed, contact.feet - turn2, placed, contact.former)


def turned_again(turns: dict[int, RingContact], model: RingModel, contact: RingContact,
                 pitches: int, beta: float, placed: Placed | None) -> RingContact:
    """:func:`turned`, with what it turns kept in ``turns`` (by pitches) for the calls after
    it: a contact kept for a phase is turned to the same few pitches for every deviation set
    solved on it. Each call has its own feet (a solve writes them)."""
    if pitches not in turns:
        turns[pitches] = turned(model, contact, pitches, beta, None)
    same = turns[pitches]
    return replace(same, beta=beta, feet=same.feet.copy(), placed=placed)


def turned_grid(grid: ToothGrid, pitches: int, count: int, pitch: float) -> ToothGrid:
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


def renumbered(sol: PairSolution, pitches: int, case: SolveCase, state,
                contact: RingContact, again: tuple | None = None) -> PairSolution:
    """``sol`` at ``case`` ``pitches`` gear-2 pitches later, on its ``contact`` turned there:
    the teeth and sectors renumbered, each tooth's clearance from ``state`` (None: kept).
    ``again``: the rigid gaps and their rates at the solved rotation, and the grids whose
    unloaded teeth's results are formed again there with the first touch (their rigid gaps
    moved)."""
    p = case.params
    clearance = None if state is None else {c.tooth: c.plus_um for c in state.teeth}
    teeth = tuple(replace(t, tooth=(t.tooth - pitches) % p.z1,
                          tooth2=None if t.tooth2 is None else (t.tooth2 - pitches) % p.z2,
                          clearance_um=t.clearance_um if clearance is None
                          else clearance.get((t.tooth - pitches) % p.z1))
                  for t in sol.teeth)
    d = sol.detail
    stresses = None if d.stresses is None else turned_stresses(d.model, d.stresses, pitches)
    detail = RingDetail(d.model, case, contact, d.solution, stresses)
    out = replace(sol, case=case, teeth=teeth, timings_s={}, detail=detail)
    if again is None:
        return out
    rigid, grids = again
    redone = list(teeth)
    shown = tuple(contact.grids[k].tooth for k in grids)
    cands = {c.tooth: c for c in candidate_data(p, d.model.shape, state, shown, case.beta)}
    for k in grids:
        tooth = contact.grids[k].tooth
        i = next(j for j, t in enumerate(teeth) if t.tooth == tooth)
        redone[i] = tooth_result(detail, k, rigid, cands.get(tooth), clearance.get(tooth))
    touch = touch_rotation(d.model, contact, sol.first_touch)
    return replace(out, teeth=tuple(redone), first_touch=touch)


def turned_stresses(model: RingModel, stresses: RingStresses, pitches: int) -> RingStresses:
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

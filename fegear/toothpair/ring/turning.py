"""A contact turned by whole pitches (:mod:`.phases`): both gears are rings of identical
sectors, so the pair at β + k·p2 is the pair at β with every tooth and sector renumbered and
the gear-frame points turned; the template-frame numbers (A, the loads, the matching points'
places in their sectors) stay."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ...geometry import Placed
from ...planar import rotate
from .grid import ToothGrid
from .influence import Matching, RingContact
from .model import RingModel
from .side import Located


def turned(model: RingModel, contact: RingContact, pitches: int, beta: float,
           placed: Placed | None) -> RingContact:
    """``contact`` at the rolling angle ``beta``, ``pitches`` gear-2 pitches after the one it
    was assembled at (:mod:`.phases`): gear 1 has turned ``pitches`` of its pitches, so the
    tooth that stood at a place is the one ``pitches`` before it, and gear 2's likewise; the
    gear-frame points turn back by as much, the template-frame numbers stay. ``placed``: the
    pair's deviations at ``beta``."""
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
        contact.A, contact.formed, contact.feet - turn2, placed)


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

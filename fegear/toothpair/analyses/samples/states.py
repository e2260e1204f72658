"""The exact pair's clearance states at a class's positions and over a whole turn
(:class:`States`), and where a sampled pair takes up the backlash (:func:`jammed`): what every
sample of a tolerance class is solved against, found once (:mod:`.solve`)."""

from __future__ import annotations

import math

import numpy as np

from ....geometry import closing_points, least_clearances
from ...case import SolveCase, revolution_positions
from ...positions import TURN_CHECK, Clearances
from ...teeth import closure


class States:
    """The exact pair's clearance states at the positions (``loaded``: (β, state) pairs, the
    loaded flanks, as the driver finds them: :class:`~.positions.Clearances`; with
    ``pitches`` > 1, ``at(i, n)``: position i's state n gear-2 pitches on) and, for the check
    that a sample leaves the pair its backlash, over a whole turn of gear 1 and at the
    positions (``turn``: :data:`~.positions.TURN_CHECK` angles a pitch and the positions, both
    sides of each state found in one search) and the loaded sides' closing points that
    deviations reaching ``reach_um`` could close (``closing``, whose feet on gear 2 the first
    pair checked finds and the others' searches start from)."""

    def __init__(self, case: SolveCase, profile, betas: tuple[float, ...],
                 reach_um: float, pitches: int = 1) -> None:
        p = case.params
        clearances = Clearances(case, profile, betas)
        find = clearances.find
        self.case = case
        self.pitches = pitches
        self.reach_um = reach_um
        self.loaded = clearances.get()
        # the positions too, as a deviated solve checks them: a pair that jams exactly
        # there may turn at the turn's angles beside them
        turn = (*revolution_positions(betas[0], TURN_CHECK, p.z1, p.z2), *betas)
        self.turn = list(zip(turn, find(turn)))
        self.closing = closing_points(p, [s for _, s in self.turn]).reachable(p, reach_um)
        # place-major: one search a place, the other pitches its state renumbered
        self.revolution = [s for _, s in self.loaded] if pitches == 1 else find(
            [self.beta(i, n) for i in range(len(betas)) for n in range(pitches)],
            directions=(+1,))

    def beta(self, i: int, n: int) -> float:
        """The rolling angle (rad) of position i, ``n`` gear-2 pitches on."""
        return self.loaded[i][0] + n * 2 * math.pi / self.case.params.z2

    def at(self, i: int, n: int):
        """The exact pair's clearance state at position i, ``n`` gear-2 pitches on."""
        return self.revolution[i * self.pitches + n]


def jammed(states: States, deviations) -> str | None:
    """Where ``deviations`` take up the pair's backlash over a whole turn (:func:`~.teeth.
    closure`, in words), else None: the check a deviated solve makes
    (:class:`~.positions.Clearances`), for many pairs against one set of closing points: the
    smallest clearances alone, the loaded sides' over the turn in one batch of gaps, the coast
    sides' where a loaded side overlaps in another."""
    p = states.case.params
    least, teeth = least_clearances(deviations, p, states.closing)
    behind = np.flatnonzero(least < 0)
    if not len(behind):
        return None
    coast = closing_points(p, [states.turn[i][1] for i in behind], -1)
    back = least_clearances(deviations, p, coast)[0]
    for i, b in zip(behind, back):
        where = closure(states.turn[i][0], int(teeth[i]), float(least[i]), float(b))
        if where is not None:
            return str(where)
    return None

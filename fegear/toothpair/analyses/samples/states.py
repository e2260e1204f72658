"""The exact pair's clearance states at a class's positions and over a whole turn
(:class:`States`), and where a sampled pair takes up the backlash (:func:`jammed`): what every
sample of a tolerance class is solved against, found once (:mod:`.solve`).

A pair's check over a turn measures its deviated clearances first on the closing points'
foot circles (:class:`ClosingCircles`: the exact pair's feet on gear 2's curve, found once,
and the curve there replaced by its osculating circle, as a kept contact's points are,
:mod:`~fegear.toothpair.ring.circles`), then exactly at the states whose least came within
:func:`screen_um` of closing: the states that close are the same, and every number the check
gives is the exact one."""

from __future__ import annotations

import math
from collections.abc import Callable
from functools import cache

import numpy as np

from ....geometry import (
    NO_DEVIATIONS,
    Closing,
    Placed,
    closing_points,
    gear2_tooth,
    least_clearances,
    least_of_states,
)
from ...case import SolveCase, revolution_positions
from ...positions import TURN_CHECK, Clearances
from ...ring.circles import FootCircles, circle_gaps, moved_by
from ...teeth import INTERFERENCE_UM, closure

#: how near closing (µm of arc at r0) a state's least clearance on the foot circles has to come
#: to be measured exactly (:func:`screen_um`): the circles match gear 2's curve to the second
#: order in a foot's slide, so their clearances are off by the cube of how far a pair's
#: deviations move its teeth, at most 1.1e-6 µm a µm³ over the baseline's classes 4-10 (0.03
#: µm for class 6, 5 µm for class 10): a margin of 1 µm and twenty times that
SCREEN_UM, SCREEN_CUBIC = 1.0, 2e-5
#: the states near closing a pair's check measures exactly at a time, in turn order
#: (:func:`jammed`): a pair that jams is told so at the first that closes
STATES_AT_ONCE = 16


def screen_um(deviations) -> float:
    """How near closing (µm) a state's least clearance on the foot circles has to come to be
    measured exactly with ``deviations`` (:data:`SCREEN_UM`)."""
    return SCREEN_UM + SCREEN_CUBIC * deviations.widest_um() ** 3


class ClosingCircles:
    """The ``closing`` points' foot circles on the exact pair (in the fixed frame at each
    point's β, where it closes the exact pair, as a kept contact's stand:
    :mod:`~fegear.toothpair.ring.circles`), found once with the points' feet, which the
    closing points keep for the exact searches to start from, and each point's gear-2
    tooth."""

    def __init__(self, params, closing: Closing) -> None:
        self.params, self.closing = params, closing
        self.turns = closing.turns(params)
        at = Placed(NO_DEVIATIONS, params, closing.beta)
        at.gap(closing.x, closing.tooth, self.turns, closing.feet, flanks=closing.direction > 0)
        self.circles = FootCircles.at_feet(at.curve2, closing.feet, closing.beta)
        self.teeth2 = gear2_tooth(closing.feet, params.z2)

    def clearances(self, deviations) -> np.ndarray:
        """Each point's clearance (µm of arc at r0) moved by ``deviations``, measured to its
        foot circle as :func:`~fegear.geometry.point_clearances` measures it to gear 2's
        curve: the points moved as :meth:`~fegear.geometry.Placed.gap` moves them
        (:func:`~fegear.toothpair.ring.circles.moved_by`), by the Newton step alone: where a
        point grazes gear 2 and the deviations close it the exact clearance follows the
        tooth's gap along the turn instead (:func:`~fegear.geometry.deviations.grazes`),
        and the step lies below it (the gap about convex in the turn), so that the screen
        measures such a state sooner, not later."""
        p, c = self.params, self.closing
        placed = Placed(deviations, p, c.beta)
        moved = moved_by(placed, c.x, c.tooth, self.turns, self.teeth2, c.direction > 0)
        gap, rate = circle_gaps(self.circles, moved, 0.0)
        return c.um + p.arc_um(np.abs(gap) / placed.levers(rate, c.direction)) * np.sign(gap)


class States:
    """The exact pair's clearance states at the positions (``loaded``: (β, state) pairs, the
    loaded flanks, as the driver finds them: :class:`~.positions.Clearances`; with
    ``pitches`` > 1, ``at(i, n)``: position i's state n gear-2 pitches on) and, for the check
    that a sample leaves the pair its backlash, over a whole turn of gear 1 and at the
    positions (``turn``: :data:`~.positions.TURN_CHECK` angles a pitch and the positions, both
    sides of each state found in one search), the loaded sides' closing points that
    deviations reaching ``reach_um`` could close (``closing``) with their foot circles
    (``circles``), and the coast sides' circles (``coast``, its points its ``closing``)."""

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
        self.circles = ClosingCircles(p, self.closing)
        self.coast = ClosingCircles(p, closing_points(p, [s for _, s in self.turn], -1))
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

    def near(self, deviations) -> np.ndarray:
        """The states over the turn (indices into ``turn``) whose least loaded clearance that
        ``deviations`` leave on the foot circles is within :func:`screen_um` of closing."""
        least = least_of_states(self.circles.clearances(deviations), self.closing)[0]
        return np.flatnonzero(least < screen_um(deviations))


def jammed(states: States, deviations) -> str | None:
    """Where ``deviations`` take up the pair's backlash over a whole turn (:func:`~.teeth.
    closure`, in words), else None: the check a deviated solve makes
    (:class:`~.positions.Clearances`), for many pairs against one set of closing points: the
    smallest clearances alone, the loaded sides' over the turn measured exactly where the foot
    circles put them near closing (:meth:`States.near`), the coast sides' where a loaded side
    overlaps and the coast's circles leave the two sides near taking up the backlash. The
    near states are measured :data:`STATES_AT_ONCE` at a time, in turn order, until one
    closes: the first that does, as where every one is measured."""
    near = states.near(deviations)
    coast = cache(lambda: least_of_states(states.coast.clearances(deviations),
                                          states.coast.closing)[0])
    for lo in range(0, len(near), STATES_AT_ONCE):
        where = _closes(states, deviations, near[lo:lo + STATES_AT_ONCE], coast)
        if where is not None:
            return where
    return None


def _closes(states: States, deviations, near: np.ndarray,
            coast: Callable[[], np.ndarray]) -> str | None:
    """Where ``deviations`` take up the backlash at the first of the states ``near`` (indices
    into ``turn``, increasing) that they close (:func:`jammed`), else None; ``coast()``: the
    coast sides' least clearances on their circles by state (formed once, where wanted)."""
    p = states.case.params
    least, teeth = least_clearances(deviations, p, states.closing.of_states(near))
    behind = np.flatnonzero(least < 0)
    if not len(behind):
        return None
    back = coast()[near[behind]]
    behind = behind[least[behind] + back < screen_um(deviations) - INTERFERENCE_UM]
    back = least_clearances(deviations, p, states.coast.closing.of_states(near[behind]))[0]
    for i, b in zip(behind, back):
        where = closure(states.turn[near[i]][0], int(teeth[i]), float(least[i]), float(b))
        if where is not None:
            return str(where)
    return None

"""Where a position's pressure grids go, and what it starts from: the ring model's part of an
attempt's placement.

Each chosen tooth gets a grid over the stretch of its profile that the expected rotation can
bring within reach of gear 2 (:func:`place_grids`): fine on the teeth the rigid rotation
closes (:func:`expected_teeth`), a coarse probe on the others. A later position of a cycle
starts from the position before it: its active set from where that one carried pressure
(:func:`loaded_before`), its influence columns first on about that stretch
(:func:`columns_before`), and its foot searches from that one's feet. A solved attempt has
settled where its contact stays on its grids (:func:`outside`), else it gives the trial to
place them again from (:func:`judged`).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ...errors import FegearError
from ...fe import contact_modulus
from ..case import SolveCase
from ..positions import SHARE_GUESS, Attempt, Trial, expected_elastic_um
from ..teeth import choose_teeth
from .grid import Facing, GridSpacing, ToothGrid, tooth_grids, windows
from .model import RingModel
from .results import RingDetail

REACH = 1.5          # grids reach where the rigid gap is within this many expected elastic
                     # approaches of closing (3 gave the same values within 6e-5 with a third
                     # more points) …
REACH_FLOOR = 1e-4   # … and at least this many modules; …
WIDEST_REACH = 0.02  # … widened up to this many where no tooth is within reach
GRID_FLOOR = 1e-5    # smallest grid spacing, in modules (20 nm at m = 2)
PLACEMENT = 0.1      # grids are placed again if the solved rotation's elastic part differs
                     # from the expected one by more than this fraction
PROBE_MARGIN_UM = 1.0  # fine grids also on teeth within this of closing at the expected rotation
CANDIDATES = 0.1     # A's columns first on the points whose rigid gap at the expected rotation
                     # is below this many expected elastic approaches (a rotation off by
                     # PLACEMENT gets new grids anyway; loaded points overlap by a fifth of the
                     # approach or more on the baseline's cycle)
BEFORE_MARGIN = 0.15 # a later position of a cycle forms them only on the points within this
BEFORE_POINTS = 4    # fraction of its loaded stretch, and this many points, of where the
                     # position before carried pressure on the same tooth (on the baseline's
                     # cycle a stretch's ends move by 0.23 of it from one position to the next
                     # at most, 0.05 on most)


@dataclass(frozen=True)
class GridPlacement:
    """What an attempt placed its grids for, handed to the next attempt at the same position
    (:attr:`~fegear.toothpair.positions.Trial.own`): the teeth with fine grids (``full``;
    None: those the expected rotation closes, :func:`expected_teeth`) and the factors their
    reach was widened by (``reach``: a grid that carried pressure at an end is placed again
    twice as wide)."""

    full: frozenset[int] | None = None
    reach: dict = field(default_factory=dict)


def by_tooth(before: RingDetail) -> dict:
    """The grids of a solved position by tooth, each with its pressures (a later position's
    start and columns read them)."""
    return {g.tooth: (g, before.solution.pressure[before.contact.block(k)])
            for k, g in enumerate(before.contact.grids)}


def loaded_before(old: dict, grids: tuple[ToothGrid, ...]) -> np.ndarray | None:
    """The points of ``grids`` that lie where the position before (its grids by tooth,
    :func:`by_tooth`) carried pressure on the same tooth (the active set's start: the
    contact moves a little from one position of a cycle to the next, and on the baseline's
    cycle the solve then takes 5-12 active-set iterations, 7 on most, instead of 12-18 from
    the rigid overlap); None where it holds no such tooth."""
    if not any(g.tooth in old for g in grids):
        return None
    out = []
    for g in grids:
        if g.tooth in old:
            prev, p = old[g.tooth]
            out.append(np.interp(g.phi, prev.phi, p, left=0.0, right=0.0) > 0.0)
        else:
            out.append(np.zeros(len(g), dtype=bool))
    return np.concatenate(out)


def columns_before(old: dict, grids: tuple[ToothGrid, ...]) -> np.ndarray | None:
    """The points of ``grids`` whose columns of A a later position forms first: on a tooth
    that carried pressure in the position before (its grids by tooth, :func:`by_tooth`),
    those within :data:`BEFORE_MARGIN` of that stretch and :data:`BEFORE_POINTS` points of it
    (the contact moves a little from one position to the next); none on a tooth that had a
    grid there but carried nothing; every point of a tooth new to the grids. Should a point
    left out close, the candidates' columns are formed, then every column
    (:meth:`~.solver.RingSolver.attempt`). None where it holds no loaded tooth of ``grids``."""
    out, narrowed = [], False
    for g in grids:
        keep = np.full(len(g), g.tooth not in old)
        if g.tooth in old and old[g.tooth][1].max() > 0.0:
            prev, p = old[g.tooth]
            loaded = prev.phi[p > 0.0]
            margin = BEFORE_MARGIN * (loaded[-1] - loaded[0])
            on = np.flatnonzero((g.phi >= loaded[0] - margin) & (g.phi <= loaded[-1] + margin))
            keep[:] = False
            if len(on):
                keep[max(on[0] - BEFORE_POINTS, 0):on[-1] + BEFORE_POINTS + 1] = True
            narrowed = True
        out.append(keep)
    return np.concatenate(out) if narrowed else None


def expected_teeth(state, closure_um: float) -> set[int]:
    """Teeth a rigid rotation of ``closure_um`` (µm of arc at r0) closes: they get fine grids,
    the others chosen coarse probe grids (:func:`~.grid.tooth_grids`)."""
    return {c.tooth for c in state.teeth
            if c.plus_um is not None and c.plus_um <= closure_um + PROBE_MARGIN_UM}


def place_grids(model: RingModel, case: SolveCase, trial: Trial, placement: GridPlacement,
                first_um: float, coarse: dict | None = None) -> tuple[ToothGrid, ...]:
    """A grid on each of ``trial``'s teeth whose profile the trial's rotation (``first_um``,
    the first touch, plus its elastic part; µm of arc at r0) brings within reach of gear 2,
    widened by ``placement.reach``; fine on ``placement.full``, a probe on the others.
    ``coarse``: the windows' coarse feet found before by tooth (:func:`~.grid.windows`'
    start)."""
    teeth, elastic_um, full, reach = trial.teeth, trial.elastic_um, placement.full, placement.reach
    p = case.params
    base = REACH * elastic_um * 1e-3 + REACH_FLOOR * p.m
    turn = p.ratio * case.beta + p.turn_of(first_um)   # at the first touch
    E_star = contact_modulus(case.E, case.E)
    load = case.torque_Nmm / p.r0 / SHARE_GUESS / case.thickness
    # the grids' largest spacing follows the reach of the expected rotation without a solution
    # before, so that a position solved in a cycle has the grid it has alone
    canonical = REACH * expected_elastic_um(case) * 1e-3 + REACH_FLOOR * p.m
    spacing = GridSpacing(load, E_star, model.level.per_b, GRID_FLOOR * p.m, canonical)
    facing = Facing(model.curve2, turn, case.beta, p.e)
    while True:
        # the deviations move a tooth's gap by at most their reach: the windows of the exact
        # pair's gaps reach that much further
        wins = [w for w in windows(model.samples, facing, tuple(teeth),
                                   [base * reach.get(t, 1.0)
                                    + 1e-3 * case.deviations.reach_um(t) for t in teeth], coarse)
                if w is not None]
        if wins:
            return tooth_grids(model.samples, wins, spacing, [w.tooth not in full for w in wins])
        # the first touch the clearance table gives is the sharp profile's: on a tip edge the
        # round stands that far back (µm at z1 = 8 and h1 0.9), so the reach widens
        if base > WIDEST_REACH * p.m:
            raise FegearError("no tooth comes within reach of gear 2: the pair does not mesh")
        base *= 4.0


def judged(case: SolveCase, state, trial: Trial, placement: GridPlacement, solved,
           predict: bool) -> Attempt:
    """The attempt that ``solved`` (a :class:`~.solver.RingAttempt`) is: settled, or with the
    trial to solve again from where the driver's rule at the solved rotation chooses a tooth
    without a grid, a grid carries pressure at an end, a probe carries any, or the rotation is
    not the one placed for (:mod:`.solver`)."""
    p, sol = case.params, solved.solution
    more, ends, touched = outside(case, state, solved)
    solved_um = p.arc_um(sol.rotation) - solved.first_um
    moved = abs(solved_um - trial.elastic_um) > PLACEMENT * max(abs(solved_um), 1e-3)
    if not predict and more <= set(trial.teeth) and not ends and not moved and not touched:
        return Attempt(solved, None)
    reach = dict(placement.reach)
    for t in ends:
        reach[t] = 2.0 * reach.get(t, 1.0)
    full = placement.full | touched | expected_teeth(state, p.arc_um(sol.rotation))
    again = Trial(tuple(sorted(set(trial.teeth) | more)), max(solved_um, 1e-6),
                  GridPlacement(frozenset(full), reach))
    why = ("probe grids first: " if predict else "") + (
        f"teeth {sorted(more - set(trial.teeth))}, ends {ends}, probes touched "
        f"{sorted(touched)}, elastic {solved_um:.3g} µm, expected {trial.elastic_um:.3g}")
    return Attempt(solved, again, why)


def outside(case: SolveCase, state, solved) -> tuple[set, list, set]:
    """What tells whether a solved contact (a :class:`~.solver.RingAttempt`) stays on its
    grids: the teeth the driver's rule pairs at its rotation, the grids' teeth that carry
    pressure at an end and the probes' that carry any."""
    contact, sol, grids = solved.contact, solved.solution, solved.grids
    paired = set(choose_teeth(state, case.params.arc_um(sol.rotation), case.extra_pairs))
    ends = [g.tooth for k, g in enumerate(grids)
            if sol.pressure[contact.block(k)][[0, -1]].max() > 0]
    touched = {g.tooth for k, g in enumerate(grids)
               if g.probe and sol.pressure[contact.block(k)].max() > 0}
    return paired, ends, touched

"""The one driver of a tooth-pair solve over rolling positions, whichever model solves a
position (the ring model in the product, the sector model as its peer in
:mod:`fegear.verify.sector`).

Torque T (N·m) acts on gear 1 counter-clockwise (the ``+`` direction of the clearance table);
gear 2's rim is held. The clearance states of all positions come from one table, and a design
whose gears overlap before any load is refused. At each position the teeth are chosen from the
clearance state and the expected loaded rotation (:func:`~.teeth.choose_teeth`): the previous
position's elastic rotation, or at the first the torque shared by :data:`SHARE_GUESS` teeth of
stiffness :data:`~.teeth.TOOTH_STIFFNESS`. The model then solves the contact on those teeth
and says whether the choice must change (a tooth outside the set would close at the solved
rotation, or what the model placed for the expected rotation does not fit the solved one); if
so it is solved again from the new choice, at most :data:`ATTEMPTS` times, and only the
settled attempt's stresses are recovered. A model supplies the pieces in
:class:`PositionModel`; the loop, the first guess, the stage timings and the progress live
here.

The loop is a chain of positions (:func:`chain`), each from the one before; what is done at a
position is the caller's :class:`AtPosition`: here a position placed and settled
(:func:`drive`) or several torques on one contact (:func:`drive_torques`), and a tolerance
class's samples solved on the exact pair's contact kept for them
(:mod:`.analyses.samples.solve`).

A cycle of :data:`CHAINED` positions or more is solved as two chains, its halves, each from a
first guess of its own, handed to the executor the caller gives (``executor``: one chain here
and one in parallel where it has a worker to spare, else one after the other here). The numbers
are the same either way: a chain starts from its own first guess wherever it is solved.

A position can be solved at several torques at once (:func:`drive_torques`, a load spectrum's
levels): the heaviest of a family of torques is placed and settled as above, and the lighter
ones are solved on its contact (:meth:`SharesContacts.again`), where the model allows it.
"""

from __future__ import annotations

import logging
import math
from collections import OrderedDict
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import Protocol

from .. import progress
from ..errors import ContactError, FegearError
from ..fe import blas_threads, keep_freed_memory
from ..geometry import Gear1Profile, ToothContact, gear1_profile, moved_clearances, pitch_phase
from ..running import SERIAL, Executor
from ..timing import clocked, timed
from .case import PairSolution, SolveCase, in_given_order, phase_major, revolution_positions
from .teeth import TOOTH_STIFFNESS, choose_teeth, refuse_closed, refuse_interference

log = logging.getLogger(__name__)

SHARE_GUESS = 3.0    # teeth assumed to share the load before the first position is solved
ATTEMPTS = 5         # solves of one position, each from the last one's choice of teeth
#: the angles a gear-2 pitch at which the deviations' backlash is checked over a whole turn of
#: gear 1 before fewer positions are solved
TURN_CHECK = 4
CHAINED = 16         # positions from which a cycle is solved as two chains (a chain's first
                     # position costs about one position more than it would following another)
#: a position's contact placed for one torque serves the torques down to this fraction of it
#: (:func:`drive_torques`): the grids' spacing follows the Hertz half-width, which goes with the
#: load's square root, so theirs is at most twice the spacing of grids of their own
SHARED = 0.25


@dataclass(frozen=True)
class Trial:
    """What one attempt at a position solves from: the paired teeth, the elastic part of the
    rotation it expects (µm of arc at r0) and what the model placed for it before (``own``,
    the model's own record: None at a position's first attempt)."""

    teeth: tuple[int, ...]
    elastic_um: float
    own: object = None


@dataclass(frozen=True)
class Attempt:
    """An attempt's outcome: the model's record of the solved contact (``solved``), the
    trial to solve again from (None: settled) and why (for the log)."""

    solved: object
    again: Trial | None
    why: str = ""


class PositionModel(Protocol):
    """How a tooth-pair model solves one position; the driver does the rest. Each method's
    stages are timed (:func:`~fegear.timing.timed`) on the driver's clocks."""

    def build(self, case: SolveCase, profile: Gear1Profile,
              states: Callable[[], list]) -> None:
        """Everything the positions share (meshes, factors, condensed responses); ``states()``
        gives the positions' clearance states ((β, state) pairs) to a build that needs them
        (the driver may find them meanwhile)."""

    def attempt(self, case: SolveCase, state, trial: Trial,
                near: PairSolution | None) -> Attempt:
        """Solve the contact at ``case.beta`` on ``trial``'s teeth; ``near``: the solution
        of the position before, to start from."""

    def finish(self, case: SolveCase, state, attempt: Attempt) -> PairSolution:
        """Stresses and per-tooth results of a settled attempt."""


class SharesContacts(PositionModel, Protocol):
    """A position model that solves a position again under another torque on the contact an
    attempt settled on there (:func:`drive_torques`)."""

    def again(self, case: SolveCase, state, attempt: Attempt) -> PairSolution | None:
        """``case``, the position ``attempt`` settled at under a lighter torque, solved on
        that attempt's contact, stresses and all; None where that contact does not hold it."""


class AtPosition(Protocol):
    """What a chain does at each position (:func:`chain`): how the position's contact is found
    and kept, and what of it the chain gives."""

    def __call__(self, k: int, case: SolveCase, state, near: tuple | None) -> tuple:
        """Position ``k`` of the chain's states: ``case`` at its rolling angle, its clearance
        ``state``; ``near``: what the position before gave (None at a chain's first), its
        first entry the solution to start from."""


def _unsettled(case: SolveCase, trial: Trial, err: Exception) -> str:
    """Why the contact did not settle, with the input that changes it: how far the load had
    turned gear 1 past its first touch at the attempt before, against what the teeth's
    stiffness gives (:func:`expected_elastic_um` without a solution before)."""
    where = (f"the contact did not settle under --torque {case.torque:g} N·m at β "
             f"{math.degrees(case.beta):.4g}° ({err})")
    expected_um = expected_elastic_um(case)
    if trial.elastic_um <= 2.0 * expected_um:
        return where
    return (f"{where}: gear 1 had turned {trial.elastic_um:.3g} µm past its first touch, "
            f"{trial.elastic_um / expected_um:.2g} times the {expected_um:.3g} µm expected at "
            "their stiffness: a load far past what these teeth carry; lower --torque")


def expected_elastic_um(case: SolveCase, near: PairSolution | None = None) -> float:
    """The elastic part of gear 1's rotation (µm of arc at r0) to place the first attempt at:
    ``near``'s where it has one (a brief solution's first touch is NaN), else the torque on
    :data:`SHARE_GUESS` teeth of stiffness
    :data:`~.teeth.TOOTH_STIFFNESS` per face width."""
    p = case.params
    if near is not None:
        elastic = p.arc_um(near.rotation - near.first_touch)
        if math.isfinite(elastic):   # a solution read without its first touch has none
            return elastic
    return case.torque_Nmm / p.r0 / (case.thickness * TOOTH_STIFFNESS) / SHARE_GUESS


def first_teeth(case: SolveCase, state, elastic_um: float) -> tuple[int, ...]:
    """The teeth a rotation of ``elastic_um`` past the first touch can close at ``state``,
    with the case's extra pairs."""
    return choose_teeth(state, state.closest(+1).plus_um + elastic_um, case.extra_pairs)


def drive(case: SolveCase, betas, solver: PositionModel,
          profile: Gear1Profile | None = None, executor: Executor = SERIAL,
          handed: Callable[[range, list], list] | None = None) -> tuple[PairSolution, ...]:
    """Solve ``case`` at each rolling angle of ``betas`` (rad) with ``solver``; a cycle's
    chains on ``executor`` (module docstring). Each solution's times are its own stages, the
    first's with the one-off ones (the clearance states, the model's build). BLAS runs on one
    thread meanwhile (:data:`~fegear.fe.BLAS_THREADS`); the process's allocator keeps the
    memory a solve frees (:func:`~fegear.fe.keep_freed_memory`). ``handed(indices,
    solutions)``: what of a chain's solutions (at those indices of ``betas``) comes back, made
    in the process that solved them (where the caller reads only some positions' details)."""
    def one(k: int, at: SolveCase, state, near: tuple | None) -> tuple[PairSolution]:
        return (_clocked(solve_position, at, state, solver, near and near[0]),)

    def run(states, span) -> list:
        got = chain(case, states, span, one)
        return got if handed is None else [(sol,) for sol in handed(span, [g[0] for g in got])]

    return tuple(sols[0] for sols in _chains(case, betas, solver, profile, executor, run))


def drive_along(case: SolveCase, betas, solver: PositionModel, also,
                executor: Executor = SERIAL) -> tuple[tuple[PairSolution, object], ...]:
    """:func:`drive`, with ``also(case, state, solution)`` done at each position as soon as it
    is solved, in the process that solved it (where what the solver kept there lives: a
    contact to solve across the face on): (solution, what ``also`` gave) a position, in the
    order of ``betas``."""
    def one(k: int, at: SolveCase, state, near: tuple | None) -> tuple:
        sol = _clocked(solve_position, at, state, solver, near and near[0])
        return sol, also(at, state, sol)

    return tuple(_chains(case, betas, solver, None, executor,
                         lambda states, span: chain(case, states, span, one)))


def drive_torques(case: SolveCase, betas, torques, solver: SharesContacts,
                  executor: Executor = SERIAL) -> list[tuple[PairSolution, ...]]:
    """``case`` at each torque of ``torques`` (N·m) and each rolling angle of ``betas``, as
    :func:`drive` solves one torque: the solutions by torque, each in the order of ``betas``.
    At each position the torques go by families (:func:`families`): the heaviest of a family
    is placed and settled from its own solution at the position before, and the others are
    solved on the contact it settled on (:meth:`SharesContacts.again`: the same grids and
    influence matrix, a contact solve and the stresses each), or, where that contact does not
    hold one, settled from its own solution before as the heaviest is. A lighter torque's
    contact lies within a heavier one's at the same place, on grids as fine as its own or up
    to twice as coarse (:data:`SHARED`)."""
    groups = families(torques)

    def each(k: int, at: SolveCase, state, near: tuple | None) -> tuple[PairSolution, ...]:
        out: list = [None] * len(torques)
        for family in groups:
            head = replace(at, torque=torques[family[0]])
            attempt, out[family[0]] = _clocked(_settled, head, state, solver,
                                               near and near[family[0]])
            for k in family[1:]:
                out[k] = _clocked(_lighter, replace(at, torque=torques[k]), state, solver,
                                  attempt, near and near[k])
        return tuple(out)

    sols = _chains(case, betas, solver, None, executor,
                   lambda states, span: chain(case, states, span, each))
    return [tuple(at[k] for at in sols) for k in range(len(torques))]


def positions_of(solver: PositionModel, revolution: bool = False):
    """How a job solves its positions with ``solver``: ``solve(case, betas, executor)``, a
    revolution (``revolution``) phase by phase (:func:`~.case.phase_major`), the solutions in
    the order of ``betas``, a revolution's with details only where read after the chains (the
    solver's peaks, :meth:`~.ring.solver.RingSolver.read_later`, and each pitch's largest
    gear-1 root stress, its files' series): about a tenth at 24 positions a pitch."""

    def solve(case: SolveCase, betas, executor: Executor):
        order = phase_major(len(betas), case.params.z1) if revolution else range(len(betas))
        per = len(betas) // case.params.z1

        def handed(span, sols: list) -> list:
            pitches: dict[int, list[int]] = {}
            for i, k in enumerate(span):
                pitches.setdefault(order[k] // per, []).append(i)
            keep = solver.read_later(sols) | {max(group, key=lambda i: sols[i].root_stress[0])
                                              for group in pitches.values()}
            return [s if i in keep else replace(s, detail=None) for i, s in enumerate(sols)]

        sols = drive(case, [betas[k] for k in order], solver, executor=executor,
                     handed=handed if revolution else None)
        return in_given_order(order, sols)

    return solve


def families(torques) -> list[list[int]]:
    """The torques (their indices) by the position's contact they are solved on
    (:func:`drive_torques`): heaviest first, each family's first its heaviest and the others
    down to :data:`SHARED` of it."""
    order = sorted(range(len(torques)), key=lambda k: -torques[k])
    out: list[list[int]] = []
    for k in order:
        if out and torques[k] >= SHARED * torques[out[-1][0]]:
            out[-1].append(k)
        else:
            out.append([k])
    return out


def _chains(case: SolveCase, betas, solver: PositionModel, profile: Gear1Profile | None,
            executor: Executor, run) -> list[tuple[PairSolution, ...]]:
    """The driver's loop (:func:`drive`): a chain or two, each what ``run(states, span)``
    gives (:func:`chain` over the ``span`` of the positions' ``states`` with the caller's
    :class:`AtPosition`, and what of it comes back)."""
    keep_freed_memory()
    with blas_threads(), clocked() as once:
        profile = profile if profile is not None else gear1_profile(case.params)
        states = Clearances(case, profile, betas, executor)
        solver.build(case, profile, states.get)
        states = states.get()
        cut = len(states) // 2 if len(states) >= CHAINED else len(states)
        spans = [range(cut), range(cut, len(states))] if cut < len(states) else [range(cut)]
        chains = executor.map(lambda span: run(states, span), spans)
    sols = [sol for done in chains for sol in done]
    first = sols[0][0]
    sols[0] = (replace(first, timings_s={**once.stages, **first.timings_s}), *sols[0][1:])
    return sols


#: the exact pair's clearance states found last, by (pair, rolling angles): they depend on the
#: geometry alone, so the levels of a load spectrum or the torques of a study find them here
_FOUND: OrderedDict = OrderedDict()
KEEP_FOUND = 4


class Clearances:
    """The clearance states of every position ((β, state) pairs, the + torque's side, one
    search), a long cycle's found on the executor while the model is built, each tooth's moved
    by the case's deviations; a pair that interferes before any load, or that its deviations
    close, is refused when they are first read (:meth:`get`). ``find``: the pair's clearance
    search (:meth:`~fegear.geometry.ToothContact.states`), for other angles."""

    def __init__(self, case: SolveCase, profile: Gear1Profile, betas,
                 executor: Executor = SERIAL) -> None:
        self._betas, self._case = tuple(betas), case
        self.find = ToothContact(case.params, profile).states
        self._key = (case.params, self._betas)
        self._task = executor.submit(self.find, self._betas, None, True, (+1,)) \
            if len(self._betas) >= CHAINED and self._key not in _FOUND else None
        self._states: list | None = None

    def get(self) -> list:
        if self._states is None:
            with timed("clearance"):
                found = _FOUND.pop(self._key, None)
                if found is None:
                    found = self._task.result() if self._task is not None else \
                        self.find(self._betas, directions=(+1,))
                _FOUND[self._key] = found
                while len(_FOUND) > KEEP_FOUND:
                    _FOUND.popitem(last=False)
                self._states = list(zip(self._betas, found))
                refuse_interference(self._states)
                if self._case.deviations:
                    self._states = self._deviated()
        return self._states

    def _deviated(self) -> list:
        """The states with each tooth's clearance moved by the case's deviations, once the
        deviations are known to leave the pair its backlash over a whole turn of gear 1: at
        these positions, and where they are fewer than a turn, at :data:`TURN_CHECK` angles
        a pitch over one (a pair that jams anywhere cannot be turned to any position)."""
        dev, params = self._case.deviations, self._case.params
        states = list(zip(self._betas, moved_clearances(dev, params, [st for _, st in
                                                                      self._states])))
        self._refuse_closed(states)
        if len({pitch_phase(b, params.z2)[1] for b in self._betas}) < params.z1:
            turn = revolution_positions(self._betas[0], TURN_CHECK, params.z1, params.z2)
            self._refuse_closed(list(zip(turn, moved_clearances(
                dev, params, self.find(turn, directions=(+1,))))))
        return states

    def _refuse_closed(self, states) -> None:
        """Where a tooth of ``states`` ((β, deviated state) pairs) stands into its mate, the
        coast side found and moved too, for the check that the deviations leave the pair its
        backlash (:func:`~.teeth.refuse_closed`)."""
        behind = [(b, st) for b, st in states if st.closest(+1).plus_um < 0]
        if behind:
            dev, params = self._case.deviations, self._case.params
            coast = moved_clearances(dev, params, self.find([b for b, _ in behind],
                                                             directions=(-1,)), -1)
            refuse_closed([(b, st, back) for (b, st), back in zip(behind, coast)], dev)


def chain(case: SolveCase, states, span, position: AtPosition, label: str = "contact"
          ) -> list[tuple]:
    """What ``position`` gives at each position ``span`` (indices, in order) of ``states``
    ((β, clearance state) pairs), each from what the one before gave, the first from its own
    first guess; ``label``: what the progress names at each."""
    sols: list[tuple] = []
    for k in span:
        beta, state = states[k]
        progress.stage(f"{label} at β {math.degrees(beta):.3g}°"
                       + (f" ({k + 1} of {len(states)})" if len(states) > 1 else ""))
        sols.append(position(k, replace(case, beta=beta), state, sols[-1] if sols else None))
    return sols


def _clocked(solve, *args):
    """``solve(*args)``'s solution with the stages it took as its times; where it gives an
    attempt and its solution, the two, the solution so timed."""
    with clocked() as clock:
        got = solve(*args)
    if isinstance(got, tuple):
        return (*got[:-1], replace(got[-1], timings_s=dict(clock.stages)))
    return replace(got, timings_s=dict(clock.stages))


def solve_position(case: SolveCase, state, solver: PositionModel,
                   near: PairSolution | None) -> PairSolution:
    """One position: attempts from the first guess until the model settles, then its
    stresses."""
    return _settled(case, state, solver, near)[1]


def _lighter(case: SolveCase, state, solver: SharesContacts, attempt: Attempt,
             near: PairSolution | None) -> PairSolution:
    """``case`` solved on the contact ``attempt`` settled on at a heavier torque, or, where
    that contact does not hold it, settled from ``near`` as any position."""
    return solver.again(case, state, attempt) or solve_position(case, state, solver, near)


def _settled(case: SolveCase, state, solver: PositionModel, near: PairSolution | None
             ) -> tuple[Attempt, PairSolution]:
    """One position's settled attempt (:func:`solve_position`) and its solution."""
    elastic = expected_elastic_um(case, near)
    trial = Trial(first_teeth(case, state, elastic), elastic)
    for _ in range(ATTEMPTS):
        try:
            attempt = solver.attempt(case, state, trial, near)
        except ContactError as err:
            raise ContactError(_unsettled(case, trial, err)) from None
        if attempt.again is None:
            return attempt, solver.finish(case, state, attempt)
        log.info("β %.6f: solving again (%s)", case.beta, attempt.why)
        trial = attempt.again
    raise FegearError(f"the paired teeth did not settle in {ATTEMPTS} attempts at "
                      f"β {math.degrees(case.beta):.4g}° ({attempt.why})")

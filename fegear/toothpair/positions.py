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

A cycle of :data:`CHAINED` positions or more is solved as two chains, its halves, each from a
first guess of its own. With ``beside`` (a second core free) the second chain is solved in a
forked copy of this process (:class:`~fegear.workers.Forked`) while this one solves the first
(it forms the unit responses the build did not, and leaves its solutions in memory for this
one to read); and, where the model's build does not read the clearance states, they are found
in another fork while this process builds the model (an interference is then refused after
the build). The build itself may leave work beside (the ring model, gear 1's responses), which
the model takes in before a chain is forked (:meth:`PositionModel.settle`).
Without it the chains run one after the other. The numbers are the same either way, to
rounding: a chain starts from its own first guess, whichever process solves it (the unit
responses it forms, formed there in other batches, differ in the last bits).
"""

from __future__ import annotations

import logging
import math
import time
from collections import Counter
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import Protocol

from .. import progress
from ..errors import ContactError, FegearError
from ..fe import blas_threads, keep_freed_memory
from ..geometry import Gear1Profile, ToothContact, gear1_profile
from .case import PairSolution, SolveCase
from .teeth import TOOTH_STIFFNESS, choose_teeth, refuse_interference

log = logging.getLogger(__name__)

SHARE_GUESS = 3.0    # teeth assumed to share the load before the first position is solved
ATTEMPTS = 5         # solves of one position, each from the last one's choice of teeth
CHAINED = 16         # positions from which a cycle is solved as two chains (a chain's first
                     # position costs about one position more than it would following another;
                     # the baseline's 24 positions: 6.1 s one chain after the other, 4.4-4.5 s
                     # side by side)


@dataclass(frozen=True)
class Trial:
    """What one attempt at a position solves from: the paired teeth, the elastic part of the
    rotation it expects (µm of arc at r0) and the model's own placement data (``own``: the
    ring model's fine grids and reach factors, say)."""

    teeth: tuple[int, ...]
    elastic_um: float
    own: dict = field(default_factory=dict)


@dataclass(frozen=True)
class Attempt:
    """An attempt's outcome: the model's record of the solved contact, the trial to solve
    again from (None: settled), why (for the log) and the stage timings (s)."""

    result: object
    again: Trial | None
    why: str = ""
    timings_s: dict = field(default_factory=dict)


class PositionModel(Protocol):
    """How a tooth-pair model solves one position; the driver does the rest."""

    #: whether :meth:`build` reads the clearance states (the sector model's scene does, the
    #: ring model's templates do not: for it a cycle's states may be found beside the build)
    reads_states: bool

    def build(self, case: SolveCase, profile: Gear1Profile, states: list | None,
              beside: bool = False) -> None:
        """Everything the positions share (meshes, factors, condensed responses), for the
        clearance states ``states`` ((β, state) pairs; None where :attr:`reads_states` is
        false and they are found beside); timings in :attr:`timings_s`. ``beside``: a second
        core is free meanwhile for part of it (:meth:`settle` takes that in before this
        process forks)."""

    @property
    def timings_s(self) -> dict:
        """The one-off stages' timings (s) of :meth:`build`."""

    def settle(self) -> dict:
        """What :meth:`build` left running beside, taken in: the driver calls it before it
        forks (a forked copy must not read it). The time it took, by stage."""

    def attempt(self, case: SolveCase, state, trial: Trial,
                near: PairSolution | None) -> Attempt:
        """Solve the contact at ``case.beta`` on ``trial``'s teeth; ``near``: the solution
        of the position before, to start from."""

    def finish(self, case: SolveCase, state, attempt: Attempt) -> PairSolution:
        """Stresses and per-tooth results of a settled attempt (timings in the solution)."""

    def prepare(self, sols: list[PairSolution], busy: Callable[[], bool]) -> None:
        """While ``busy()`` (a cycle's other chain still runs beside): what :meth:`complete`
        will most likely need, from the positions ``sols`` solved here, done ahead (the same
        numbers as done there)."""

    def complete(self, sols: tuple[PairSolution, ...], beside: bool = False
                 ) -> tuple[PairSolution, ...]:
        """The solutions of all positions, with what the model leaves until the cycle is
        known (the ring model's submodels where the cycle peaks); ``beside``: a second core
        is free for part of that work."""

    def detach(self, sol: PairSolution) -> PairSolution:
        """``sol`` as it crosses from a chain solved beside (:func:`drive`): without what
        :meth:`attach` gives back (the model)."""

    def attach(self, sol: PairSolution) -> PairSolution:
        """A :meth:`detach` ed solution joined to this model again."""


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
    ``near``'s, else the torque on :data:`SHARE_GUESS` teeth of stiffness
    :data:`~.teeth.TOOTH_STIFFNESS` per face width."""
    p = case.params
    if near is not None:
        return p.arc_um(near.rotation - near.first_touch)
    return case.torque * 1e3 / p.r0 / (case.thickness * TOOTH_STIFFNESS) / SHARE_GUESS


def first_teeth(case: SolveCase, state, elastic_um: float) -> tuple[int, ...]:
    """The teeth a rotation of ``elastic_um`` past the first touch can close at ``state``,
    with the case's extra pairs."""
    return choose_teeth(state, state.closest(+1).plus_um + elastic_um, case.extra_pairs)


def drive(case: SolveCase, betas, solver: PositionModel,
          profile: Gear1Profile | None = None, beside: bool = False,
          ahead: Callable[[list[PairSolution]], None] | None = None
          ) -> tuple[PairSolution, ...]:
    """Solve ``case`` at each rolling angle of ``betas`` (rad) with ``solver``; the first
    position carries the one-off stages' timings. BLAS runs on one thread meanwhile
    (:data:`~fegear.fe.BLAS_THREADS`). ``beside`` (a second core free): a cycle's second
    chain is solved in a forked process (module docstring); should that fail in any way, it
    is solved here. ``ahead``: called with every position solved, before the model
    completes them (:meth:`PositionModel.complete`), to start beside what needs only them.
    The process's allocator keeps the memory a solve frees
    (:func:`~fegear.fe.keep_freed_memory`)."""
    keep_freed_memory()
    with blas_threads():
        return _drive(case, betas, solver, profile, beside, ahead)


def _drive(case: SolveCase, betas, solver: PositionModel, profile: Gear1Profile | None,
           beside: bool, ahead) -> tuple[PairSolution, ...]:
    t0 = time.perf_counter()
    profile = profile if profile is not None else gear1_profile(case.params)
    tca = ToothContact(case.params, profile)
    chained = len(betas) >= CHAINED
    if beside:
        from ..workers import Forked

    def clearances():   # the + torque's side, every position in one search
        return tca.states(betas, directions=(+1,))

    found = states = None
    if beside and chained and not solver.reads_states:
        found = Forked(clearances)     # while the model is built here
    else:
        states = list(zip(betas, clearances()))
        refuse_interference(states)
    t_tca = time.perf_counter() - t0
    try:
        solver.build(case, profile, states, beside)
        if states is None:
            t0 = time.perf_counter()
            got = found.result()
            states = list(zip(betas, got if got is not None else clearances()))
            refuse_interference(states)
            t_tca += time.perf_counter() - t0
    finally:
        if found is not None:
            found.stop()
    cut = len(states) // 2 if chained else len(states)
    other, waited = None, {}
    if beside and cut < len(states):
        waited = solver.settle()
        other = Forked(lambda: [solver.detach(s) for s in _chain(
            case, states, range(cut, len(states)), solver, announce=False)])
    try:
        sols = _chain(case, states, range(cut), solver)
        if cut < len(states):
            if other is not None:   # the wait for the other chain, used
                solver.prepare(sols, other.running)
            got = other.result() if other is not None else None
            if got is None:
                sols += _chain(case, states, range(cut, len(states)), solver)
            else:
                for k, sol in enumerate(got, start=cut):
                    _announce(states, k)
                    sols.append(solver.attach(sol))
    finally:
        if other is not None:
            other.stop()
    # the first position carries the one-off stages, and the wait for what was built beside
    first = Counter(sols[0].timings_s)
    first.update(waited)
    sols[0] = replace(sols[0], timings_s={**solver.timings_s, "clearance": t_tca, **first})
    if ahead is not None:
        ahead(sols)
    # the second core shares the completion unless what ``ahead`` started holds it
    return solver.complete(tuple(sols), beside=beside and ahead is None)


def _announce(states, k: int) -> None:
    beta = states[k][0]
    progress.stage(f"contact at β {math.degrees(beta):.3g}°"
                   + (f" ({k + 1} of {len(states)})" if len(states) > 1 else ""))


def _chain(case: SolveCase, states, span: range, solver: PositionModel,
           announce: bool = True) -> list[PairSolution]:
    """The positions ``span`` of ``states`` ((β, clearance state) pairs), each from the one
    before, the first from the first guess; ``announce``: their progress stages."""
    sols: list[PairSolution] = []
    for k in span:
        beta, state = states[k]
        if announce:
            _announce(states, k)
        at = replace(case, beta=beta)
        near = sols[-1] if sols else None
        elastic = expected_elastic_um(at, near)
        trial = Trial(first_teeth(at, state, elastic), elastic)
        times: Counter = Counter()
        for _ in range(ATTEMPTS):
            try:
                attempt = solver.attempt(at, state, trial, near)
            except ContactError as err:
                raise ContactError(_unsettled(at, trial, err)) from None
            times.update(attempt.timings_s)
            if attempt.again is None:
                break
            log.info("β %.6f: solving again (%s)", beta, attempt.why)
            trial = attempt.again
        else:
            raise FegearError(f"the paired teeth did not settle in {ATTEMPTS} attempts at "
                              f"β {math.degrees(beta):.4g}° ({attempt.why})")
        sol = solver.finish(at, state, attempt)
        sols.append(replace(sol, timings_s={**times, **sol.timings_s}))
    return sols

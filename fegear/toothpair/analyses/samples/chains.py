"""How a tolerance class's samples are run (:mod:`.solve`): the positions split into chains
of the driver's (:func:`~.positions.chain`), each every other position with every sample
there (one position: a share of the samples each), on the executor the caller gives, and the
exact pair's solutions at the positions from them (or, where the chains run elsewhere,
solved here meanwhile); and when a run may end early (:class:`Enough`)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from ....running import Executor
from ...case import PairSolution, SolveCase
from ...positions import chain, solve_position
from ...ring.solver import RingSolver, SolverModes
from .states import States


class Enough:
    """What a class's run needs solved to answer its question: ``only`` its pairs of these (by
    sample; None: every one), the others' answer known already (a relief trial's pairs that
    kept a round off at a smaller relief); and when it may end before those are solved
    everywhere: once more of its pairs that turn than ``share`` of them show what ``shows``
    finds in a reading (what the run's ``read`` took of a solution), the answer is known (a
    relief trial fails where more pairs load a tip round than the quantile leaves, whatever
    the others do). Counted where the chains run: chains in one process count together, a
    forked chain its own pairs (each count alone reaching the bound is enough for the
    whole). ``jams``: the answer is known before any pair is solved where more than this
    share of all the pairs jam (a design search's design that jams in more of its class's
    pairs than the quantile leaves: not buildable at that class)."""

    def __init__(self, shows: Callable[[object], bool], share: float,
                 only: frozenset[int] | None = None, jams: float | None = None) -> None:
        self.shows, self.share, self.only, self.jams = shows, share, only, jams
        self.turning = self.count = 0
        self.seen: set[int] = set()

    def among(self, turning: int, count: int) -> None:
        """The run's ``count`` pairs and those of them that turn (not jammed), solved or not:
        the count ``share`` is of."""
        self.turning, self.count = turning, count

    def wants(self, k: int) -> bool:
        """Whether pair ``k`` is to be solved (:attr:`only`)."""
        return self.only is None or k in self.only

    def saw(self, k: int, reading) -> None:
        """Pair ``k``'s ``reading`` at a position."""
        if self.shows(reading):
            self.seen.add(k)

    def failed(self, k: int) -> None:
        """Pair ``k`` failed at a position (its contact did not settle): left out of what the
        run reads, here nothing (a subclass that bounds a quantile drops it)."""

    @property
    def reached(self) -> bool:
        """Whether more pairs than the bound have shown it, or more jam than ``jams``."""
        jammed = self.count - self.turning
        return ((self.jams is not None and jammed > self.jams * self.count)
                or len(self.seen) > self.share * self.turning)


@dataclass(frozen=True)
class Chains:
    """How a class's chains are run (:func:`run_chains`): against ``states`` with
    ``solver`` on ``executor``, what each does at a position made by ``on_kept`` from its
    jobs by position (:class:`~.solve.OnKept`); ``parts``: how many chains a run."""

    states: States
    solver: RingSolver
    executor: Executor
    on_kept: Callable[[dict], object]

    @property
    def parts(self) -> int:
        return max(2, self.executor.workers)

    def __call__(self, work, exact: bool = True):
        """The chains of ``work`` ((positions, jobs by position) pairs): the exact pair's
        solutions by position and what each chain gave (:func:`run_chains`)."""
        return run_chains(self.states.case, self.states, self.solver,
                          [(span, self.on_kept(jobs)) for span, jobs in work],
                          self.executor, exact)


def parts_of(items, parts: int) -> list:
    """``items`` in ``parts`` runs as even as they come (fewer where there are fewer items)."""
    items = list(items)
    cuts = np.linspace(0, len(items), min(parts, max(len(items), 1)) + 1).round().astype(int)
    return [items[a:b] for a, b in zip(cuts[:-1], cuts[1:])]


def work_of(free: list[int], positions: list[int], pitches: int, parts: int
            ) -> list[tuple[list[int], dict[int, list[tuple[int, int]]]]]:
    """The chains: each one's positions (indices, of ``positions``) and by position the
    (sample, gear-2 pitches on) pairs it solves there, of the samples ``free`` (not jammed).
    Every ``parts``-th position a chain, every sample at each (a cycle's positions where more
    teeth carry, more points in contact and dearer solves, come in a run); one position: a
    share of the samples each."""
    if len(positions) > 1:
        jobs = every(free, positions, pitches)
        return [(positions[k::parts], jobs) for k in range(min(parts, len(positions)))]
    return [(positions, every(part, positions, pitches)) for part in parts_of(free, parts)]


def every(samples, positions: list[int], pitches: int) -> dict[int, list[tuple[int, int]]]:
    """By position (of ``positions``), the (sample, gear-2 pitches on) pairs solved there:
    every one of ``samples`` at each of the ``pitches``."""
    return {i: [(k, n) for k in samples for n in range(pitches)] for i in positions}


def run_chains(case: SolveCase, states: States, solver: RingSolver, work,
               executor: Executor, exact: bool = True
               ) -> tuple[dict[int, PairSolution], list[list[tuple]]]:
    """The chains of ``work`` ((positions, what is done at each) pairs) on ``executor``: the
    exact pair's solutions by position and what each chain gave at its positions
    (:meth:`~.solve.OnKept.__call__`). A chain's exact solutions refer to the model it solved
    them on: they come back from a process that shares this one's; elsewhere (a cluster) a
    chain gives plain data alone and the exact pair is solved here meanwhile, at every
    position (none where ``exact`` is False: solved before)."""
    if executor.shares_memory:
        chains = executor.map(lambda job: chain(case, states.loaded, *job, label="samples"),
                              work)
        return {i: got[0] for (span, _), done in zip(work, chains)
                for i, got in zip(span, done)}, chains
    tasks = [executor.submit(_plain, case, states.loaded, span, at) for span, at in work]
    nominal = _exact(case, states, solver) if exact else {}
    return nominal, [task.result() for task in tasks]


def _plain(case: SolveCase, loaded, span, at) -> list[tuple]:
    """A chain of the samples (:func:`~.positions.chain`) in another process: what it gave
    without the exact pair's solutions (plain data alone)."""
    return [(None, *got[1:]) for got in chain(case, loaded, span, at, label="samples")]


def _exact(case: SolveCase, states: States, solver: RingSolver) -> dict[int, PairSolution]:
    """The exact pair at the positions, one chain, on ``solver``'s model."""
    placed = RingSolver(solver.model, SolverModes(submodels="none"))

    def settled(k: int, at: SolveCase, state, near: tuple | None) -> tuple[PairSolution]:
        return (solve_position(at, state, placed, near and near[0]),)

    sols = chain(case, states.loaded, range(len(states.loaded)), settled)
    return {i: got[0] for i, got in enumerate(sols)}

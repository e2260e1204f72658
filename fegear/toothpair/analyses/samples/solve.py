"""A tolerance class's sampled gear pairs solved at a job's positions (docs/tolerance.md).

Every sample is the same pair with other deviations (:mod:`fegear.tolerance.sampling`), so it
is the same model with other rigid gaps: at each position the exact pair is solved first, then
its contact kept with grids on every tooth that any sample pairs there, each reaching as far as
the deviations of any pair that turns can move a tooth (:class:`~.ring.phases.Phases`; a pair
that jams is not solved), and
each sample is a contact solve on that contact, its stresses read with the other samples'
held there (:class:`~.ring.kept_batch.KeptBatch`: the same numbers as alone,
:meth:`~.ring.solver.RingSolver.on_kept`); one whose contact the kept grids do not hold is
placed and solved as a position of its own, after those held are read, and the contact kept
again with its teeth too.

Over a whole revolution, where a cycle has places to spare and only the headlines are read,
the pairs are screened (:mod:`.screen`): each solved at every pitch at a few of the places
first, then at every other position about those that came nearest its largest, then beside
the ones of those nearest it, and its row the largest of the positions solved.

A sample whose deviations take up the pair's backlash somewhere over a whole turn of gear 1
(:func:`~.teeth.closure`, checked at :data:`~.positions.TURN_CHECK` angles a pitch, as a
deviated solve checks it) cannot be turned: it is counted as jammed, with where, and carries no
stresses. A sample whose contact does not settle is counted as failed, with why: no sample
leaves the tables unseen.

Across the face (a job with a face: :mod:`.across`), each sample is solved besides on its
position's kept contact at the face's sections, with its own helix deviations and
misalignment, and the exact pair too: each one's stresses are its worst section's, with its
K_Hβ; a sample whose face takes up the backlash (:class:`~...face_room.FaceRoom`) is jammed.

The positions are the parallel work: two chains of the driver's (:mod:`.chains`), each every
other position with every sample (one position: half the samples each), on the executor the
caller gives; what a chain does at a position is this module's
(:class:`~.positions.AtPosition`: the exact pair's contact found, then kept for the samples).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from itertools import groupby

from ....errors import FegearError
from ....fe import Allowables, blas_threads, keep_freed_memory
from ....geometry import closing_points, gear1_profile, moved_clearances
from ....running import SERIAL, Executor
from ....tolerance import Draw
from ...case import PairSolution, SolveCase
from ...face import Face
from ...face_room import FaceRoom
from ...positions import solve_position
from ...ring.face_results import face_sections
from ...ring.kept_batch import KeptBatch
from ...ring.phases import Phases
from ...ring.readout import readout
from ...ring.solver import RingSolver, SolverModes
from ...teeth import choose_teeth
from .across import Across, across_of, worst_sections
from .chains import Chains, Enough, parts_of, work_of
from .rows import EXACT, LEFT_OUT, SKIPPED, STOPPED, brief_of, gathered, sample_row
from .screen import scout_places, screened
from .states import States, jammed

#: the samples a position holds on its kept contact before their stresses are read together
#: (:class:`~fegear.toothpair.ring.kept_batch.KeptBatch`): the products a sector take them as
#: columns; more only hold more contacts in memory
BATCH = 64


@dataclass(frozen=True)
class SampleCase:
    """A tolerance class's pairs to solve: the exact pair's ``case`` at the rolling angles
    ``betas`` (rad) and ``draw``'s samples, their safety factors against ``allowables``;
    ``pitches`` > 1: each sample at ``betas`` and at each of that many gear-2 pitches on (a
    revolution: z1), its worst over all of them, screened (``screen``, :mod:`.screen`: each
    at every pitch at a few places, then about where those came nearest its largest) where a
    cycle has places to spare and nothing but the headlines is read; ``face``: each solved
    across it too, with its own helix deviations and misalignment (``draw`` across the face),
    its worst section's.
    """

    case: SolveCase
    betas: Sequence[float]
    draw: Draw
    allowables: Allowables
    pitches: int = 1
    face: Face | None = None
    screen: bool = True


@dataclass(frozen=True)
class Sampled:
    """The exact pair's solutions at the positions (in order) and one row a sample: its
    deviations in brief, ``status`` ("solved", "jammed" or "failed", with ``why``), and where
    solved its largest headline stresses over the positions, each with its position, and
    the safety factors they give; ``readings``: by sample, what the caller's ``read`` took of
    its solution at each position (:func:`solve_samples`); ``across``: across the face, the
    exact pair's headlines at its worst sections and K_Hβ at the positions (in order);
    ``solved_per_pair``: a revolution screened, the positions solved a pair that turns (mean;
    None: every position)."""

    nominal: tuple[PairSolution, ...]
    rows: tuple[dict, ...]
    readings: dict = field(default_factory=dict)
    across: tuple[dict, ...] = ()
    solved_per_pair: float | None = None
    stopped: bool = False

    @property
    def turning(self) -> list[int]:
        """The samples solved at every position (neither jammed nor failed); in a run that
        ended early (``stopped``: :class:`~.chains.Enough`), those neither jammed nor failed
        where they were solved, and in one that left some out (:attr:`~.chains.Enough.only`)
        those too."""
        return [r["sample"] for r in self.rows if r["status"] not in ("jammed", "failed")]

    @property
    def jammed_share(self) -> float:
        """The share of the samples that jam."""
        return sum(r["status"] == "jammed" for r in self.rows) / len(self.rows)


def solve_samples(samples: SampleCase, solver: RingSolver, executor: Executor = SERIAL,
                  read: Callable[[PairSolution], object] | None = None,
                  enough: Enough | None = None) -> Sampled:
    """The exact pair and the class's samples (``samples``) solved with ``solver``, a ring
    solver that keeps a contact a position (:attr:`~.ring.solver.SolverModes.keep_phases`),
    its grids set here to reach as far as the deviations of the drawn pairs that turn move a
    tooth (module docstring), through the driver's chains (:func:`~.positions.chain`) on
    ``executor``; ``read``: what to keep of each sample's solution at each position beside
    its headlines (a relief search's tip-round loads, say), and ``enough``: when what it
    read answers the run's question before every pair is solved (:class:`~.chains.Enough`:
    the rest is not solved, and the rows say "stopped"). Across the face
    (``samples.face``), the grids reach as far as the samples' faces move a flank besides."""
    keep_freed_memory()
    case, count = samples.case, samples.draw.count
    with blas_threads():
        profile = gear1_profile(case.params)
        pairs = [samples.draw.pair(k) for k in range(count)]   # drawn once, here
        across = None if samples.face is None else across_of(case, samples.face, samples.draw)
        states = States(case, profile, tuple(samples.betas), _reach_um(pairs, across),
                        samples.pitches)
        jammed = _jams(states, pairs, across, executor)
        solver.reach(_reach_um([d for d, j in zip(pairs, jammed) if j is None], across))
        solver.build(case, profile, lambda: states.loaded)
        if not solver.modes.contact_only:   # the root zones' maps, before the chains fork
            for side in solver.model.gears:
                readout(side)
        free = [k for k in range(count) if jammed[k] is None]
        if enough is not None:
            enough.among(len(free), count)
            free = [k for k in free if enough.wants(k)]
        places = list(range(len(samples.betas)))
        scouts = (scout_places(len(places)) if samples.screen and samples.pitches > 1
                  and read is None and across is None else None)
        run = Chains(states, solver, executor, lambda jobs: OnKept(states, pairs, solver, jobs,
                                                                   read, across, enough))
        if scouts is None:
            nominal, chains = run(work_of(free, places, samples.pitches, run.parts))
            solved = None
        else:
            nominal, chains, solved = screened(run, free, scouts, samples.pitches)
    found, readings = gathered(chains)
    stopped = SKIPPED in found
    z = (case.params.z1, case.params.z2)
    rows = tuple(sample_row(k, brief_of(pairs[k], z, across and across.faces[k]), jammed[k],
                            found.get(k, []), samples.allowables,
                            _unfinished(enough, k, stopped))
                 for k in range(count))
    exact = tuple(head for _, head in sorted(found.get(EXACT, []), key=lambda g: g[0]))
    return Sampled(tuple(nominal[i] for i in range(len(samples.betas))), rows, readings,
                   exact, solved, stopped)


def _unfinished(enough: Enough | None, k: int, stopped: bool) -> tuple[str, str] | None:
    """Sample ``k``'s status and why where its run did not solve it everywhere: left out
    (``enough`` did not want it), or stopped (the run ended early); None where it did."""
    if enough is not None and not enough.wants(k):
        return "left out", LEFT_OUT
    return ("stopped", STOPPED) if stopped else None


def _reach_um(pairs: list, across: Across | None) -> float:
    """How far (µm) the deviations of ``pairs`` move a tooth at most, their faces a flank
    besides (``across``)."""
    return (max((d.widest_um() for d in pairs), default=0.0)
            + (across.reach_um if across is not None else 0.0))


def _jams(states: States, pairs: list, across: Across | None, executor: Executor) -> list:
    """Where each of ``pairs`` jams (None where it turns): in the plane
    (:func:`~.states.jammed`), or across the face with its own face
    (:meth:`~...face_room.FaceRoom.jammed`), in a share of the pairs a worker."""
    if across is None:
        def jams(k: int) -> str | None:
            return jammed(states, pairs[k])
    else:
        room = FaceRoom(states.case, states.turn, states.reach_um, across.face.sections)

        def jams(k: int) -> str | None:
            return room.jammed(pairs[k], across.faces[k])
    parts = parts_of(range(len(pairs)), max(2, executor.workers))
    return [j for part in executor.map(lambda ks: [jams(k) for k in ks], parts) for j in part]


def class_samples(job, allowables: Allowables, read=None, contact_only: bool = False,
                  executor: Executor = SERIAL, enough: Enough | None = None) -> Sampled:
    """A checked job's class (``job.draw``) solved at its positions (:func:`solve_samples`,
    ``read`` and ``enough`` as there) on a ring solver made for it: the stresses without
    submodels (across the job's face where it has one), or the contact alone
    (``contact_only``: a relief search's trial)."""
    solver = RingSolver(None, SolverModes(submodels="none", contact_only=contact_only,
                                         keep_phases=True))
    face = None if contact_only else job.face
    return solve_samples(class_case(job, allowables, face), solver, executor, read, enough)


def class_case(job, allowables: Allowables, face: Face | None) -> SampleCase:
    """A checked job's class (``job.draw``) to solve at its positions, across ``face`` where
    given: over a revolution (``job.revolution``), the first pitch's places at each of gear
    1's z1 pitches, so that each place keeps one contact for all of them."""
    pitches = job.case.params.z1 if job.revolution else 1
    return SampleCase(job.case, job.betas[:len(job.betas) // pitches], job.draw, allowables,
                      pitches, face)


@dataclass(frozen=True)
class OnKept:
    """What a chain of the samples does at a position (:class:`~.positions.AtPosition`):
    the exact pair is solved as any position, then its contact kept with grids on every tooth
    that the samples solved there pair (:func:`_paired`), each sample solved on it and held,
    their stresses read together (:class:`~.ring.kept_batch.KeptBatch`, :data:`BATCH` at a
    time), and the contact let go of; ``jobs``: by
    position, the samples solved there ((index into the drawn ``pairs``' deviations, gear-2
    pitches on) pairs). A solver received without its model (from another process) builds or
    finds one here. ``across``: the exact pair and each sample solved across the face too,
    on the same kept contact (their worst sections' headlines and K_Hβ, the exact pair's under
    :data:`~.rows.EXACT`); ``enough``: once it is reached, the pairs are solved no more
    (the exact pair still is), and the positions left say how many they skipped
    (:data:`~.rows.SKIPPED`)."""

    states: States
    pairs: list
    solver: RingSolver
    jobs: dict[int, list[tuple[int, int]]]
    read: Callable[[PairSolution], object] | None = None
    across: Across | None = None
    enough: Enough | None = None

    def __call__(self, i: int, at: SolveCase, state, near: tuple | None
                 ) -> tuple[PairSolution, dict[int, list], dict[int, list]]:
        """The exact pair's solution at position ``i`` and, by sample, each one's (β, headline)
        a pitch, or (β, why) where it failed, and what ``read`` took of each solution."""
        solver = self.solver
        if solver.model is None:
            solver.build(at, gear1_profile(at.params), lambda: self.states.loaded)
        placed = RingSolver(solver.model, SolverModes(submodels="none"))
        exact = solve_position(at, state, placed, near and near[0])
        if not self.jobs.get(i) and self.across is None:   # no sample here: no contact kept
            return exact, {}, {}
        if self._enough():
            return exact, {SKIPPED: [(at.beta, len(self.jobs[i]))]}, {}
        moved = self._moved(i, at.params)
        solver.widen(at, state, exact, _paired(at, exact, state, moved))
        found: dict[int, list] = {}
        took: dict[int, list] = {}
        if self.across is not None:
            found[EXACT] = [(at.beta, self._face(at, state, self.across.face))]
        batch = None if self.across is not None else KeptBatch(solver)
        held: list[tuple[int, float]] = []
        for j, (k, n) in enumerate(self.jobs[i]):
            if self._enough():
                found[SKIPPED] = [(at.beta, len(self.jobs[i]) - j)]
                break
            one = replace(at, beta=self.states.beta(i, n), deviations=self.pairs[k])
            try:
                if batch is not None and batch.add(one, moved[k, n]):
                    held.append((k, one.beta))
                    if len(held) == BATCH:
                        self._record(batch, held, found, took)
                    continue
                # the held ones first: placing this one widens the kept grids under them
                self._record(batch, held, found, took)
                sol = self._sample(one, moved[k, n], placed, exact, batch is None)
                head = sol.headline() if self.across is None else \
                    self._face(one, moved[k, n], self.across.faces[k])
            except FegearError as err:
                self._failed(found, k, one.beta, err)
                continue
            self._add(found, took, k, one.beta, head, sol)
        self._record(batch, held, found, took)
        solver.forget(at)
        return exact, found, took

    def _enough(self) -> bool:
        """Whether the run's question is answered (:attr:`enough`)."""
        return self.enough is not None and self.enough.reached

    def _face(self, one: SolveCase, state, face: Face) -> dict[str, float]:
        """``one`` (clearance ``state``) across ``face`` on the contact kept at its position:
        its worst sections' headlines and K_Hβ (:func:`~.across.worst_sections`)."""
        sections = face_sections(self.solver.model, self.solver.phases, one, state, face,
                                 self.across.coupling)
        if sections is None:
            raise FegearError("no contact kept where the sample is solved across the face")
        return worst_sections(sections)

    def _moved(self, i: int, params) -> dict:
        """The clearance states at position i of the samples ``jobs[i]`` names, by (sample,
        gear-2 pitches on): a sample's pitches moved at once, from the closing points of every
        pitch solved here found once (:meth:`~fegear.geometry.Closing.found`)."""
        pitches = sorted({n for _, n in self.jobs[i]})
        states = [self.states.at(i, n) for n in pitches]
        every = closing_points(params, states).found(params)
        where = {n: j for j, n in enumerate(pitches)}
        moved = {}
        for k, run in groupby(self.jobs[i], key=lambda job: job[0]):
            ns = sorted(n for _, n in run)
            at = [where[n] for n in ns]
            moved.update(zip(((k, n) for n in ns), moved_clearances(
                self.pairs[k], params, [states[j] for j in at], closing=every.of_states(at))))
        return moved

    def _record(self, batch: KeptBatch | None, held: list, found: dict, took: dict) -> None:
        """The ``held`` samples' (sample, β) records, finished together (``batch``), into
        ``found`` and ``took`` as :meth:`__call__` gives them; none held after."""
        if not held:
            return
        try:
            sols: list = batch.finish()
        except FegearError as err:
            sols = [err] * len(held)
        for (k, beta), sol in zip(held, sols, strict=True):
            if isinstance(sol, FegearError):
                self._failed(found, k, beta, sol)
                continue
            self._add(found, took, k, beta, sol.headline(), sol)
        held.clear()

    def _failed(self, found: dict, k: int, beta: float, err: FegearError) -> None:
        """Sample ``k`` failed at ``beta`` (``err`` says why): into ``found``, and
        :attr:`enough` told (a failed pair is left out of a class's quantiles)."""
        found.setdefault(k, []).append((beta, str(err)))
        if self.enough is not None:
            self.enough.failed(k)

    def _add(self, found: dict, took: dict, k: int, beta: float, head: dict,
             sol: PairSolution) -> None:
        """Sample ``k``'s headline ``head`` at ``beta`` into ``found``, and what ``read`` takes of
        its solution into ``took``."""
        found.setdefault(k, []).append((beta, head))
        if self.read is not None:
            took.setdefault(k, []).append(self.read(sol))
            if self.enough is not None:
                self.enough.saw(k, took[k][-1])

    def _sample(self, one: SolveCase, state, placed: RingSolver, exact: PairSolution,
                kept: bool = True) -> PairSolution:
        """A sample (``one``, its clearance ``state``) on the kept contact (``kept``: else
        known not to hold it), or where the kept grids miss it placed on its own (from
        ``exact``) and its teeth kept for those after it."""
        sol = self.solver.on_kept(one, state, brief=True) if kept else None
        if sol is None:
            sol = solve_position(one, state, placed,
                                 Phases.beside(self.solver.model, exact, one.beta))
            self.solver.widen(one, state, sol)
        return sol


#: a sample's teeth are those the driver's rule pairs at its first touch plus this many times
#: the exact pair's elastic rotation (a deviated pair carries its load on fewer teeth, which
#: turn gear 1 further)
ELASTIC_MARGIN = 1.5


def _paired(case: SolveCase, exact: PairSolution, state, moved: dict) -> set[int]:
    """The teeth, counted at pitch 0, that the samples (their clearance states ``moved``, by
    (sample, gear-2 pitches on)) pair: the driver's rule (:func:`~.teeth.choose_teeth`) at
    each one's first touch plus :data:`ELASTIC_MARGIN` times the exact pair's elastic
    rotation (µm of arc at r0); a tooth ``n`` pitches on is the one n after it at pitch 0."""
    elastic = case.params.arc_um(exact.rotation) - state.closest(+1).plus_um
    z1 = case.params.z1
    return {(t + n) % z1 for (_, n), m in moved.items() for t in choose_teeth(
        m, m.closest(+1).plus_um + ELASTIC_MARGIN * elastic, case.extra_pairs)}

"""The ring model's part of one rolling position, for the driver of
:mod:`fegear.toothpair.positions`.

Each chosen tooth gets a pressure grid over the stretch of its profile that the expected
rotation can close (:mod:`.placement`), and the contact is solved. Then the driver's rule at the
solved rotation must choose no tooth without a grid, no grid may carry pressure at its ends and
the rotation the grids were placed at must be the solved one within
:data:`~.placement.PLACEMENT` of the elastic part; otherwise the grids are placed again
(:meth:`RingSolver.attempt` returns the new trial). A settled position's stresses come from
the templates (:mod:`.stresses`); its contact submodels only where a cycle peaks
(:mod:`.peaks`).

The model (meshes, factors, responses to unit loads), built once per geometry and quality, serves
every torque and position (:class:`~.model.RingModel`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

from ... import progress
from ...errors import ContactError
from ...fe import projector
from ...geometry import Gear1Profile, Placed
from ...timing import note, timed
from ..case import ContactChecks, PairSolution, SolveCase
from ..positions import Attempt, Trial
from ..teeth import candidate_data
from .contact import RingContactSolution, solve_ring_contact
from .grid import ToothGrid
from .influence import ColumnRule, RingContact, assemble_contact
from .model import RingModel, keep_cached, ring_model
from .modes import WHOLE, SolverModes
from .peaks import peak_candidates, pictured, whole, with_peak_submodels
from .phases import Phases
from .placement import (
    CANDIDATES,
    GridPlacement,
    by_tooth,
    columns_before,
    expected_teeth,
    judged,
    loaded_before,
    outside,
    place_grids,
)
from .readout import brief_stresses
from .results import RingDetail, equilibrium_residuals, solved_rigid_gap, tooth_results
from .stresses import RingStresses, ring_stresses
from .tangent import tangent_stiffness
from .touch import touch_rotation

#: the one-off stages a solve reports: the model built (profile, mesh, assembly and
#: factorisation), read back from the model cache, or kept from an earlier solve
MODEL_STAGES = ("profile", "mesh", "assemble_factor", "cache", "model (kept)")


@dataclass(frozen=True)
class RingAttempt:
    """What an attempt solved (:attr:`~fegear.toothpair.positions.Attempt.solved`): the
    contact on its grids, its solution, the grids, the rigid rotation to the first touch
    (µm of arc at r0) and the teeth it paired (a paired tooth with nothing within reach of
    gear 2 has no grid; none recorded on a phase's kept contact)."""

    contact: RingContact
    solution: RingContactSolution
    grids: tuple[ToothGrid, ...]
    first_um: float
    teeth: tuple[int, ...] = ()


class RingSolver:
    """The ring model as a :class:`~fegear.toothpair.positions.PositionModel`: ``model``, a
    ring model built before, is kept if it fits the case; ``modes``: what it gives and keeps
    (:class:`SolverModes`)."""

    def __init__(self, model: RingModel | None = None, modes: SolverModes = WHOLE) -> None:
        self.model = model
        self.modes = modes
        self.phases = Phases() if modes.keep_phases else None

    def __getstate__(self) -> dict:
        """What another process receives: the settings and the kept grids' reach, without
        the model (its factors do not pickle, and it refers to this process's:
        :meth:`build` builds or finds one there) or the contacts kept for it."""
        state = dict(self.__dict__, model=None)
        if self.phases is not None:
            state["phases"] = Phases(self.phases.reach_um)
        return state

    def build(self, case: SolveCase, profile: Gear1Profile, states) -> None:
        # the same stages on every solve (zero where not run), so that a study's table has
        # the same columns whichever way its cases found their models
        note(dict.fromkeys(MODEL_STAGES, 0.0))
        with timed("model (kept)"):   # the stages of a model built or read back: their own
            if self.model is None or not self.model.fits(case):
                progress.stage("model: both gears meshed and condensed at quality "
                               f"{case.quality}")
                self.model = ring_model(case, profile)
        if not self.modes.contact_only:   # the stresses' projection, which every position shares
            with timed("assemble_factor"):
                for side in self.model.gears:
                    projector(side.body)

    def attempt(self, case: SolveCase, state, trial: Trial,
                near: PairSolution | None) -> Attempt:
        first_um = state.closest(+1).plus_um
        if self.phases is not None and near is not None:
            near = self.phases.beside(self.model, near, case.beta)
        if self.phases is not None and trial.own is None and (
                on := self._on_phase(case, state)) is not None:
            return on
        if self.phases is not None and near is not None and trial.own is None and not \
                self.phases.keeps(case.beta, case.params.z2):
            # a phase's first position after a solved one: its contact kept at once, about
            # the rotation of the one before (it turns little from a position to the next),
            # not first placed on grids of its own that the kept ones would replace; where
            # the kept grids do not hold it, placed as below
            with timed("assemble"):
                kept = self.phases.keep(self.model, case, state, trial, near.rotation)
            if kept is not None:
                return kept_attempt(kept, state)
        # without a solution before, the expected rotation is an estimate (20-50 % off): a
        # first solve on probe grids only finds the rotation to place the fine grids at
        predict = near is None and trial.own is None
        placement = trial.own or GridPlacement()
        if placement.full is None:
            placement = replace(placement, full=frozenset() if predict else frozenset(
                expected_teeth(state, first_um + trial.elastic_um)))
        coarse = None if near is None else {g.tooth: g.coarse for g in near.detail.contact.grids
                                            if g.coarse is not None}
        with timed("grids"):
            grids = place_grids(self.model, case, trial, placement, first_um, coarse)
        solved = self._contact(case, trial, grids, first_um, near)
        if solved is None:   # probe grids too coarse for this contact to settle: fine grids
            return Attempt(None, replace(trial, own=replace(placement, full=None)),
                           "probe grids did not settle")
        outcome = judged(case, state, trial, placement, solved, predict)
        if self.phases is not None and outcome.again is None:
            with timed("assemble"):
                kept = self.phases.keep(self.model, case, state, trial,
                                        solved.solution.rotation)
            if kept is not None:   # the position solved on its phase's contact
                return kept_attempt(kept, state)
        return outcome

    def on_kept(self, case: SolveCase, state, brief: bool = False) -> PairSolution | None:
        """``case`` (clearance ``state``) solved on the contact kept for its phase, stresses and
        all, and not kept for the positions after it: one of many deviation sets at a position
        solved before (a tolerance class's samples). ``brief``: the headline stresses and the
        teeth's loads and pressures only, without the first touch (NaN: no transmission
        error), the tangent stiffness, the equilibrium residuals, the teeth's Hertz values and
        half-plane references or an unloaded tooth's root stress on gear 2, which a sample's
        row does not read. None where no contact is kept there or its grids do not hold this
        one's."""
        kept = self.phases.solve(self.model, case, state, brief)
        return None if kept is None else self.record(case, state, kept_attempt(kept, state),
                                                        brief)[0]

    def again(self, case: SolveCase, state, attempt: Attempt) -> PairSolution | None:
        """``case``, the position ``attempt`` settled at (clearance ``state``) under a lighter
        torque, solved on that attempt's contact, stresses and all
        (:func:`~fegear.toothpair.positions.drive_torques`): its grids and influence matrix
        serve, the rigid gaps are those of this torque's rotation; with kept phases, on the
        contact kept for the position's phase (:meth:`_on_phase`). None where that contact
        does not hold it (the driver's rule pairs a tooth the attempt did not, a grid carries
        pressure at an end, a probe any) or its points cannot carry the torque."""
        if self.phases is not None:
            on = self._on_phase(case, state)
            return None if on is None else self.finish(case, state, on)
        solved = attempt.solved
        try:
            with timed("contact"):
                sol = solve_ring_contact(self.model, solved.contact, case.torque_Nmm,
                                         solved.solution.rotation,
                                         start=solved.solution.pressure > 0)
        except ContactError:
            return None
        if sol is None:
            return None
        again = replace(solved, solution=sol)
        paired, ends, touched = outside(case, state, again)
        if paired - set(solved.teeth) or ends or touched:
            return None
        return self.record(case, state, Attempt(again, None))[0]

    def _on_phase(self, case: SolveCase, state) -> Attempt | None:
        """``case`` settled on what the phases keep: a solution at a pitch before, renumbered,
        or a solve on the contact kept for its phase; None where neither holds it."""
        with timed("contact"):
            same = self.phases.repeat(self.model, case, state)
            if same is not None:
                return Attempt(same, None)
            kept = self.phases.solve(self.model, case, state)
        return None if kept is None else kept_attempt(kept, state)

    def reach(self, reach_um: float) -> None:
        """Keep the contacts from now on with grids reaching ``reach_um`` beyond the exact
        pair's at least: the most the deviation sets to be solved on them move a tooth
        (:meth:`~fegear.geometry.Deviations.widest_um`)."""
        self.phases.reach_um = reach_um

    def widen(self, case: SolveCase, state, sol: PairSolution, teeth=()) -> None:
        """Keep the contact of ``case``'s phase (again, where one is kept) with grids on the
        teeth ``sol`` paired, on the kept one's and on ``teeth``: the teeth that the deviation
        sets to be solved there pair, or that one the kept grids did not hold (:meth:`on_kept`)
        paired on grids of its own, so that the sets after it find theirs."""
        first_um = state.closest(+1).plus_um
        teeth = tuple(sorted({g.tooth for g in sol.detail.contact.grids} | set(teeth)))
        if set(teeth) <= self.phases.gridded(case.beta, case.params.z2):
            return   # the kept grids have them all
        trial = Trial(teeth, case.params.arc_um(sol.rotation) - first_um)
        with timed("assemble"):
            self.phases.keep(self.model, case, state, trial, sol.rotation, widen=True)

    def forget(self, case: SolveCase) -> None:
        """Let go of the contact kept for ``case``'s phase (:meth:`.phases.Phases.forget`)."""
        if self.phases is not None:
            self.phases.forget(case.beta, case.params.z2)

    def _contact(self, case: SolveCase, trial: Trial, grids: tuple[ToothGrid, ...],
                 first_um: float, near: PairSolution | None) -> RingAttempt | None:
        """The contact on ``grids`` under the torque; None where probe grids alone did not
        settle it. A's columns are formed first only where pressure can act: not the probes'
        (where one closes, the attempt is made again with that tooth's fine grid), and on the
        fine grids the points that overlap rigidly at the expected rotation, or nearly
        (:data:`~.placement.CANDIDATES`); in a cycle's later position, of those, the ones
        about where the position before carried pressure
        (:func:`~.placement.columns_before`). Where a point left out closes, the candidates',
        and then every column."""
        p = case.params
        predict = near is None and trial.own is None
        theta = p.turn_of(first_um + trial.elastic_um)
        within = None if predict else CANDIDATES * trial.elastic_um * 1e-3
        old = None if near is None else by_tooth(near.detail)
        start = None if old is None else loaded_before(old, grids)
        columns = None if old is None else columns_before(old, grids)
        tries = [ColumnRule(False, within, columns)] if columns is not None else []
        tries += [ColumnRule(False, within), ColumnRule()]
        placed = Placed(case.deviations, p, case.beta) if case.deviations else None
        for rule in tries:
            with timed("assemble"):
                contact = assemble_contact(self.model, grids, case.beta,
                                           p.ratio * case.beta + theta, rule, placed)
            try:
                with timed("contact"):
                    # the rotation's linearisations start at the expected rotation after a
                    # solved position (its elastic part off by a few per cent: three, not
                    # four), else at the first touch
                    sol = solve_ring_contact(self.model, contact, case.torque_Nmm,
                                             theta if near is not None else p.turn_of(first_um),
                                             guess=theta, start=start)
            except ContactError:   # the candidates alone cannot carry the torque: on
                if rule.within is not None:
                    continue
                if not predict:
                    raise
                return None
            if sol is not None:    # None: a point left out closes, its column is wanted
                return RingAttempt(contact, sol, grids, first_um, trial.teeth)
        raise AssertionError("the last try forms every column")   # pragma: no cover

    def finish(self, case: SolveCase, state, attempt: Attempt) -> PairSolution:
        if isinstance(attempt.solved, PairSolution):   # a pitch that repeats one solved
            return attempt.solved
        sol, rigid = self.record(case, state, attempt)
        if self.phases is not None:
            self.phases.solved(sol, rigid[0])
        return sol

    def record(self, case: SolveCase, state, attempt: Attempt, brief: bool = False,
               read: RingStresses | None = None) -> tuple[PairSolution, tuple]:
        """The record of a settled ``attempt`` (stresses, teeth, checks) and its rigid gaps at
        its solved rotation (with their rates), kept for no later position (:meth:`finish`
        keeps it); ``brief`` as :meth:`on_kept`; ``read``: its stresses, read with others'
        (:mod:`.kept_batch`)."""
        model, solved = self.model, attempt.solved
        contact, first_um = solved.contact, solved.first_um
        # the stresses take the clamped fields the contact's check formed, the teeth the
        # rigid gaps its last evaluation formed; neither is kept
        clamped, formed = solved.solution.clamped, solved.solution.rigid
        sol = replace(solved.solution, clamped=None, rigid=None)
        with timed("stresses"):
            touch = (math.nan if brief else
                     touch_rotation(model, contact, case.params.turn_of(first_um)))
            roots_only = self.modes.roots_only
            tangent = (math.nan if brief or roots_only else
                       tangent_stiffness(model, contact, sol))
            stresses, lean = self._stresses(case, solved, sol.pressure, brief, read, clamped)
            cands = () if stresses is None or brief or roots_only or read is not None else \
                candidate_data(case.params, model.shape, state,
                               tuple(g.tooth for g in solved.grids), case.beta)
            detail = RingDetail(model, case, replace(contact, A=None, former=None), sol, stresses)
            rigid = formed if formed is not None else solved_rigid_gap(detail)
            teeth = tooth_results(detail, state, cands, rigid,
                                  references=not (brief or roots_only or lean))
        residuals = () if stresses is None or brief or roots_only or lean else tuple(
            equilibrium_residuals(model, contact, sol, stresses))
        return PairSolution(
            case=case, teeth=teeth,
            root_stress=((math.nan, math.nan) if stresses is None else
                         (stresses.roots[0].max, stresses.roots[1].max)),
            von_mises_max=math.nan if stresses is None else stresses.von_mises_max,
            rotation=sol.rotation, first_touch=touch, dofs=model.dofs,
            checks=ContactChecks(sol.balance_error, sol.max_penetration, sol.iterations,
                                 residuals, contact.npoints),
            timings_s={}, detail=detail,
            von_mises_estimated=stresses is None or not stresses.submodels,
            tangent_stiffness=tangent), rigid

    def _stresses(self, case: SolveCase, solved: RingAttempt, pressure, brief: bool,
                  read: RingStresses | None, clamped) -> tuple[RingStresses | None, bool]:
        """A settled attempt's stresses as :meth:`record` forms them, and whether they were
        read without the fields on a kept contact (:attr:`SolverModes.read_kept`)."""
        model, contact = self.model, solved.contact
        if self.modes.contact_only:
            return None, False
        if read is not None:
            return read, False
        lean = self.modes.read_kept and self.phases.on_kept(contact, case.params.z2)
        if brief or self.modes.roots_only or lean:
            strains = None if self.modes.roots_only else self.phases.strains(model, case.beta)
            return brief_stresses(model, contact, pressure, strains), lean
        return ring_stresses(model, contact, pressure, self.modes.solved_submodels == "all",
                             clamped), False

    def with_pictured(self, sols: tuple[PairSolution, ...]) -> tuple[PairSolution, ...]:
        """``sols`` with the position pictured (the largest gear-1 root stress) formed whole
        where it was read without its fields (:attr:`SolverModes.read_kept`:
        :func:`~.peaks.whole`), for what is drawn and checked of it."""
        if not self.modes.read_kept or not sols:
            return sols
        k = pictured(sols)
        return (*sols[:k], whole(sols[k]), *sols[k + 1:])

    def read_later(self, sols) -> set[int]:
        """The positions of ``sols`` (a chain's) whose details this solver reads after the
        chains: the pictured one (:meth:`with_pictured`) and, where the submodels are solved
        at the peaks, the peaks' candidates (:func:`~.peaks.peak_candidates`)."""
        if self.modes.solved_submodels == "peaks":
            return peak_candidates(sols)
        return {pictured(sols)} if sols else set()

    def at_peaks(self, sols: tuple[PairSolution, ...]) -> tuple[PairSolution, ...]:
        """``sols`` with their contact submodels where the cycle peaks
        (:func:`~.peaks.with_peak_submodels`, with :attr:`SolverModes.submodels` "peaks"); the
        model is then kept in the model cache if it is on (:func:`~.model.keep_cached`)."""
        out = with_peak_submodels(sols) if self.modes.solved_submodels == "peaks" else sols
        if self.model is not None:
            keep_cached(self.model)
        return out


def kept_attempt(kept: tuple, state) -> Attempt:
    """The attempt settled on a kept contact: ``kept``, its contact and solution."""
    return Attempt(RingAttempt(*kept, kept[0].grids, state.closest(+1).plus_um), None)

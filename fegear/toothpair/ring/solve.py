"""The ring model's solve of one rolling position, for the driver of
:mod:`fegear.toothpair.positions`.

Each chosen tooth gets a pressure grid over the stretch of its profile that the expected
rotation can close, and the contact is solved. Then the driver's rule at the solved rotation
must choose no tooth without a grid, no grid may carry pressure at its ends and the rotation
the grids were placed at must be the solved one within :data:`PLACEMENT` of the elastic part;
otherwise the grids are placed again (:meth:`RingSolver.attempt` returns the new trial).

The model (meshes, factors, responses to unit loads) is built once per geometry and quality and
reused for every torque and position (:class:`~.model.RingModel`).
"""

from __future__ import annotations

import math
import time
from dataclasses import replace

import numpy as np
import scipy.sparse as sp

from ... import progress
from ...errors import ContactError, FegearError
from ...fe import contact_modulus, prepare_submodels, submodel_meshes
from ...geometry import Gear1Profile
from ..case import ContactChecks, PairSolution, SolveCase
from ..positions import SHARE_GUESS, Attempt, Trial, expected_elastic_um
from ..teeth import candidate_data, choose_teeth
from .contact import solve_ring_contact, tangent_stiffness, touch_rotation
from .grid import ToothGrid, tooth_grids, windows
from .influence import RingContact, assemble_contact
from .model import RingModel, keep_on_disk, ring_model
from .results import RingDetail, tooth_results
from .stresses import ring_stresses, submodel_keys, submodel_problems, with_submodels

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
                     # approach or more on the baseline's cycle): 0.55 of the fine grids' points
BEFORE_MARGIN = 0.15 # a later position of a cycle forms them only on the points within this
BEFORE_POINTS = 4    # fraction of its loaded stretch, and this many points, of where the
                     # position before carried pressure on the same tooth (on the baseline's
                     # cycle a stretch's ends move by 0.23 of it from one position to the next
                     # at most, 0.05 on most): 0.6 of the candidates' columns
PEAK_MARGIN = 0.02   # a cycle's position gets its submodels where its von Mises estimate is
                     # within this fraction of the cycle's largest von Mises stress (the
                     # estimate is within 0.6 % of the submodel at `standard`, 1 % at
                     # `coarse`, on the baseline's cycles, edge and relieved alike:
                     # docs/model.md, "Submodels over a cycle")
DISK_S = 0.07        # a contact submodel's disk meshed, assembled and factorised (s, baseline)
SUBMODEL_S = 0.007   # a position's submodels solved on disks meshed before (s, baseline)
FORK_S = 0.05        # a forked copy's start and its solutions read back (s)
#: the one-off stages a solve reports: the model built (profile, mesh, assembly and
#: factorisation), read back from the disk cache, or kept from an earlier solve
MODEL_STAGES = ("profile", "mesh", "assemble_factor", "disk", "model (kept)")
#: where the contact submodels are solved: at every position, only where a cycle's von Mises
#: peak is (and where any other headline stress peaks), or nowhere
SUBMODELS = ("all", "peaks", "none")


class RingSolver:
    """The ring model as a :class:`~fegear.toothpair.positions.PositionModel`: ``model``, a
    ring model built before, is kept if it fits the case; ``submodels`` one of
    :data:`SUBMODELS` (:meth:`complete`). Without a submodel, a position's von Mises stress at
    the contacts is the template's surface estimate (:func:`~.stresses.ring_stresses`).
    ``contact_only``: no stresses at all, for a caller that reads only the contact (loads,
    shares, pressures, flank and edge apart, rotations: the tip-relief search); the root and
    von Mises stresses are NaN, the teeth's Hertz values and half-plane references None."""

    reads_states = False   # the templates are the same whatever the positions

    def __init__(self, model: RingModel | None = None, submodels: str = "peaks",
                 contact_only: bool = False) -> None:
        if submodels not in SUBMODELS:
            raise ValueError(f"submodels must be one of {SUBMODELS}, not {submodels!r}")
        self.model = model
        self.submodels = "none" if contact_only else submodels
        self.contact_only = contact_only
        self.timings_s: dict = {}

    def build(self, case: SolveCase, profile: Gear1Profile, states,
              beside: bool = False) -> None:
        t0 = time.perf_counter()
        if self.model is None or not self.model.fits(case):
            progress.stage(f"model: both gears meshed and condensed at quality {case.quality}")
            self.model = ring_model(case, profile, beside)
        # a model's own stages count once, where it was built or read back; the same stages
        # on every solve (zero where not run), so that a study's table has the same columns
        # whichever way its cases found their models
        times = (self.model.timings_s if not self.model.served
                 else {"model (kept)": time.perf_counter() - t0})
        self.model.served += 1
        self.timings_s = {k: times.get(k, 0.0) for k in MODEL_STAGES}

    def settle(self) -> dict:
        """Gear 1's responses formed beside the build (:func:`~.model.build_ring`), taken in;
        the time, as the responses'."""
        t0 = time.perf_counter()
        for side in self.model.gears:
            side.settle()
        return {"responses": time.perf_counter() - t0}

    def attempt(self, case: SolveCase, state, trial: Trial,
                near: PairSolution | None) -> Attempt:
        model, p = self.model, case.params
        torque = case.torque * 1e3
        times = {"grids": 0.0, "assemble": 0.0, "contact": 0.0}
        first_um = state.closest(+1).plus_um
        elastic_um = trial.elastic_um
        # without a solution before, the expected rotation is an estimate (20-50 % off): a
        # first solve on probe grids only finds the rotation to place the fine grids at
        predict = near is None and not trial.own
        full = set() if predict else trial.own.get("full",
                                                   _expected(state, first_um + elastic_um))
        reach = trial.own.get("reach", {})
        formed = sum(g.response_s for g in model.gears)
        theta = p.turn_of(first_um + elastic_um)
        t0 = time.perf_counter()
        coarse = None if near is None else {g.tooth: g.coarse for g in near.detail.contact.grids
                                            if g.coarse is not None}
        grids = _grids(model, case, trial.teeth, full, theta, elastic_um, reach, coarse)
        times["grids"] += time.perf_counter() - t0
        # A's columns first only where pressure can act: not the probes' (where one closes,
        # the attempt is made again with that tooth's fine grid: once in 24 positions of the
        # baseline's cycle), and on the fine grids the points that overlap rigidly at the
        # expected rotation, or nearly (CANDIDATES); in a cycle's later position, of those, the
        # ones about where the position before carried pressure (_columns_before). Where a
        # point left out closes, the candidates', and then every column
        within = None if predict else CANDIDATES * elastic_um * 1e-3
        old = None if near is None else _by_tooth(near.detail)
        start = None if old is None else _loaded_before(old, grids)
        columns = None if old is None else _columns_before(old, grids)
        tries = [(False, within, columns)] if columns is not None else []
        tries += [(False, within, None), (True, None, None)]
        sol = None
        for probe_columns, within, columns in tries:
            t0 = time.perf_counter()
            contact = assemble_contact(model, grids, case.beta, p.ratio * case.beta + theta,
                                       probe_columns, within, columns)
            times["assemble"] += time.perf_counter() - t0
            t0 = time.perf_counter()
            try:
                # the rotation's linearisations start at the expected rotation after a
                # solved position (its elastic part off by a few per cent: three, not four),
                # else at the first touch
                sol = solve_ring_contact(model, contact, torque,
                                         theta if near is not None else p.turn_of(first_um),
                                         guess=theta, start=start)
            except ContactError:
                if within is not None:    # the candidates alone cannot carry the torque
                    sol = None
                elif not predict:
                    raise
                else:   # probe grids too coarse for this contact to settle: fine grids
                    return Attempt(None, replace(trial, own={"reach": reach}),
                                   "probe grids did not settle", times)
            times["contact"] += time.perf_counter() - t0
            if sol is not None:
                break
        formed = sum(g.response_s for g in model.gears) - formed
        times["assemble"] -= formed
        times["responses"] = formed
        result = (contact, sol, grids, first_um)
        more = set(choose_teeth(state, p.arc_um(sol.rotation), case.extra_pairs))
        ends = [g.tooth for k, g in enumerate(grids)
                if sol.pressure[contact.block(k)][[0, -1]].max() > 0]
        touched = {g.tooth for k, g in enumerate(grids)
                   if g.probe and sol.pressure[contact.block(k)].max() > 0}
        solved_um = p.arc_um(sol.rotation) - first_um
        moved = abs(solved_um - elastic_um) > PLACEMENT * max(abs(solved_um), 1e-3)
        if not predict and more <= set(trial.teeth) and not ends and not moved \
                and not touched:
            return Attempt(result, None, timings_s=times)
        reach = dict(reach)
        for t in ends:
            reach[t] = 2.0 * reach.get(t, 1.0)
        again = Trial(tuple(sorted(set(trial.teeth) | more)), max(solved_um, 1e-6),
                      {"full": full | touched | _expected(state, p.arc_um(sol.rotation)),
                       "reach": reach})
        why = ("probe grids first: " if predict else "") + (
            f"teeth {sorted(more - set(trial.teeth))}, ends {ends}, probes touched "
            f"{sorted(touched)}, elastic {solved_um:.3g} µm, expected {elastic_um:.3g}")
        return Attempt(result, again, why, times)

    def finish(self, case: SolveCase, state, attempt: Attempt) -> PairSolution:
        model, p = self.model, case.params
        contact, sol, grids, first_um = attempt.result
        # the stresses take the clamped fields the contact's check formed; not kept
        clamped, sol = sol.clamped, replace(sol, clamped=None)
        t0 = time.perf_counter()
        touch = touch_rotation(model, contact, p.turn_of(first_um))
        tangent = tangent_stiffness(model, contact, sol)
        if self.contact_only:
            teeth_out = tooth_results(model, case, contact, sol, None, state, ())
            checks = ContactChecks(sol.balance_error, sol.max_penetration, sol.iterations,
                                   (), contact.npoints)
            return PairSolution(
                case=case, teeth=teeth_out, root_stress=(math.nan, math.nan),
                von_mises_max=math.nan, rotation=sol.rotation, first_touch=touch,
                dofs=model.dofs, checks=checks,
                timings_s={"stresses": time.perf_counter() - t0},
                detail=RingDetail(model, case, _kept(contact), sol, None), von_mises_estimated=True,
                tangent_stiffness=tangent)
        stresses = ring_stresses(model, contact, sol.pressure, self.submodels == "all",
                                 clamped)
        cands = candidate_data(p, model.shape, state, tuple(g.tooth for g in grids), case.beta)
        teeth_out = tooth_results(model, case, contact, sol, stresses, state, cands)
        times = {"stresses": time.perf_counter() - t0}
        checks = ContactChecks(sol.balance_error, sol.max_penetration, sol.iterations,
                               tuple(_residuals(model, contact, sol, stresses)),
                               contact.npoints)
        return PairSolution(
            case=case, teeth=teeth_out,
            root_stress=(stresses.roots[0].max, stresses.roots[1].max),
            von_mises_max=stresses.von_mises_max, rotation=sol.rotation, first_touch=touch,
            dofs=model.dofs, checks=checks, timings_s=times,
            detail=RingDetail(model, case, _kept(contact), sol, stresses),
            von_mises_estimated=not stresses.submodels, tangent_stiffness=tangent)

    def complete(self, sols: tuple[PairSolution, ...], beside: bool = False
                 ) -> tuple[PairSolution, ...]:
        """With ``submodels`` "peaks", the submodels of the positions that decide a cycle's
        von Mises stress: where the largest gear-1 root stress is (the position the job
        pictures and estimates), where the von Mises estimate is largest, and wherever it
        comes within :data:`PEAK_MARGIN` of the largest von Mises stress solved, until no
        other does. A single position is its own peak. The first round takes every position
        whose estimate is within the margin of the largest estimate (on the baseline's cycle,
        one round of 7 instead of 2 and then 5). The others keep the surface estimate
        (``von_mises_estimated``); everything else a position reports, the other headline
        stresses included, does not depend on submodels. ``beside``: each round's peaks may
        be shared with a forked copy of this process (:func:`_shares`; their disks are meshed
        where they are solved: the same disks, the same numbers).
        The model is then kept on disk if the cache is on (:func:`~.model.keep_on_disk`)."""
        out = self._complete(sols, beside)
        if self.model is not None:
            keep_on_disk(self.model)
        return out

    def prepare(self, sols: list[PairSolution], busy) -> None:
        """While ``busy()`` (a cycle's other chain still runs beside), the disks of the
        submodels that :meth:`complete` most likely solves, meshed and factorised ahead one at
        a time, from the positions ``sols`` solved here: those of the largest gear-1 root
        stress among them and of the largest von Mises estimate. They are the same disks
        as meshed later (the same numbers); on the baseline's cycle every peak's submodels
        solve on these two, and the wait meshes them."""
        if self.submodels != "peaks" or not sols:
            return
        picks = dict.fromkeys([max(range(len(sols)), key=lambda i: sols[i].root_stress[0]),
                               max(range(len(sols)), key=lambda i: sols[i].von_mises_max)])
        kept = self.model.submodels
        for i in picks:
            d = sols[i].detail
            for problem, _ in submodel_problems(self.model, d.contact, d.solution.pressure,
                                                d.stresses):
                if problem.key in kept:
                    continue
                if not busy():
                    return
                prepare_submodels([problem], self.model.case.material, kept)

    def detach(self, sol: PairSolution) -> PairSolution:
        """``sol`` without its model, to cross from a chain solved beside (the fields of its
        sectors stay: a peak's submodels are cut from them), its contact's loads as sparse
        matrices (a hat loads the dofs of a few facets: 1.6 of a position's 3.3 MB, dense)."""
        d = sol.detail
        return replace(sol, detail=replace(d, model=None, contact=_loads_as(d.contact, True)))

    def attach(self, sol: PairSolution) -> PairSolution:
        """A :meth:`detach` ed solution on this solver's model (the one it was solved on, or
        the one its forked copy came from), its loads dense again (the same numbers)."""
        d = sol.detail
        return replace(sol, detail=replace(d, model=self.model,
                                           contact=_loads_as(d.contact, False)))

    def _complete(self, sols: tuple[PairSolution, ...], beside: bool
                  ) -> tuple[PairSolution, ...]:
        if self.submodels != "peaks" or not sols:
            return sols
        out = list(sols)
        # the pictured position, and from the start every position whose estimate comes
        # within the margin of the largest (that one among them): the submodels lift the
        # estimate by a few tenths of a per cent, so these are mostly the positions the rule
        # below would add a round later
        estimated = max(s.von_mises_max for s in sols)
        want = {max(range(len(sols)), key=lambda i: sols[i].root_stress[0])}
        want |= {i for i, s in enumerate(sols)
                 if s.von_mises_max >= (1.0 - PEAK_MARGIN) * estimated}
        done: set[int] = set()
        while want:
            self._with_submodels(out, sorted(want), beside)
            done |= want
            solved = [s.von_mises_max for s in out if not s.von_mises_estimated]
            if not solved:   # no peak a submodel could take (no surface stress anywhere)
                break
            want = {i for i, s in enumerate(out) if i not in done
                    and s.von_mises_max >= (1.0 - PEAK_MARGIN) * max(solved)}
        return tuple(out)

    def _with_submodels(self, out: list[PairSolution], which: list[int],
                        beside: bool) -> None:
        """``out[i]`` with its submodels for each of ``which``; ``beside``: a share of them
        in a forked copy of this process (should that fail in any way, here), split by
        :func:`_shares`."""
        mine, theirs = _shares(self.model, [out[i] for i in which]) if beside else \
            (list(range(len(which))), [])
        mine, theirs = [which[j] for j in mine], [which[j] for j in theirs]
        child = None
        if theirs:
            from ...workers import Forked

            def there():   # the solutions, and the disks meshed there for later peaks here
                before = set(self.model.submodels)
                sols = [self.detach(_with_submodels(out[i])) for i in theirs]
                return sols, submodel_meshes({k: v for k, v in self.model.submodels.items()
                                              if k not in before})

            child = Forked(there)
        try:
            for i in mine:
                out[i] = _with_submodels(out[i])
            got = child.result() if child is not None else None
        finally:
            if child is not None:
                child.stop()
        if got is None:
            for i in theirs:
                out[i] = _with_submodels(out[i])
            return
        solved, meshes = got
        for key, mesh in meshes.items():
            self.model.submodels.setdefault(key, mesh)
        for i, sol in zip(theirs, solved, strict=True):
            out[i] = self.attach(sol)


def _shares(model: RingModel, sols: list[PairSolution]) -> tuple[list[int], list[int]]:
    """``sols`` (their indices) in two shares of about equal cost, this process's and a forked
    copy's: a disk not meshed yet costs :data:`DISK_S`, a position's submodels on meshed disks
    :data:`SUBMODEL_S`, the fork and its answer read back :data:`FORK_S`, and a disk
    meshed for one position serves every other in the same share. The positions needing most
    new disks are placed first, each where it adds least. On the baseline's cycle every
    position of the first round needs the same two disks: they stay in one share, and no
    copy is forked."""
    have = set(model.submodels)
    need = [submodel_keys(model, s.detail.contact, s.detail.solution.pressure,
                          s.detail.stresses) - have for s in sols]
    members, meshed, cost = ([], []), (set(), set()), [0.0, FORK_S]
    for j in sorted(range(len(sols)), key=lambda j: -len(need[j])):
        added = [cost[k] + DISK_S * len(need[j] - meshed[k]) + SUBMODEL_S for k in (0, 1)]
        k = int(np.argmin(added))
        members[k].append(j)
        meshed[k].update(need[j])
        cost[k] = added[k]
    return sorted(members[0]), sorted(members[1])


def _with_submodels(sol: PairSolution) -> PairSolution:
    """``sol`` with its contact submodels solved (its stresses' time included)."""
    t0 = time.perf_counter()
    d = sol.detail
    stresses = with_submodels(d.model, d.contact, d.solution.pressure, d.stresses)
    times = dict(sol.timings_s)
    times["stresses"] = times.get("stresses", 0.0) + time.perf_counter() - t0
    return replace(sol, von_mises_max=stresses.von_mises_max, timings_s=times,
                   detail=replace(d, stresses=stresses),
                   von_mises_estimated=not stresses.submodels)


def _loads_as(contact: RingContact, sparse: bool) -> RingContact:
    """``contact`` with its load blocks' matrices sparse (CSC) or dense."""
    def block(b):
        return replace(b, matrix=sp.csc_matrix(b.matrix) if sparse else b.matrix.toarray())
    return replace(contact, loads=tuple({t: block(b) for t, b in loads.items()}
                                        for loads in contact.loads))


def _kept(contact: RingContact) -> RingContact:
    """What a solved position keeps of its contact: all but A (:class:`~.influence
    .RingContact`)."""
    return replace(contact, A=None)


def _by_tooth(before: RingDetail) -> dict:
    """The grids of a solved position by tooth, each with its pressures (a later position's
    start and columns read them)."""
    return {g.tooth: (g, before.solution.pressure[before.contact.block(k)])
            for k, g in enumerate(before.contact.grids)}


def _loaded_before(old: dict, grids: tuple[ToothGrid, ...]) -> np.ndarray | None:
    """The points of ``grids`` that lie where the position before (its grids by tooth,
    :func:`_by_tooth`) carried pressure on the same tooth (the active set's start: the
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


def _columns_before(old: dict, grids: tuple[ToothGrid, ...]) -> np.ndarray | None:
    """The points of ``grids`` whose columns of A a later position forms first: on a tooth
    that carried pressure in the position before (its grids by tooth, :func:`_by_tooth`),
    those within :data:`BEFORE_MARGIN` of that stretch and :data:`BEFORE_POINTS` points of it
    (the contact moves a little from one position to the next); none on a tooth that had a
    grid there but carried nothing; every point of a tooth new to the grids. Should a point
    left out close, the candidates' columns are formed, then every column
    (:meth:`RingSolver.attempt`). None where it holds no loaded tooth of ``grids``."""
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


def _expected(state, closure_um: float) -> set[int]:
    """Teeth a rigid rotation of ``closure_um`` (µm of arc at r0) closes: they get fine grids,
    the others chosen coarse probe grids (:func:`~.grid.tooth_grids`)."""
    return {c.tooth for c in state.teeth
            if c.plus_um is not None and c.plus_um <= closure_um + PROBE_MARGIN_UM}


def _grids(model: RingModel, case: SolveCase, teeth, full: set[int], theta: float,
           elastic_um: float, reach: dict, coarse: dict | None = None
           ) -> tuple[ToothGrid, ...]:
    """A grid on each of ``teeth`` whose profile a rotation θ (rad, from the kinematic
    position) brings within reach of gear 2 (``reach``: extra factors per tooth); fine on the
    ``full`` ones, a probe on the others. ``coarse``: the windows' coarse feet found before
    by tooth (:func:`~.grid.windows`' start)."""
    p = case.params
    base = REACH * elastic_um * 1e-3 + REACH_FLOOR * p.m
    turn = p.ratio * case.beta + theta - p.turn_of(elastic_um)   # at the first touch
    E_star = contact_modulus(case.E, case.E)
    load = case.torque * 1e3 / p.r0 / SHARE_GUESS / case.thickness
    # the grids' largest spacing follows the reach of the expected rotation without a solution
    # before, so that a position solved in a cycle has the grid it has alone
    canonical = REACH * expected_elastic_um(case) * 1e-3 + REACH_FLOOR * p.m
    while True:
        wins = [w for w in windows(model.samples, model.curve2, tuple(teeth), turn, case.beta,
                                   p.e, [base * reach.get(t, 1.0) for t in teeth], coarse)
                if w is not None]
        if wins:
            return tooth_grids(model.samples, wins, load, E_star, model.level.per_b,
                               GRID_FLOOR * p.m, canonical, [w.tooth not in full for w in wins])
        # the first touch the clearance table gives is the sharp profile's: on a tip edge the
        # round stands that far back (µm at z1 = 8 and h1 0.9), so the reach widens
        if base > WIDEST_REACH * p.m:
            raise FegearError("no tooth comes within reach of gear 2: the pair does not mesh")
        base *= 4.0


def _residuals(model: RingModel, contact: RingContact, sol, stresses) -> list[float]:
    """Each gear's equilibrium residual on its computed sectors (relative to its loads)."""
    out = []
    for side, loads, fields in zip(model.gears, contact.loads, stresses.fields):
        f = {t: b.vector(sol.pressure, side.body.ndofs) for t, b in loads.items()}
        out.append(side.body.residual(f, fields))
    return out


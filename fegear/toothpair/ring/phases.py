"""The ring's symmetry, used: a contact assembled at one rolling angle serves every angle whole
gear-2 pitches away.

Both gears are rings of identical sectors, so the pair at β + k·p2 (gear 2 turned k of its
pitches, gear 1 k of its own) is the pair at β with every tooth and sector renumbered: the
grids, the influence matrix A, the loads per unit hat pressure and the matching points are the
same numbers (:func:`~.turning.turned` renumbers them and turns the gear-frame points). Only
the rigid gaps differ, where the pair's deviations differ from tooth to tooth. A revolution's
z1 pitches meet each place within a pitch (a phase) z1 times; :class:`Phases` keeps one
contact a phase and solves the other pitches as gap vectors on it:

* the first position of a phase has the phase's contact made for its rotation, with fine
  grids on every paired tooth and one more either side, each as wide as the largest deviation
  of any tooth needs, A's columns formed where a solve first reads them (:mod:`.lazy`), and
  is solved on it (:meth:`Phases.keep`): about
  the rotation of the position solved before it (a position turns little from the next),
  else, or where those grids do not hold it, about its own, placed and solved first as any
  position;
* another pitch is a contact solve on that contact turned to it, its iterations measuring the
  gaps to the kept points' foot circles (:mod:`.circles`) (:meth:`Phases.solve`); where
  the kept grids do not hold it (a tooth without a grid would close, a grid carries pressure
  at an end), it is placed anew and its own contact kept instead;
* a pitch whose teeth on the kept contact carry the deviations of a pitch solved before, place
  by place, is the same contact problem: that solution renumbered, stresses and all, with no
  rigid gap formed (:meth:`Phases.repeat`; a runout turns with its gear, so with one every
  pitch differs);
* otherwise, a pitch whose rigid gaps leave a solution of its phase (the one that saw no
  deviation, else the last one solved) meeting every contact condition (the same gaps on
  every loaded tooth, the moved points open) is that solution renumbered, with the moved
  teeth's results formed again.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ...errors import ContactError
from ...geometry import Placed, gear2_tooth, pitch_phase
from ..case import PairSolution, SolveCase
from ..positions import Trial
from ..teeth import choose_teeth
from .circles import FootCircles, foot_circles
from .coarse import CoarseLevels
from .contact import Iterations, RingContactSolution, rigid_gap, solve_with
from .influence import ColumnRule, RingContact, assemble_contact
from .lazy import with_lazy_columns
from .model import RingModel
from .placement import PLACEMENT, REACH, REACH_FLOOR, GridPlacement, place_grids
from .readout import SurfaceStrains
from .turning import renumbered, turned, turned_again

#: rigid gaps (mm) that differ by less than this anywhere are the same contact problem: 0.1 nm,
#: a ten-thousandth of the smallest deviation given in whole µm, far above the turned
#: points' rounding (1e-15 mm)
SAME_GAP = 1e-7
#: a solve on a kept contact iterates on the points whose rigid gap is within this many times
#: the kept position's elastic approach of the least one (its wide grids are mostly far from
#: closing); the others are checked at the solution (:class:`~.contact.Iterations`)
NEAR = 1.5


@dataclass(frozen=True)
class SolvedPitch:
    """A position's solution kept for the pitches of its phase whose rigid gaps, at its solved
    rotation, are its ``gaps`` (mm): solved ``pitch`` gear-2 pitches from zero."""

    pitch: int
    gaps: np.ndarray
    solution: PairSolution


@dataclass(frozen=True)
class Kept:
    """A position's contact kept for the positions whole pitches away: assembled at the rolling
    angle ``pitch`` gear-2 pitches from zero, A spanning every point (its columns formed
    where first read: :mod:`.lazy`), with its
    solved rotation (rad), the points that carried pressure (where a solve at another pitch
    starts from), the rotation's elastic part (µm of arc at r0), and the teeth paired there,
    each with the reach (µm) beyond the exact pair's that its grid was sought within (a paired
    tooth with nothing of it within reach of gear 2 has no grid); ``teeth``: each gear's teeth
    whose deviations its rigid gaps can see (gear 1's with grids, gear 2's that their points
    face and one either side), in order."""

    pitch: int
    contact: RingContact
    rotation: float
    active: np.ndarray
    elastic_um: float
    reach_um: dict[int, float]
    teeth: tuple[tuple[int, ...], tuple[int, ...]] = ((), ())

    def seen(self, deviations, pitches: int, z: tuple[int, int]) -> tuple | None:
        """The deviations its rigid gaps see turned by ``pitches`` gear-2 pitches, place by
        place (:attr:`teeth`, each renumbered): two pitches that see the same are one contact
        problem. None with a runout (its offset turns with the gear: every pitch differs)."""
        if deviations.runout1.fr or deviations.runout2.fr:
            return None
        return tuple(tuple(table.get((t - pitches) % zg) for t in teeth)
                     for table, teeth, zg in zip((deviations.teeth(1), deviations.teeth(2)),
                                                 self.teeth, z))


class Phases:
    """The contacts kept by phase (:class:`Kept`), for one model; ``reach_um``: the most that
    any deviations solved on them can move a tooth (µm; the pairs drawn of a tolerance class),
    which every kept grid reaches beyond the exact pair's whatever the deviations of the
    position it is kept at.

    The contacts are kept at one torque, the first one kept at (``torque``); lighter torques
    are solved on them too (a load spectrum's levels over a revolution: a lighter load's
    contact lies within a heavier one's), each with the solutions it repeats from pitch to
    pitch its own (by phase and torque), and none of them keeps a contact (:meth:`keep`
    refuses it: the heavier torque's solutions stay those of the pair alone)."""

    def __init__(self, reach_um: float = 0.0) -> None:
        self.reach_um = reach_um
        self.torque: float | None = None
        self._kept: dict[int, Kept] = {}
        self._solved: dict[tuple[int, float], SolvedPitch] = {}   # (phase, torque) → …
        self._seen: dict[tuple[int, float], dict[tuple, SolvedPitch]] = {}   # … what it saw
        self._circles: dict[int, FootCircles] = {}   # phase → its kept contact's feet …
        self._strains: dict[int, SurfaceStrains] = {}   # … and surface strains
        self._coarse = CoarseLevels()   # … and coarse level
        self._turns: dict[int, dict] = {}   # … and its turned copies, by pitches

    def __len__(self) -> int:
        """How many phases have a contact kept."""
        return len(self._kept)

    def keeps(self, beta: float, z2: int) -> bool:
        """Whether a contact is kept for the phase of ``beta``."""
        return pitch_phase(beta, z2)[0] in self._kept

    def gridded(self, beta: float, z2: int) -> set[int]:
        """The teeth with grids on the contact kept at ``beta`` itself (none where none is
        kept there, or it was kept at another pitch of the phase)."""
        phase, pitch = pitch_phase(beta, z2)
        kept = self._kept.get(phase)
        if kept is None or kept.pitch != pitch:
            return set()
        return {g.tooth for g in kept.contact.grids}

    def on_kept(self, contact: RingContact, z2: int) -> bool:
        """Whether ``contact`` is the one kept for its phase, turned to its pitch (it shares
        the kept one's arrays), rather than placed on grids of its own."""
        kept = self._kept.get(pitch_phase(contact.beta, z2)[0])
        return kept is not None and contact.formed is kept.contact.formed

    def forget(self, beta: float, z2: int) -> None:
        """Let go of what is kept for the phase of ``beta`` (a position whose deviation sets
        are all solved: its contact is a large matrix)."""
        phase = pitch_phase(beta, z2)[0]
        for kept in (self._kept, self._circles, self._strains, self._coarse, self._turns):
            kept.pop(phase, None)
        self._drop_solved(phase)

    def _drop_solved(self, phase: int) -> None:
        """Let go of the solutions of ``phase`` at every torque."""
        for solved in (self._solved, self._seen):
            for key in [k for k in solved if k[0] == phase]:
                del solved[key]

    def repeat(self, model: RingModel, case: SolveCase, state) -> PairSolution | None:
        """The solution at ``case.beta`` (clearance ``state``) as one solved before in its
        phase, renumbered, where it solves this position's contact too; else None.

        It does where its teeth on the kept contact see the deviations a pitch solved before
        saw (:meth:`Kept.seen`): that solution, renumbered whole. Otherwise it tries the
        pitch of its phase that saw no deviation, then the last one solved: a solution does
        where the rigid gaps are the same on every tooth that carries load, and the points of
        the others, whose rigid gaps the deviations moved, stay open under the same pressures
        (their gaps are the solved ones moved by as much): the pressures and the rotation then
        meet every contact condition, and the compliance, positive definite, admits one
        solution. Those teeth's results are formed again, and the first touch."""
        p = case.params
        phase, pitch = pitch_phase(case.beta, p.z2)
        key = (phase, case.torque)
        last, kept = self._solved.get(key), self._kept.get(phase)
        if last is None or kept is None:
            return None
        placed = Placed(case.deviations, p, case.beta) if case.deviations else None
        seen = kept.seen(case.deviations, pitch - kept.pitch, (p.z1, p.z2))
        solved = self._seen.get(key, {})
        same = solved.get(seen)
        if same is not None:
            sol = same.solution
            contact = turned(model, sol.detail.contact, pitch - same.pitch, case.beta, placed)
            if not _teeth_hold(case, state, kept, pitch - kept.pitch, contact, sol.rotation):
                return None
            return renumbered(sol, pitch - same.pitch, case, state, contact)
        exact = None if seen is None else solved.get(tuple((None,) * len(t) for t in seen))
        for base in (exact, last) if exact is not last else (last,):
            out = None if base is None else _moved_only(model, case, state, kept, base, placed)
            if out is not None:
                if seen is not None:
                    self._seen.setdefault(key, {})[seen] = out
                return out.solution
        return None

    @staticmethod
    def beside(model: RingModel, near: PairSolution, beta: float) -> PairSolution:
        """``near``, the solution a position starts from, renumbered by the whole pitches
        between it and ``beta`` (a revolution solved phase by phase starts a pitch from the
        pitch before, and a phase from the last pitch of the phase before: their teeth stand
        a tooth or more on), so that it stands within a pitch of ``beta``."""
        pitches = round((beta - near.case.beta) / (2 * math.pi / near.case.params.z2))
        if pitches == 0:
            return near
        at = near.case.beta + pitches * 2 * math.pi / near.case.params.z2
        contact = turned(model, near.detail.contact, pitches, at, None)
        return renumbered(near, pitches, replace(near.case, beta=at), None, contact)

    def solved(self, sol: PairSolution, gaps: np.ndarray) -> None:
        """Keep ``sol``, solved, for the pitches of its phase with its rigid ``gaps`` (mm) at its
        solved rotation, where it was solved on the phase's kept contact (a contact turned from
        it shares its arrays); a position placed anew, on grids of its own, is not
        repeated."""
        detail, case = sol.detail, sol.case
        phase, pitch = pitch_phase(case.beta, case.params.z2)
        key = (phase, case.torque)
        contact = detail.contact
        if not self.on_kept(contact, case.params.z2):
            self._solved.pop(key, None)
            return
        kept = self._kept[phase]
        self._solved[key] = SolvedPitch(pitch, gaps, sol)
        seen = kept.seen(case.deviations, pitch - kept.pitch, (case.params.z1, case.params.z2))
        if seen is not None:
            self._seen.setdefault(key, {})[seen] = self._solved[key]

    def strains(self, model: RingModel, beta: float) -> SurfaceStrains:
        """The surface strains (:class:`~.readout.SurfaceStrains`) of the contact kept for
        the phase of ``beta``, made the first time they are asked for."""
        phase = pitch_phase(beta, model.case.params.z2)[0]
        if phase not in self._strains:
            self._strains[phase] = SurfaceStrains(model, self._kept[phase].contact)
        return self._strains[phase]

    def solve(self, model: RingModel, case: SolveCase, state, brief: bool = False
              ) -> tuple[RingContact, RingContactSolution] | None:
        """The contact at ``case.beta`` on the contact kept for its phase, turned to it, and its
        solution; None where none is kept or the kept grids do not hold this contact: the
        driver's rule at the solved rotation (``state``) chooses a tooth without a grid, or a
        grid carries pressure at an end (:func:`_holds`). ``brief``: its record reads no open
        point's rigid gap (:class:`~.contact.Iterations`)."""
        phase, pitch = pitch_phase(case.beta, case.params.z2)
        kept = self._kept.get(phase)
        if kept is None:
            return None
        placed = Placed(case.deviations, case.params, case.beta) if case.deviations else None
        contact = turned_again(self._turns.setdefault(phase, {}), model, kept.contact,
                               pitch - kept.pitch, case.beta, placed)
        if phase not in self._circles:
            self._circles[phase] = foot_circles(model, kept.contact, kept.rotation)
        try:
            sol = solve_with(model, contact, case.torque_Nmm, kept.rotation, Iterations(
                start=kept.active, within=NEAR * 1e-3 * max(kept.elastic_um, 1.0),
                circles=self._circles[phase],
                coarse=self._coarse.level(phase, kept.contact, model.case.thickness),
                brief=brief))
        except ContactError:
            return None
        if sol is None or not _holds(case, state, kept, pitch - kept.pitch, contact, sol):
            return None
        return contact, sol

    def kept(self, beta: float, z2: int) -> Kept | None:
        """What is kept for the phase of ``beta`` (None: nothing)."""
        return self._kept.get(pitch_phase(beta, z2)[0])

    def contact_at(self, model: RingModel, case: SolveCase) -> tuple[RingContact, Kept] | None:
        """The contact kept for the phase of ``case.beta`` turned to it, its rigid gaps with
        the case's deviations, and what was kept with it; None where none is kept."""
        phase, pitch = pitch_phase(case.beta, case.params.z2)
        kept = self._kept.get(phase)
        if kept is None:
            return None
        placed = Placed(case.deviations, case.params, case.beta) if case.deviations else None
        return turned(model, kept.contact, pitch - kept.pitch, case.beta, placed), kept

    def keep(self, model: RingModel, case: SolveCase, state, trial: Trial, rotation: float,
             widen: bool = False) -> tuple[RingContact, RingContactSolution] | None:
        """The contact of the phase of ``case.beta``, made about gear 1's ``rotation`` (rad:
        the position's solved one, or the one before it) on ``trial``'s teeth, kept, and
        solved: fine grids on every paired tooth and one more either side, each reaching as far
        as the largest deviation of any tooth could need (so that a pitch whose deviations sit
        on other teeth finds its grids), A's columns formed where a solve first reads them
        (:mod:`.lazy`); ``widen``: grids on the teeth of
        the contact kept there before too (a deviation set that needed others:
        :meth:`~.solver.RingSolver.widen`). None (nothing kept) where it does not hold the
        position's own contact, or the case's torque is not the one the contacts are kept at
        (:class:`Phases`)."""
        if self.torque is not None and case.torque != self.torque:
            return None
        p = case.params
        phase, pitch = pitch_phase(case.beta, case.params.z2)
        first_um = state.closest(+1).plus_um
        elastic_um = max(p.arc_um(rotation) - first_um, 1e-6)
        teeth = set(choose_teeth(state, p.arc_um(rotation), case.extra_pairs + 1))
        teeth |= set(trial.teeth)
        before = self._kept.get(phase)
        if widen and before is not None:
            teeth |= {(g.tooth - (pitch - before.pitch)) % p.z1 for g in before.contact.grids}
        widest = max(self.reach_um, *(case.deviations.reach_um(t) for t in range(p.z1)))
        base = REACH * elastic_um * 1e-3 + REACH_FLOOR * p.m
        reach = {t: 1.0 + 1e-3 * (widest - case.deviations.reach_um(t)) / base for t in teeth}
        grids = place_grids(model, case, Trial(tuple(sorted(teeth)), elastic_um),
                            GridPlacement(frozenset(teeth), reach), first_um)
        placed = Placed(case.deviations, p, case.beta) if case.deviations else None
        contact = with_lazy_columns(model, assemble_contact(
            model, grids, case.beta, p.ratio * case.beta + rotation, ColumnRule(now=False),
            placed))
        try:
            sol = solve_with(model, contact, case.torque_Nmm, rotation,
                             Iterations(guess=rotation))
        except ContactError:
            return None
        kept = Kept(pitch, replace(contact, feet=contact.feet.copy()), rotation,
                    np.zeros(contact.npoints, bool), elastic_um, dict.fromkeys(teeth, widest),
                    seen_teeth(contact, p.z2))
        if sol is None or not _holds(case, state, kept, 0, contact, sol):
            return None
        self._kept[phase] = replace(kept, rotation=sol.rotation, active=sol.pressure > 0,
                                    elastic_um=p.arc_um(sol.rotation) - first_um)
        self.torque = case.torque
        self._drop_solved(phase)   # what was solved on the contact it replaces
        for dropped in (self._circles, self._strains, self._coarse, self._turns):
            dropped.pop(phase, None)
        return contact, sol


def seen_teeth(contact: RingContact, z2: int) -> tuple[tuple[int, ...], tuple[int, ...]]:
    """The teeth whose deviations ``contact``'s rigid gaps can see (:attr:`Kept.teeth`):
    gear 1's with grids, gear 2's under its points' feet and one either side."""
    feet = contact.feet[np.isfinite(contact.feet)]
    under = gear2_tooth(feet, z2)
    near = np.unique(np.concatenate([under - 1, under, under + 1]) % z2)
    return tuple(g.tooth for g in contact.grids), tuple(int(t) for t in near)


def _moved_only(model: RingModel, case: SolveCase, state, kept: Kept, base: SolvedPitch,
                placed: Placed | None) -> SolvedPitch | None:
    """``base`` renumbered to ``case.beta`` where it solves that contact too
    (:meth:`Phases.repeat`), kept with its rigid gaps there; else None."""
    pitch = pitch_phase(case.beta, case.params.z2)[1]
    pitches, sol = pitch - base.pitch, base.solution
    contact = turned(model, sol.detail.contact, pitches, case.beta, placed)
    if not _teeth_hold(case, state, kept, pitch - kept.pitch, contact, sol.rotation):
        return None
    turn = case.params.ratio * case.beta + sol.rotation
    rigid = rigid_gap(model, contact, turn, contact.feet.copy())
    moved = np.abs(rigid[0] - base.gaps) > SAME_GAP
    if not moved.any():
        return SolvedPitch(pitch, rigid[0], renumbered(sol, pitches, case, state, contact))
    pressure = sol.detail.solution.pressure
    loaded = np.array([pressure[contact.block(k)].max() > 0
                       for k in range(len(contact.grids))])[contact.grid_index]
    opened = sol.detail.solution.gap + rigid[0] - base.gaps
    if (moved & loaded).any() or (opened[moved] <= 0).any():
        return None
    again = sorted({int(k) for k in contact.grid_index[moved]})
    return SolvedPitch(pitch, rigid[0], renumbered(sol, pitches, case, state, contact,
                                                   (rigid, again)))


def _holds(case: SolveCase, state, kept: Kept, pitches: int, contact: RingContact,
           sol: RingContactSolution) -> bool:
    """Whether the ``kept`` grids, turned by ``pitches`` (``contact``), hold its solution
    ``sol`` (:meth:`Phases.solve`). A tooth the driver's rule pairs at the solved rotation
    needs a grid, unless it was paired where the contact was kept, had no grid there, and
    neither the deviations nor the elastic rotation reach further now (its gap is then
    beyond the reach its window was sought within)."""
    if not _teeth_hold(case, state, kept, pitches, contact, sol.rotation):
        return False
    for k, g in enumerate(contact.grids):
        pressure = sol.pressure[contact.block(k)]
        if pressure[[0, -1]].max() > 0 or (g.probe and pressure.max() > 0):
            return False
    return True


def _teeth_hold(case: SolveCase, state, kept: Kept, pitches: int, contact: RingContact,
                rotation: float) -> bool:
    """Whether every tooth the driver's rule pairs at the ``rotation`` (rad) has a grid on
    ``contact`` (the ``kept`` one turned by ``pitches``) or had none where it was kept
    for want of a stretch within reach, which the deviations and the elastic rotation do not
    extend now (:func:`_holds`)."""
    p = case.params
    gridded = {g.tooth for g in contact.grids}
    elastic_um = p.arc_um(rotation) - state.closest(+1).plus_um
    for t in set(choose_teeth(state, p.arc_um(rotation), case.extra_pairs)) - gridded:
        then = (t + pitches) % p.z1
        if (then not in kept.reach_um or case.deviations.reach_um(t) > kept.reach_um[then]
                or elastic_um > (1.0 + PLACEMENT) * kept.elastic_um):
            return False
    return True

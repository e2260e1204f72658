"""A position's deviation sets solved on the contact kept for its phase and read together
(:class:`KeptBatch`): a tolerance class's samples at one position, or at one place over a
revolution's pitches.

Each set is solved on the kept contact as alone (:meth:`~.phases.Phases.solve`), in the order
given, so that a set the kept grids do not hold can be placed on its own and widen them for
the sets after it (:meth:`~.solver.RingSolver.widen`) before those are solved. Their brief
stresses are read together (:func:`~.readout.brief_stresses_of`): the root zones' loads, cut
motions and nodal stresses of every set of a phase as one product a sector where a set alone
takes a product a sector each, the same numbers to rounding. A set turned by whole pitches
from the kept contact is the kept contact's problem with its sectors renumbered, so it is read
in the kept contact's numbering and its stresses turned to its own; the rest of each set's
record is its own (:meth:`~.solver.RingSolver.on_kept`, brief).
"""

from __future__ import annotations

import numpy as np

from ...geometry import pitch_phase
from ..case import PairSolution, SolveCase
from ..positions import Attempt
from .readout import brief_stresses_of
from .solver import RingSolver, kept_attempt
from .turning import turned_stresses


class KeptBatch:
    """Deviation sets solved on ``solver``'s kept contacts (:meth:`add`), their records
    finished together (:meth:`finish`)."""

    def __init__(self, solver: RingSolver) -> None:
        self.solver = solver
        self.pending: list[tuple[SolveCase, object, Attempt]] = []

    def add(self, case: SolveCase, state) -> bool:
        """Solve ``case`` (clearance ``state``) on the contact kept for its phase and hold it
        for :meth:`finish`; False (nothing held) where none is kept there or its grids do not
        hold this one (:meth:`~.phases.Phases.solve`)."""
        kept = self.solver.phases.solve(self.solver.model, case, state, brief=True)
        if kept is None:
            return False
        self.pending.append((case, state, kept_attempt(kept, state)))
        return True

    def finish(self) -> list[PairSolution]:
        """The held sets' records, in the order they were added, brief (no first touch, no
        tangent stiffness, no references: :meth:`~.solver.RingSolver.on_kept`); none held
        after. The stresses of the sets of one phase are read together, on the contact kept
        for it and the strains kept with it, whatever pitch each was turned to, and each
        set's then turned to its own pitch (:func:`~.turning.turned_stresses`: the ring's
        sectors renumbered): every set held was solved on the contact kept now (a caller
        finishes the held sets before it places one that widens the kept grids, as a class's
        chains do); as the solver's modes say (:class:`~.solver.SolverModes`: none
        for ``contact_only``, the roots alone for ``roots_only``)."""
        solver, pending = self.solver, self.pending
        self.pending = []
        groups: dict[int, list[tuple[int, int]]] = {}   # phase → (set, its pitch)
        for i, (case, _, _) in enumerate(pending):
            phase, pitch = pitch_phase(case.beta, case.params.z2)
            groups.setdefault(phase, []).append((i, pitch))
        out: list[PairSolution | None] = [None] * len(pending)
        modes = solver.modes
        for members in groups.values():
            case = pending[members[0][0]][0]
            kept = solver.phases.kept(case.beta, case.params.z2)
            pressures = np.column_stack([pending[i][2].solved.solution.pressure
                                         for i, _ in members])
            strains = None if modes.roots_only else solver.phases.strains(solver.model,
                                                                          case.beta)
            read = [None] * len(members) if modes.contact_only else brief_stresses_of(
                solver.model, kept.contact, pressures, strains)
            for (i, pitch), stresses in zip(members, read, strict=True):
                case, state, attempt = pending[i]
                if stresses is not None and pitch != kept.pitch:
                    stresses = turned_stresses(solver.model, stresses, pitch - kept.pitch)
                out[i] = solver.record(case, state, attempt, brief=True, read=stresses)[0]
        return out

"""A job's positions solved across the face width (docs/model.md, "Across the face"): each
position solved by the one driver on a solver that keeps its contact, then at once across the
face on that contact, in the process that kept it (:func:`drive_across`). What is taken of a
position across the face is the caller's: the face's own row and contact pattern, or a
load level's tooth stresses for a life."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import replace
from typing import TYPE_CHECKING

from ..running import SERIAL, Executor
from .case import PairSolution, SolveCase, in_given_order, phase_major
from .face import Face
from .positions import drive_along
from .ring.face import FaceCoupling, measured_coupling
from .ring.face_results import face_sections
from .ring.model import ring_model
from .ring.solver import RingSolver, SolverModes

if TYPE_CHECKING:   # the job hands itself over; the job never imports this module's callers
    from .job import Job


def coupling_of(case: SolveCase, face: Face) -> FaceCoupling:
    """The sections of ``face`` across ``case``'s face width and their coupling, the 3D
    tooth's measured kernel mirrored in the free ends (:func:`~.ring.face
    .measured_coupling`; docs/model.md, "Across the face")."""
    return measured_coupling(ring_model(case), face.sections, case.thickness)


def drive_across(job: Job, take: Callable, coupling: FaceCoupling,
                 executor: Executor = SERIAL, model=None,
                 lighter: Sequence[float] = ()
                 ) -> tuple[RingSolver, tuple[PairSolution, ...], list]:
    """``job``'s case at its rolling angles (a revolution's, phase by phase, where it asks for
    one), each position solved across its face, its sections coupled by ``coupling``
    (:func:`coupling_of`: formed once by the caller, whatever the torque), on the contact the
    solver kept there: (the solver, the 2D solutions and what ``take(solution, sections)``
    gave at each position, both in the order of the job's angles). ``model``: the ring model
    to solve on (one built for the case where None). ``take`` gets the sections of every
    torque solved there, the job's first: the job's alone, or with ``lighter``'s, torques
    (N·m) below the job's, each solved across the face too on the contact kept at the job's
    torque (a lighter load's contact lies within a heavier one's at the same place, on grids
    at most twice as coarse as its own down to a quarter of it:
    :func:`~.positions.families`)."""
    case, face, betas = job.case, job.face, job.betas
    solver = RingSolver(model, SolverModes(keep_phases=True))
    order = phase_major(len(betas), case.params.z1) if job.revolution else range(len(betas))

    def across(at: SolveCase, state, sol: PairSolution):
        sections = tuple(face_sections(solver.model, solver.phases, replace(at, torque=torque),
                                       state, face, coupling)
                         for torque in (at.torque, *lighter))
        if any(s is None for s in sections):
            raise RuntimeError("no contact kept at a position solved across the face")
        return take(sol, sections)

    solved = drive_along(case, [betas[k] for k in order], solver, across, executor)
    ordered = in_given_order(order, solved)
    return solver, tuple(sol for sol, _ in ordered), [got for _, got in ordered]

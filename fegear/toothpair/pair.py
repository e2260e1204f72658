"""Solve a tooth pair with the ring model (:mod:`.ring`), the product's one model, through the
driver of :mod:`.positions`. The sector model, the full-FE peer it is checked against, lives in
:mod:`fegear.verify.sector` and runs through the same driver."""

from __future__ import annotations

from ..running import SERIAL, Executor
from .case import PairSolution, SolveCase


def solve_positions(case: SolveCase, betas, *, model=None, submodels: str = "peaks",
                    contact_only: bool = False, executor: Executor = SERIAL
                    ) -> tuple[PairSolution, ...]:
    """Solve ``case`` at each rolling angle of ``betas`` (rad) on one model. ``model``: a ring
    model (:func:`~.ring.build_ring`) built before for the same geometry and quality, kept.
    ``submodels``: where the contact submodels are solved, "peaks" (where a cycle's headline
    stresses peak; every position of one), "all" or "none"; elsewhere the von Mises stress at
    a contact is the template's surface estimate (contact pressures, root stresses and
    everything else are the same: :mod:`.ring.peaks`). ``contact_only``: no stresses (NaN),
    for a caller that reads only the contact. ``executor``: where a cycle's chains of
    positions are solved (:func:`~.positions.drive`)."""
    from .positions import drive  # lazy: heavy: the driver loads scipy
    from .ring.solver import RingSolver, SolverModes  # lazy: heavy: scikit-fem

    solver = RingSolver(model, SolverModes(submodels=submodels, contact_only=contact_only))
    return solver.at_peaks(drive(case, betas, solver, executor=executor))


def solve_job_positions(job, *, submodels: str = "peaks", contact_only: bool = False
                        ) -> tuple[PairSolution, ...]:
    """A prepared job's pair (:func:`~.job.prepare_job`) at its positions, ``submodels`` and
    ``contact_only`` as :func:`solve_positions`'; a revolution's (``job.revolution``) as
    ``fegear solve --revolution`` solves them, phase by phase with each phase's contact kept,
    so that a pitch that sees the same teeth as one solved before (every pitch of a perfect
    pair) is that one renumbered, not solved again (:func:`~.positions.positions_of`)."""
    from .positions import positions_of  # lazy: heavy: the driver loads scipy
    from .ring.solver import RingSolver, SolverModes  # lazy: heavy: scikit-fem

    modes = SolverModes(submodels=submodels, contact_only=contact_only,
                        keep_phases=job.revolution, read_kept=job.revolution)
    solver = RingSolver(None, modes)
    return solver.at_peaks(positions_of(solver, job.revolution)(job.case, job.betas, SERIAL))


def solve_pair(case: SolveCase, *, model=None) -> PairSolution:
    """Solve ``case`` at its rolling angle (``model``: a ring model built before, kept)."""
    return solve_positions(case, (case.beta,), model=model)[0]

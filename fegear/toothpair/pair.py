"""Solve a tooth pair with the ring model (:mod:`.ring`), the product's one model, through the
driver of :mod:`.positions`. The sector model, the full-FE peer it is checked against, lives in
:mod:`fegear.verify.sector` and runs through the same driver."""

from __future__ import annotations

from ..geometry import Gear1Profile
from .case import PairSolution, SolveCase


def solve_positions(case: SolveCase, betas, profile: Gear1Profile | None = None,
                    model=None, submodels: bool = True) -> tuple[PairSolution, ...]:
    """Solve ``case`` at each rolling angle of ``betas`` (rad) on one model. ``model``: a ring
    model (:func:`~.ring.build_ring`) built before for the same geometry and quality, kept.
    ``submodels`` False: no contact submodels, the von Mises stress at a contact is the
    template's surface estimate (contact pressures and root stresses are the same)."""
    from .positions import drive
    from .ring.solve import RingSolver

    return drive(case, betas, RingSolver(model, submodels), profile)


def solve_pair(case: SolveCase, profile: Gear1Profile | None = None,
               model=None) -> PairSolution:
    """Solve ``case`` at its rolling angle."""
    return solve_positions(case, (case.beta,), profile, model)[0]

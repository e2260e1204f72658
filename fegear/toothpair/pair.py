"""Solve a tooth pair with the ring model (:mod:`.ring`), the product's one model, through the
driver of :mod:`.positions`. The sector model, the full-FE peer it is checked against, lives in
:mod:`fegear.verify.sector` and runs through the same driver."""

from __future__ import annotations

from ..geometry import Gear1Profile
from .case import PairSolution, SolveCase


def solve_positions(case: SolveCase, betas, profile: Gear1Profile | None = None,
                    model=None, submodels: str = "peaks", contact_only: bool = False,
                    beside: bool = False, ahead=None) -> tuple[PairSolution, ...]:
    """Solve ``case`` at each rolling angle of ``betas`` (rad) on one model. ``model``: a ring
    model (:func:`~.ring.build_ring`) built before for the same geometry and quality, kept.
    ``submodels``: where the contact submodels are solved, "peaks" (where the cycle's
    headline stresses peak; every position of one), "all" or "none"; elsewhere the von Mises
    stress at a contact is the template's surface estimate (contact pressures, root stresses
    and everything else are the same: :meth:`~.ring.solve.RingSolver.complete`).
    ``contact_only``: no stresses (NaN), for a caller that reads only the contact.
    ``beside``: a second core is free for a cycle's second chain of positions; ``ahead``:
    called with the positions solved, before their submodels (:func:`~.positions.drive`)."""
    from .positions import drive
    from .ring.solve import RingSolver

    return drive(case, betas, RingSolver(model, submodels, contact_only), profile, beside,
                 ahead)


def solve_pair(case: SolveCase, profile: Gear1Profile | None = None,
               model=None) -> PairSolution:
    """Solve ``case`` at its rolling angle."""
    return solve_positions(case, (case.beta,), profile, model)[0]

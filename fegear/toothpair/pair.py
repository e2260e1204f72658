"""Solve a tooth pair with the model its case names: the ring model (the default) or the
sector model (:mod:`.ring`, :mod:`.sector`)."""

from __future__ import annotations

from ..geometry import Gear1Profile
from .case import PairSolution, SolveCase


def solve_positions(case: SolveCase, betas, profile: Gear1Profile | None = None,
                    model=None) -> tuple[PairSolution, ...]:
    """Solve ``case`` at each rolling angle of ``betas`` (rad) on one mesh. ``model``: a ring
    model built before for the same geometry and quality (ring model only; reused)."""
    if case.model == "sector":
        from .sector.solve import solve_positions as sector

        return sector(case, betas, profile)
    from .ring.solve import solve_positions as ring

    return ring(case, betas, profile, model)


def solve_pair(case: SolveCase, profile: Gear1Profile | None = None,
               model=None) -> PairSolution:
    """Solve ``case`` at its rolling angle."""
    return solve_positions(case, (case.beta,), profile, model)[0]

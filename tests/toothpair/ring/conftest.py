"""The solved cases the ring model's tests share: the baseline pair's model (``model``, the
session's ``baseline_ring``), its position at β = 0 under 200 N·m, a solver with that
position's contact kept for deviation sets (``kept_at_zero``), and random contact problems
(``contact_problem``)."""

from dataclasses import replace

import numpy as np
import pytest

from fegear.running import SERIAL
from fegear.toothpair.positions import positions_of
from fegear.toothpair.ring import RingSolver, SolverModes
from fegear.toothpair.ring.contact_system import ContactSystem


@pytest.fixture(scope="session")
def model(baseline_ring):
    """The baseline pair's ring model at ``coarse``."""
    return baseline_ring


@pytest.fixture(scope="session")
def baseline_200(baseline_ring):
    """The baseline pair at β = 0 under 200 N·m, coarse: four teeth carry it, two on their
    tip rounds."""
    from fegear.toothpair import solve_pair

    return solve_pair(replace(baseline_ring.case, torque=200.0), model=baseline_ring)


@pytest.fixture(scope="session")
def kept_at_zero(baseline_ring):
    """A ring solver with the baseline's position at β = 0 under 200 N·m solved and its
    contact kept, reaching as far as the deviation sets given move a tooth, and the case."""

    def kept(sets) -> tuple:
        case = replace(baseline_ring.case, torque=200.0)
        solver = RingSolver(baseline_ring, SolverModes(keep_phases=True))
        solver.reach(max(d.reach_um(t) for d in sets for t in range(case.params.z1)))
        positions_of(solver, False)(case, (0.0,), SERIAL)
        return solver, case

    return kept


@pytest.fixture(scope="session")
def contact_problem():
    """A contact of n points drawn with a seed, as its linear system
    (:class:`~fegear.toothpair.ring.contact_system.ContactSystem`): a symmetric positive
    compliance in the form the ring's (A = C W, pressures times weights are forces), rigid gaps
    with a rotation rate a < 0 on most."""

    def problem(n: int, seed: int) -> ContactSystem:
        rng = np.random.default_rng(seed)
        x = np.sort(rng.uniform(0.0, 1.0, n))
        C = 1e-4 * np.exp(-np.abs(x[:, None] - x[None, :]) / 0.2) + 1e-5 * np.eye(n)
        w = rng.uniform(0.01, 0.05, n)
        g0 = 1e-3 * (x - 0.4) ** 2 - 2e-5
        a = -rng.uniform(5.0, 20.0, n)
        return ContactSystem(C * w[None, :], w, g0, a)

    return problem

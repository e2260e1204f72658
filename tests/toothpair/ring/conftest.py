"""The solved cases the ring model's tests share: the baseline pair's model (``model``, the
session's ``baseline_ring``), its position at β = 0 under 200 N·m, and random contact
problems (``contact_problem``)."""

from dataclasses import replace

import numpy as np
import pytest

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

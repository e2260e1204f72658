"""GMRES for the face's bordered systems (:mod:`fegear.toothpair.ring.krylov`): a
nonsymmetric system solved to scipy's tolerance in scipy's steps, restarted or not; an exact
preconditioner in one step; a start at the solution in none; a system it cannot meet in the
cycles it has reported unconverged."""

import numpy as np
import pytest
from scipy.sparse.linalg import gmres as scipy_gmres

from fegear.toothpair.ring import krylov
from fegear.toothpair.ring.krylov import gmres


def _system(seed: int, n: int = 200):
    """A nonsymmetric, well-conditioned matrix, a rough inverse of it and a right-hand side."""
    rng = np.random.default_rng(seed)
    a = 3.0 * np.eye(n) + rng.standard_normal((n, n)) / np.sqrt(n)
    m = np.linalg.inv(a + 0.5 * rng.standard_normal((n, n)) / np.sqrt(n))
    return a, m, rng.standard_normal(n)


@pytest.mark.parametrize("seed", range(3))
def test_it_solves_to_scipys_tolerance_in_scipys_steps(seed):
    a, m, b = _system(seed)
    found = gmres(lambda x: a @ x, lambda x: m @ x, b, np.zeros(len(b)), 1e-13)
    assert found.converged
    assert np.linalg.norm(a @ found.x - b) <= 1e-13 * np.linalg.norm(b)
    np.testing.assert_allclose(found.x, np.linalg.solve(a, b), rtol=0, atol=1e-12)
    steps = []
    scipy_gmres(a, b, M=m, rtol=1e-13, atol=0.0, restart=80, maxiter=20,
                callback=steps.append, callback_type="pr_norm")
    assert abs(found.steps - len(steps)) <= 1


def test_restarted_it_still_converges(monkeypatch):
    a, m, b = _system(7)
    monkeypatch.setattr(krylov, "RESTART", 3)
    found = gmres(lambda x: a @ x, lambda x: m @ x, b, np.zeros(len(b)), 1e-12)
    assert found.converged and found.steps > 3
    np.testing.assert_allclose(found.x, np.linalg.solve(a, b), rtol=0, atol=1e-11)


def test_an_exact_preconditioner_takes_one_step_and_the_solution_none():
    a, _, b = _system(1)
    inverse = np.linalg.inv(a)
    found = gmres(lambda x: a @ x, lambda x: inverse @ x, b, np.zeros(len(b)), 1e-12)
    assert found.converged and found.steps == 1
    again = gmres(lambda x: a @ x, lambda x: inverse @ x, b, found.x, 1e-12)
    assert again.converged and again.steps == 0


def test_a_system_it_cannot_meet_is_reported_unconverged(monkeypatch):
    a, _, b = _system(2)
    monkeypatch.setattr(krylov, "RESTART", 2)
    monkeypatch.setattr(krylov, "CYCLES", 2)
    found = gmres(lambda x: a @ x, lambda x: x, b, np.zeros(len(b)), 1e-13)
    assert not found.converged and found.steps == 4

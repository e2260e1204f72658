"""What every position the ring model solves must satisfy (tests/toothpair/ring)."""

import math

import numpy as np
import pytest


def assert_converged(sol):
    """Converged: the torque carried by the pressure, pressures and gaps complementary, both
    rings in equilibrium, every headline stress finite."""
    d = sol.detail
    p, gap = d.solution.pressure, d.solution.gap
    assert sol.checks.balance_error < 1e-9
    assert np.all(p >= 0) and gap.min() > -1e-12
    assert np.abs(p * gap).max() < 1e-9 * p.max()
    assert max(sol.checks.residuals) < 1e-9
    assert sum(t.load_share for t in sol.teeth) == pytest.approx(1.0, abs=1e-9)
    assert all(math.isfinite(v) for v in sol.headline().values())

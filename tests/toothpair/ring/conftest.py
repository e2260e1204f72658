"""The solved cases the ring model's tests share: the baseline pair's model (``model``, the
session's ``baseline_ring``) and its position at β = 0 under 200 N·m."""

from dataclasses import replace

import pytest


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

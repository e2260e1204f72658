"""The contact submodels of a mesh cycle (:mod:`fegear.toothpair.ring.peaks`): where the
cycle peaks and at the pictured position, each position as alone."""

import math
from dataclasses import dataclass, replace

import numpy as np
import pytest

from fegear.toothpair import solve_pair, solve_positions
from fegear.toothpair.ring import peaks


def test_a_cycle_solves_submodels_where_it_peaks_and_each_position_as_alone(baseline_ring):
    # a cycle's positions are the positions solved alone; only the von Mises stress of those
    # away from the cycle's peaks is the surface estimate, and the cycle's largest is solved
    p = baseline_ring.case.params
    case = replace(baseline_ring.case, torque=200.0)
    betas = tuple(np.linspace(0.0, 2 * math.pi / p.z2, 6, endpoint=False))
    cycle = solve_positions(case, betas, model=baseline_ring)
    every = solve_positions(case, betas, model=baseline_ring, submodels="all")
    estimated = [s for s in cycle if s.von_mises_estimated]
    assert 0 < len(estimated) < len(cycle)
    for s, full in zip(cycle, every):
        alone = solve_pair(replace(case, beta=s.case.beta), model=baseline_ring)
        assert not alone.von_mises_estimated and not full.von_mises_estimated
        for key, value in alone.headline().items():
            tol = 0.015 if key == "von_mises_max_MPa" and s.von_mises_estimated else 1e-3
            assert s.headline()[key] == pytest.approx(value, rel=tol), (s.case.beta, key)
            assert full.headline()[key] == pytest.approx(value, rel=1e-3), (s.case.beta, key)
    assert max(s.von_mises_max for s in cycle) == pytest.approx(
        max(s.von_mises_max for s in every), rel=1e-3)
    pictured = max(cycle, key=lambda s: s.root_stress[0])
    assert not pictured.von_mises_estimated and pictured.detail.stresses.submodels


@dataclass(frozen=True)
class Position:
    """What :func:`~fegear.toothpair.ring.peaks.with_peak_submodels` reads of a solved
    position: its von Mises stress (MPa; the surface estimate until its submodels are solved),
    its root stresses and whether its von Mises stress is the estimate."""

    von_mises_max: float
    root_stress: tuple[float, float]
    von_mises_estimated: bool = True


def _solving(monkeypatch, solved: dict[int, float]):
    """Stand in for the submodels: position k's von Mises stress becomes ``solved[k]``
    (positions are told apart by their root stress, k); the positions solved, in order."""
    asked = []

    def with_submodels_of(sol):
        k = int(sol.root_stress[1])
        asked.append(k)
        return replace(sol, von_mises_max=solved[k], von_mises_estimated=False)

    monkeypatch.setattr(peaks, "with_submodels_of", with_submodels_of)
    return asked


def test_the_pictured_position_and_those_near_the_peak_get_their_submodels(monkeypatch):
    """Round one: the pictured position (the largest gear-1 root stress, however low its von
    Mises estimate) and every position within PEAK_MARGIN of the largest estimate. A later
    round: those the solved peak brings within the margin (the submodels here lower the
    largest estimate from 1000 to 960, which brings position 2's 945 within 2 % of it), until
    none is left; a position farther below keeps its estimate."""
    estimates = [1000.0, 990.0, 945.0, 700.0, 500.0]
    roots = [200.0, 210.0, 205.0, 190.0, 260.0]            # position 4 is pictured
    sols = tuple(Position(v, (r, k)) for k, (v, r) in enumerate(zip(estimates, roots)))
    asked = _solving(monkeypatch, {0: 960.0, 1: 955.0, 2: 950.0, 3: 705.0, 4: 505.0})
    out = peaks.with_peak_submodels(sols)
    assert asked == [0, 1, 4, 2]
    assert [s.von_mises_estimated for s in out] == [False, False, False, True, False]
    assert out[3] == sols[3]
    assert 1.0 - 945.0 / 960.0 < peaks.PEAK_MARGIN < 1.0 - 945.0 / 1000.0


def test_a_lone_position_is_its_own_peak_and_no_submodel_stops_the_rounds(monkeypatch):
    asked = _solving(monkeypatch, {0: 1001.0})
    (alone,) = peaks.with_peak_submodels((Position(1000.0, (300.0, 0)),))
    assert asked == [0] and not alone.von_mises_estimated
    assert peaks.with_peak_submodels(()) == ()

    def none_taken(sol):       # no surface stress anywhere: nothing a submodel could take
        return sol

    monkeypatch.setattr(peaks, "with_submodels_of", none_taken)
    sols = (Position(0.0, (0.0, 0)), Position(0.0, (0.0, 1)))
    assert peaks.with_peak_submodels(sols) == sols

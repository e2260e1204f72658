"""A kept contact's A formed where it is read (:mod:`fegear.toothpair.ring.lazy`): the columns
asked for are those of A formed whole, to rounding, the others are left unformed, a contact
solve on it settles the solution of A formed whole, and deviation sets solved on a kept
contact never read a column it left unformed."""

from dataclasses import replace

import numpy as np
import pytest

from fegear.geometry import Deviations, ToothDeviation, gear1_profile, moved_clearances
from fegear.toothpair.positions import Clearances
from fegear.toothpair.ring import phases
from fegear.toothpair.ring.coarse import AFTER
from fegear.toothpair.ring.contact import solve_ring_contact
from fegear.toothpair.ring.influence import ColumnRule, assemble_contact
from fegear.toothpair.ring.lazy import CHUNK, LazyColumns, with_lazy_columns


@pytest.fixture(scope="module")
def both(baseline_200):
    """The baseline's contact at β = 0 with A formed whole, and the same contact with A formed
    where it is read."""
    d = baseline_200.detail
    every = assemble_contact(d.model, d.contact.grids, 0.0, d.contact.turn)
    bare = assemble_contact(d.model, d.contact.grids, 0.0, d.contact.turn, ColumnRule(now=False))
    assert bare.A is None
    return d.model, every, with_lazy_columns(d.model, bare)


def test_the_columns_asked_for_are_those_of_a_formed_whole(both):
    _, every, lazy = both
    scale = np.abs(every.A).max()
    asked = np.array([0, 5, lazy.npoints // 2, lazy.npoints - 1])
    lazy.ready(asked)
    former = lazy.former
    assert isinstance(former, LazyColumns)
    runs = np.unique(former.run[asked])
    assert former.formed.sum() == len(runs)   # a run of points a time, no more
    columns = np.concatenate([np.arange(former.starts[r], former.ends[r]) for r in runs])
    assert len(columns) <= CHUNK * len(runs)
    np.testing.assert_allclose(lazy.A[:, columns], every.A[:, columns], rtol=0,
                               atol=1e-13 * scale)
    lazy.ready(np.arange(lazy.npoints))   # then every one
    assert former.formed.all()
    np.testing.assert_allclose(lazy.A, every.A, rtol=0, atol=1e-13 * scale)


def test_a_run_never_crosses_a_grids_end(both):
    _, _, lazy = both
    former = lazy.former
    grid = lazy.grid_index
    for lo, hi in zip(former.starts, former.ends):
        assert 0 < hi - lo <= CHUNK
        assert grid[lo] == grid[hi - 1]


def test_a_solve_on_a_lazy_contact_settles_the_solution_of_a_formed_whole(baseline_200):
    d = baseline_200.detail
    torque, start, turn = d.case.torque * 1e3, baseline_200.first_touch, d.contact.turn
    every = assemble_contact(d.model, d.contact.grids, 0.0, turn)
    lazy = with_lazy_columns(d.model, assemble_contact(d.model, d.contact.grids, 0.0, turn,
                                                       ColumnRule(now=False)))
    full = solve_ring_contact(d.model, every, torque, start, guess=turn)
    part = solve_ring_contact(d.model, lazy, torque, start, guess=turn)
    np.testing.assert_allclose(part.pressure, full.pressure, rtol=0,
                               atol=1e-10 * full.pressure.max())
    assert part.rotation == pytest.approx(full.rotation, rel=1e-12)
    assert lazy.former.formed.mean() < 0.8   # the solve read some of its columns


def test_sets_solved_on_a_kept_contact_read_no_column_left_unformed(kept_at_zero, monkeypatch):
    # the kept contact's columns NaN until formed: a solve, its record or its coarse level
    # reading one left out would carry NaN into a set's numbers
    def unformed_nan(model, contact):
        former = LazyColumns(model, contact)
        former.A[:] = np.nan
        return replace(contact, A=former.A, former=former)

    monkeypatch.setattr(phases, "with_lazy_columns", unformed_nan)
    sets = (Deviations(gear1={10: ToothDeviation(pitch=3.0)}),
            Deviations(gear1={11: ToothDeviation(pitch=-2.0, slope=2.0)}),
            Deviations(centre_distance=4.0))
    solver, case = kept_at_zero(sets)
    state = Clearances(case, gear1_profile(case.params), (0.0,)).get()[0][1]
    kept = solver.phases.kept(0.0, case.params.z2)
    assert np.isnan(kept.contact.A).any()   # columns left unformed after the exact pair
    for _ in range(AFTER // len(sets) + 2):   # past its coarse level's forming too
        for d in sets:
            one = replace(case, deviations=d)
            sol = solver.on_kept(one, moved_clearances(d, case.params, [state])[0], brief=True)
            assert sol is not None
            assert all(np.isfinite(v) for v in sol.headline().values()), sol.headline()
            assert np.isfinite(sol.detail.solution.pressure).all()
    assert kept.contact.former.formed.mean() < 0.9

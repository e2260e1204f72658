"""A kept contact's A formed where it is read (:mod:`fegear.toothpair.ring.lazy`): the columns
asked for are those of A formed whole, to rounding, the others are left unformed, and a
contact solve on it settles the solution of A formed whole."""

import numpy as np
import pytest

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

"""Where a position's grids go and what a cycle's later position starts from
(:mod:`fegear.toothpair.ring.placement`): the active set from where the position before
carried pressure, the influence columns about there; the same solution either way."""

import math
from dataclasses import replace

import numpy as np
import pytest

from fegear.toothpair import solve_positions
from fegear.toothpair.ring.grid import ToothGrid
from fegear.toothpair.ring.placement import (
    BEFORE_MARGIN,
    BEFORE_POINTS,
    columns_before,
    loaded_before,
)


def test_a_later_position_starts_its_contact_from_the_one_before_with_the_same_solution(
        monkeypatch, baseline_ring):
    # the active set starts where the position before carried pressure: the iterations go,
    # the solution stays, to the bit
    import fegear.toothpair.ring.solver as solver

    p = baseline_ring.case.params
    case = replace(baseline_ring.case, torque=200.0)
    betas = tuple(np.linspace(0.0, 2 * math.pi / p.z2, 24, endpoint=False)[:4])
    warm = solve_positions(case, betas, model=baseline_ring, submodels="none")
    monkeypatch.setattr(solver, "loaded_before", lambda before, grids: None)
    cold = solve_positions(case, betas, model=baseline_ring, submodels="none")
    for a, b in zip(warm, cold, strict=True):
        np.testing.assert_array_equal(a.detail.solution.pressure, b.detail.solution.pressure)
        assert a.rotation == b.rotation and a.headline() == b.headline()
    assert warm[0].checks.iterations == cold[0].checks.iterations   # nothing before it
    for a, b in zip(warm[1:], cold[1:]):
        assert a.checks.iterations < 0.7 * b.checks.iterations


def test_a_later_position_forms_the_columns_about_where_the_one_before_carried_pressure(
        monkeypatch, baseline_ring):
    # in a cycle, A's columns first only about where the position before carried pressure:
    # fewer columns, the same solution to rounding; where a point left out closes (a margin
    # of none), the candidates' columns are formed and the position solves as before
    import fegear.toothpair.ring.influence as influence
    import fegear.toothpair.ring.placement as placement
    import fegear.toothpair.ring.solver as solver

    p = baseline_ring.case.params
    case = replace(baseline_ring.case, torque=200.0)
    betas = tuple(np.linspace(0.0, 2 * math.pi / p.z2, 24, endpoint=False)[:4])
    formed = []
    assemble = influence.assemble_contact

    def counted(*args, **kwargs):
        contact = assemble(*args, **kwargs)
        rule = kwargs.get("rule", args[4] if len(args) > 4 else None)
        formed.append((rule is not None and rule.mask is not None, int(contact.formed.sum())))
        return contact

    monkeypatch.setattr(solver, "assemble_contact", counted)
    columns_before = solver.columns_before
    narrow = solve_positions(case, betas, model=baseline_ring, submodels="none")
    used = formed[:]
    monkeypatch.setattr(solver, "columns_before", lambda before, grids: None)
    formed.clear()
    wide = solve_positions(case, betas, model=baseline_ring, submodels="none")
    for a, b in zip(narrow, wide, strict=True):
        assert a.rotation == pytest.approx(b.rotation, rel=1e-12)
        for key, value in b.headline().items():
            assert a.headline()[key] == pytest.approx(value, rel=1e-9), key
    narrowed = [n for masked, n in used if masked]
    assert len(narrowed) == 3                     # each later position, once
    assert sum(narrowed) < 0.85 * sum(n for _, n in formed[-3:])
    # the middle fifth of each loaded stretch only: a point left out closes, and the
    # candidates' columns are formed at every later position
    monkeypatch.setattr(solver, "columns_before", columns_before)
    monkeypatch.setattr(placement, "BEFORE_MARGIN", -0.4)
    monkeypatch.setattr(placement, "BEFORE_POINTS", 0)
    formed.clear()
    again = solve_positions(case, betas, model=baseline_ring, submodels="none")
    masked = [k for k, (m, _) in enumerate(formed) if m]
    assert len(masked) == 3 and all(not formed[k + 1][0] for k in masked)   # then candidates
    for a, b in zip(again, wide, strict=True):
        for key, value in b.headline().items():
            assert a.headline()[key] == pytest.approx(value, rel=1e-9), key


def _grid(tooth: int, phi: np.ndarray) -> ToothGrid:
    """A grid on ``tooth`` at polar angles ``phi`` (all that placement reads of one)."""
    n = len(phi)
    x = np.column_stack([np.cos(phi), np.sin(phi)])
    return ToothGrid(tooth, phi.copy(), phi, x, x, np.ones(n), np.zeros(n, dtype=bool))


def test_a_later_position_starts_where_the_one_before_pressed_and_forms_columns_about_there():
    """The position before: tooth 10 loaded on [0.40, 0.50] rad, tooth 11 gridded but unloaded.
    Now tooth 10's grid is finer and shifted, tooth 11 as before, tooth 12 new: the active set
    starts on tooth 10's points inside the loaded stretch alone; the columns are formed on
    tooth 10 within BEFORE_MARGIN of that stretch and BEFORE_POINTS points beyond, on none of
    tooth 11's and on all of the new tooth's."""
    before_phi = np.linspace(0.3, 0.6, 31)
    old = {10: (_grid(10, before_phi), np.where((before_phi > 0.395) & (before_phi < 0.505),
                                                 1.0, 0.0)),
           11: (_grid(11, before_phi), np.zeros(31))}
    now = np.linspace(0.305, 0.605, 61)
    grids = (_grid(10, now), _grid(11, now), _grid(12, now))
    start = loaded_before(old, grids)
    assert start.shape == (183,)
    assert np.array_equal(np.flatnonzero(start), np.flatnonzero((now > 0.39) & (now < 0.51)))
    columns = columns_before(old, grids)
    tooth10, tooth11, tooth12 = np.split(columns, 3)
    margin = BEFORE_MARGIN * 0.1
    inside = np.flatnonzero((now >= 0.4 - margin) & (now <= 0.5 + margin))
    expected = np.zeros(61, dtype=bool)
    expected[inside[0] - BEFORE_POINTS:inside[-1] + BEFORE_POINTS + 1] = True
    assert np.array_equal(tooth10, expected)
    assert not tooth11.any() and tooth12.all()


def test_a_position_with_nothing_loaded_before_on_its_teeth_starts_afresh():
    phi = np.linspace(0.3, 0.6, 31)
    grids = (_grid(12, phi), _grid(13, phi))
    assert loaded_before({10: (_grid(10, phi), np.ones(31))}, grids) is None
    assert columns_before({10: (_grid(10, phi), np.ones(31))}, grids) is None
    unloaded = {12: (_grid(12, phi), np.zeros(31))}
    assert not loaded_before(unloaded, grids).any()
    assert columns_before(unloaded, grids) is None       # no loaded tooth: every column

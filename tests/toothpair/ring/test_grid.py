"""The contact grids (:mod:`fegear.toothpair.ring.grid`): windows found together as alone and
from the feet before, grids as fine as the local Hertz width and finer at the tip round, on
the exact profile, sharing their points whatever the reach."""

import math

import numpy as np
import pytest

from fegear.fe import contact_modulus
from fegear.toothpair.ring.grid import (
    PROBE_POINTS,
    Facing,
    GridSpacing,
    tooth_grid,
    window,
    windows,
)


def test_the_windows_of_several_teeth_found_together_are_each_found_alone(model):
    # one closest-point search a pass for all teeth: the points are independent, so every
    # window (its range, anchor and gear-2 curvature) is the one-tooth search's to the bit
    facing = Facing(model.curve2, 135e-6, 0.0, model.case.params.e)
    teeth, reaches = (9, 10, 11, 12, 30, 40), (0.004, 0.02, 0.02, 0.001, 0.02, 0.02)
    together = windows(model.samples, facing, teeth, reaches)
    alone = [window(model.samples, facing, t, r) for t, r in zip(teeth, reaches)]
    assert together[-1] is None and sum(w is not None for w in together) >= 3
    for a, b in zip(together, alone):
        if b is None:
            assert a is None
            continue
        assert (a.tooth, a.lo, a.hi, a.anchor) == (b.tooth, b.lo, b.hi, b.anchor)
        assert np.array_equal(a.kappa2, b.kappa2)


def test_windows_searched_from_the_feet_of_the_position_before_are_the_polar_searchs(model):
    # a cycle's later position starts its coarse foot searches at the position before's
    # feet: the same windows, and feet and gear-2 curvature to rounding
    p = model.case.params
    teeth, reaches = (9, 10, 11, 12), (0.02,) * 4
    step = 2.0 * math.pi / p.z2 / 24
    before = windows(model.samples, Facing(model.curve2, 135e-6, 0.0, p.e), teeth, reaches)
    start = {w.tooth: w.coarse for w in before if w is not None}
    assert len(start) >= 3
    later = Facing(model.curve2, p.ratio * step + 135e-6, step, p.e)
    polar = windows(model.samples, later, teeth, reaches)
    started = windows(model.samples, later, teeth, reaches, start)
    assert sum(w is not None for w in polar) >= 3
    for a, b in zip(started, polar):
        if b is None:
            assert a is None
            continue
        assert (a.tooth, a.lo, a.hi, a.anchor) == (b.tooth, b.lo, b.hi, b.anchor)
        np.testing.assert_allclose(a.kappa2, b.kappa2, rtol=1e-9)
        near = np.abs(b.coarse - start[b.tooth]) < 0.1    # the feet that moved with the tooth
        assert near.mean() > 0.9
        np.testing.assert_allclose(a.coarse[near], b.coarse[near], rtol=0, atol=1e-12)


def test_grids_follow_the_local_hertz_width_and_refine_at_the_tip_round(model):
    facing = Facing(model.curve2, 135e-6, 0.0, model.case.params.e)
    win = window(model.samples, facing, 11, 0.02)
    spacing = GridSpacing(300.0, contact_modulus(2.06e5, 2.06e5), 8, 2e-5, 0.02)
    grid = tooth_grid(model.samples, win, spacing)
    step = np.diff(grid.s)
    assert grid.on_round.any() and not grid.on_round.all()
    # on the round (radius 0.25 mm) the Hertz width is far smaller than on the flank
    assert step[grid.on_round[:-1]].max() < 0.2 * step[~grid.on_round[:-1]].max()
    assert np.all(step > 0) and grid.weights.sum() == pytest.approx(grid.s[-1])
    # the grid points lie on the exact rounded profile, normals outward and unit
    assert np.abs(np.linalg.norm(grid.x, axis=1) - model.shape.radius(grid.phi)).max() < 1e-9
    assert np.abs(np.linalg.norm(grid.normal, axis=1) - 1).max() < 1e-10


def test_grids_of_two_reaches_share_their_points_but_the_ends(model):
    # a position solved alone places its windows for another expected rotation than within a
    # cycle: the grid points are counted from the tooth's smallest gap, so the wider window
    # holds every inner point of the narrower one, and the rounds' tangent points
    facing = Facing(model.curve2, 135e-6, 0.0, model.case.params.e)
    spacing = GridSpacing(300.0, contact_modulus(2.06e5, 2.06e5), 8, 2e-5, 0.02)
    grids = [tooth_grid(model.samples, window(model.samples, facing, 11, reach), spacing)
             for reach in (0.01, 0.02)]
    narrow, wide = (g.phi for g in grids)
    assert len(wide) > len(narrow) + 4
    inner = narrow[1:-1]
    assert np.abs(wide[:, None] - inner[None, :]).min(axis=0).max() < 1e-12
    pitch = model.shape.pitch
    ends = np.array([a + (np.round((model.samples.phi[2000] - a) / pitch) + 11) * pitch
                     for f in model.shape.fillets for a in (f.phi_a, f.phi_b)])
    ends = ends[(ends > wide[0]) & (ends < wide[-1])]
    assert len(ends) and np.abs(wide[:, None] - ends[None, :]).min(axis=0).max() < 1e-12


@pytest.mark.parametrize("tooth, load, per_b", [(11, 300.0, 8), (10, 30.0, 4), (9, 300.0, 8)])
def test_a_grid_is_as_fine_as_its_share_of_the_local_hertz_width(model, tooth, load, per_b):
    """Each interval of a fine grid is at most a ``per_b``-th of the Hertz half-width of the
    two profiles' relative curvature at its ends (its floor where that is finer); a whole
    count of spacings gives way to a mark (a window's end, a tangent point of a round) within
    half a spacing, so next to those it may be half as wide again. A probe grid has
    PROBE_POINTS even intervals. Both lie on the exact rounded profile."""
    E_star = contact_modulus(2.06e5, 2.06e5)
    win = window(model.samples, Facing(model.curve2, 135e-6, 0.0, model.case.params.e),
                 tooth, 0.02)
    spacing = GridSpacing(load, E_star, per_b, 2e-5, 0.02)
    grid = tooth_grid(model.samples, win, spacing)
    turned = model.samples.phi[win.lo:win.hi + 1] + tooth * model.shape.pitch
    relative = np.maximum(grid.curvature + np.interp(grid.phi, turned, win.kappa2), 1e-9)
    b = np.sqrt(4.0 * load / (math.pi * E_star * relative))
    allowed = np.maximum(b / per_b, spacing.floor)
    step = np.diff(grid.s) / np.maximum(allowed[:-1], allowed[1:])
    marked = np.zeros(len(step), dtype=bool)
    marked[[0, -1]] = True                                    # the window's ends
    for j in np.flatnonzero(np.diff(grid.on_round.astype(int))):   # a round's tangent point
        marked[max(j - 1, 0):j + 2] = True
    assert step[~marked].max() < 1.01 and step.max() < 1.5
    probe = tooth_grid(model.samples, win, spacing, probe=True)
    assert len(probe) == PROBE_POINTS + 1
    assert np.ptp(np.diff(probe.s)) < 0.02 * np.diff(probe.s).mean()
    for g in (grid, probe):
        assert np.abs(np.linalg.norm(g.x, axis=1) - model.shape.radius(g.phi)).max() < 1e-9

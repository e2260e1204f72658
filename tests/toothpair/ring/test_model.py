"""The ring model's pieces: the template sectors (one tooth pitch of each gear, periodic cut
faces), a gear's sectors and loads, the contact grids."""

import math

import numpy as np
import pytest
from skfem import Basis, ElementTriP2, Functional

from fegear.planar import rotate


@pytest.fixture(scope="module")
def model(baseline_ring):
    return baseline_ring


def _area(side):
    m = side.body.mesh
    return float(Functional(lambda w: 1.0 + 0.0 * w.x[0]).assemble(Basis(m, ElementTriP2())))


def test_templates_tile_each_gear_exactly(model):
    """z1 (z2) copies of a template cover gear 1 (gear 2): the template's area is one pitch of
    the area between the exact rounded profile and the bore (rim), to the mesh's accuracy."""
    p = model.case.params
    shape = model.shape
    g1, g2 = model.gears
    phi = np.linspace(shape.tooth_center, shape.tooth_center + shape.pitch, 20001)
    r1 = shape.radius(phi)
    bore = float(np.min(np.linalg.norm(g1.body.mesh.doflocs, axis=0)))
    expected1 = 0.5 * np.trapezoid(r1 ** 2, phi) - 0.5 * bore ** 2 * shape.pitch
    assert _area(g1) == pytest.approx(expected1, rel=1e-6)
    theta = np.linspace(0.0, 2 * math.pi / p.z2, 20001)
    r2 = model.curve2.radius_at_angle(theta)
    rim = float(np.max(np.linalg.norm(g2.body.mesh.doflocs, axis=0)))
    expected2 = 0.5 * rim ** 2 * 2 * math.pi / p.z2 - 0.5 * np.trapezoid(r2 ** 2, theta)
    assert _area(g2) == pytest.approx(expected2, rel=1e-6)


def test_cut_faces_match_and_the_rings_close(model):
    p = model.case.params
    for side, z in zip(model.gears, (p.z1, p.z2)):
        body = side.body
        x = body.mesh.doflocs.T
        a, b = body.face_a[0::2] // 2, body.face_b[0::2] // 2
        assert np.abs(rotate(x[a], side.pitch) - x[b]).max() < 1e-9
        assert side.count == z and side.pitch * z == pytest.approx(2 * math.pi)


def test_a_point_turned_by_k_pitches_lands_in_sector_k_at_the_same_place(model):
    side = model.gears[0]
    rng = np.random.default_rng(1)
    x = model.samples.x[rng.integers(0, len(model.samples.x), 50)]
    here = side.locate(x)
    for k in (1, 7, side.count - 1):
        there = side.locate(rotate(x, k * side.pitch))
        assert np.array_equal(there.sector, (here.sector + k) % side.count)
        assert np.abs(there.local - here.local).max() < 1e-9


def test_nodal_loads_carry_the_force_and_its_moment(model):
    """The consistent nodal loads of point forces on gear 1's profile sum to the forces and to
    their moment about the gear's centre, in every sector they fall in."""
    side = model.gears[0]
    rng = np.random.default_rng(2)
    i = rng.integers(0, len(model.samples.x), 40)
    x = rotate(model.samples.x[i], rng.integers(0, 44, 40) * side.pitch)
    n = -rotate(model.samples.normal[i], np.arctan2(x[:, 1], x[:, 0])
                - np.arctan2(model.samples.x[i, 1], model.samples.x[i, 0]))
    size = rng.uniform(1.0, 5.0, (40, 1))
    loads = side.nodal_loads(x, n, np.zeros((40, 1), dtype=int), size)
    where = side.locate(x)
    nodes = side.body.mesh.doflocs.T
    for k, block in loads.items():
        f = np.zeros(side.body.ndofs)
        f[block.dofs] = block.matrix[:, 0]
        sel = where.sector == k
        local_force = rotate(n[sel], -where.turn[sel]) * size[sel]
        assert f.reshape(-1, 2).sum(axis=0) == pytest.approx(local_force.sum(axis=0), abs=1e-9)
        moment = np.sum(nodes[:, 0] * f[1::2] - nodes[:, 1] * f[0::2])
        arm = where.local[sel]
        expected = np.sum(arm[:, 0] * local_force[:, 1] - arm[:, 1] * local_force[:, 0])
        assert moment == pytest.approx(expected, rel=1e-6, abs=1e-9)


def test_the_windows_of_several_teeth_found_together_are_each_found_alone(model):
    # one closest-point search a pass for all teeth: the points are independent, so every
    # window (its range, anchor and gear-2 curvature) is the one-tooth search's to the bit
    from fegear.toothpair.ring.grid import Facing, window, windows

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
    from fegear.toothpair.ring.grid import Facing, windows

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
    from fegear.fe import contact_modulus
    from fegear.toothpair.ring.grid import Facing, GridSpacing, tooth_grid, window

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
    from fegear.fe import contact_modulus
    from fegear.toothpair.ring.grid import Facing, GridSpacing, tooth_grid, window

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

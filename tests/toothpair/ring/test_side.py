"""One gear of the ring model (:mod:`fegear.toothpair.ring.side`): points carried between the
gear and its template's sectors, vectors back, and the consistent loads on its profile."""

import numpy as np
import pytest

from fegear.planar import rotate, wrap


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


def test_a_point_carried_into_the_template_and_back_is_the_same_point(model):
    """Points all round each gear: their template-frame position turned back by their sector's
    turn is the point again, and lies in the template's pitch; a field that moves the
    template by one unit along its x axis moves each point by that unit turned with its
    sector (vectors come back to the gear's frame)."""
    rng = np.random.default_rng(3)
    for side, r in zip(model.gears, (model.case.params.r0 - 3.0, model.case.params.r0 + 3.0)):
        angle = rng.uniform(-np.pi, np.pi, 200)
        x = r * np.column_stack([np.cos(angle), np.sin(angle)])
        where = side.locate(x)
        assert np.abs(rotate(where.local, where.turn) - x).max() < 1e-12
        local = np.arctan2(where.local[:, 1], where.local[:, 0])
        assert np.abs(wrap(local - side.template.start - 0.5 * side.pitch)).max() \
            <= 0.5 * side.pitch + 1e-12
        assert set(np.unique(where.sector)) <= set(range(side.count))
        near = np.abs(angle) < 0.1              # points in the sectors of a tooth or two
        x, where = x[near], side.locate(x[near])
        shift = np.tile([1.0, 0.0], side.body.ndofs // 2)
        moved = side.displacement_at(x, {int(k): shift for k in np.unique(where.sector)})
        expected = np.column_stack([np.cos(where.turn), np.sin(where.turn)])
        assert np.abs(moved - expected).max() < 1e-12

"""A contact turned by whole pitches (:mod:`fegear.toothpair.ring.turning`) is the contact
assembled there, number for number, and a deviated pitch on it takes its own rigid gaps."""

import math

import numpy as np
import pytest

from fegear.geometry import Deviations, Placed, ToothDeviation
from fegear.toothpair.ring.contact import rigid_gap
from fegear.toothpair.ring.influence import ColumnRule, assemble_contact
from fegear.toothpair.ring.turning import turned, turned_again, turned_grid


@pytest.fixture(scope="module")
def settled(baseline_200):
    return baseline_200.detail


@pytest.mark.parametrize("pitches", [1, 7, -3])
def test_a_contact_turned_by_whole_pitches_is_the_one_assembled_there(settled, pitches):
    model, contact = settled.model, settled.contact
    p = model.case.params
    beta = contact.beta + pitches * 2 * math.pi / p.z2
    whole = assemble_contact(model, contact.grids, contact.beta, contact.turn,
                             ColumnRule(probes=False))
    grids = tuple(turned_grid(g, pitches, p.z1, 2 * math.pi / p.z1) for g in contact.grids)
    there = assemble_contact(model, grids, beta, contact.turn + pitches * 2 * math.pi / p.z1,
                             ColumnRule(probes=False))
    moved = turned(model, whole, pitches, beta, None)
    assert [g.tooth for g in moved.grids] == [(g.tooth - pitches) % p.z1 for g in whole.grids]
    assert np.allclose(moved.x, there.x, rtol=0, atol=1e-12)
    assert np.allclose(moved.facing[0], there.facing[0], rtol=0, atol=1e-12)
    # a grid point on a facet's end takes either facet's length for its matching depth, as
    # rounding falls: A differs there by 1e-6 of its largest entry, nowhere else
    scale = np.abs(there.A).max()
    assert np.abs(moved.A - there.A).max() < 1e-5 * scale
    assert (np.abs(moved.A - there.A) > 1e-9 * scale).mean() < 0.01
    for gear in (0, 1):
        assert moved.loads[gear].keys() == there.loads[gear].keys()
        for k, block in there.loads[gear].items():
            assert np.array_equal(moved.loads[gear][k].dofs, block.dofs)
            assert np.allclose(moved.loads[gear][k].matrix, block.matrix, rtol=1e-9, atol=1e-12)
        assert np.array_equal(moved.matching[gear].at.sector, there.matching[gear].at.sector)


def test_a_deviated_pitch_on_the_kept_contact_takes_its_own_gaps(settled):
    model, contact = settled.model, settled.contact
    case = settled.case
    p = case.params
    loaded = max(settled.solution.pressure.nonzero()[0], key=lambda i: settled.solution.pressure[i])
    tooth = int(contact.teeth[loaded])
    dev = Deviations({(tooth - 1) % p.z1: ToothDeviation(pitch=5)})
    beta = case.beta + 2 * math.pi / p.z2
    moved = turned(model, contact, 1, beta, Placed(dev, p, beta))
    nominal = turned(model, contact, 1, beta, None)
    turn = p.ratio * beta + settled.solution.rotation
    g_dev = rigid_gap(model, moved, turn, moved.feet.copy())[0]
    g_nom = rigid_gap(model, nominal, turn, nominal.feet.copy())[0]
    on = moved.teeth == (tooth - 1) % p.z1
    # the tooth turned 5 µm into the mesh stands about 5 µm closer along its normal's share
    assert (g_nom[on] - g_dev[on]).max() == pytest.approx(5e-3, rel=0.3)
    assert np.abs(g_nom[~on] - g_dev[~on]).max() < 1e-12


@pytest.mark.parametrize("pitches", [0, 5])
def test_a_contact_turned_again_is_turned_once_and_each_call_keeps_its_own_feet(settled,
                                                                                 pitches):
    model, contact = settled.model, settled.contact
    p = model.case.params
    beta = contact.beta + pitches * 2 * math.pi / p.z2
    placed = Placed(Deviations({3: ToothDeviation(pitch=2)}), p, beta)
    turns = {}
    first = turned_again(turns, model, contact, pitches, beta, placed)
    first.feet[:] = 0.0   # a solve writes its feet
    again = turned_again(turns, model, contact, pitches, beta, None)
    once = turned(model, contact, pitches, beta, placed)
    assert list(turns) == [pitches]
    assert again.x is first.x and again.grids is first.grids   # turned once
    assert first.placed is placed and again.placed is None
    assert np.array_equal(again.feet, once.feet)                # not the first call's
    assert np.array_equal(first.x, once.x)
    assert [g.tooth for g in first.grids] == [g.tooth for g in once.grids]


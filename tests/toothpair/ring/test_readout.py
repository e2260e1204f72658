"""The brief stresses read off the ring's condensed unknowns (:mod:`fegear.toothpair.ring.
readout`): the root zones and the surface von Mises estimate the fields give, number for
number, without the fields; many samples' read together as each one's alone."""

import numpy as np
import pytest

from fegear.toothpair.ring.readout import SurfaceStrains, brief_stresses, brief_stresses_of
from fegear.toothpair.ring.stresses import ring_stresses


@pytest.fixture(scope="module")
def settled(baseline_200):
    return baseline_200.detail


def _pressures(settled):
    """The solved pressures, and pressures on every point of the first and last grids (more
    sectors loaded, hats at a grid's ends)."""
    contact, solved = settled.contact, settled.solution.pressure
    spread = np.zeros(contact.npoints)
    for k in (0, len(contact.grids) - 1):
        blk = contact.block(k)
        spread[blk] = 300.0 + 100.0 * np.sin(np.arange(blk.stop - blk.start))
    return [solved, spread]


@pytest.mark.parametrize("which", [0, 1])
def test_the_brief_stresses_are_the_fields_own(settled, which):
    model, contact = settled.model, settled.contact
    pressure = _pressures(settled)[which]
    full = ring_stresses(model, contact, pressure, submodels=False)
    brief = brief_stresses(model, contact, pressure, SurfaceStrains(model, contact))
    for g in (0, 1):
        assert np.allclose(brief.roots[g].angle, full.roots[g].angle, rtol=0, atol=1e-14)
        assert np.abs(brief.roots[g].s1 - full.roots[g].s1).max() < 1e-9 * full.roots[g].max
    assert np.abs(brief.surface - full.surface).max() < 1e-9 * full.surface.max()
    assert brief.fields == ({}, {}) and brief.submodels == ()
    # the bulk von Mises stress is the root zones': below the fields', which see the
    # contacts' near fields just beyond their reach
    assert 0 < brief.bulk_von_mises <= full.bulk_von_mises


def test_samples_read_together_are_each_one_read_alone(settled):
    # pressures loading different sectors (the solved ones, the first and last grids', one
    # loaded grid's alone, none): each column read with the others is its own reading, its
    # sectors its own (a sample that loads none has no root stress)
    model, contact = settled.model, settled.contact
    solved, spread = _pressures(settled)
    middle = np.zeros(contact.npoints)
    blk = next(contact.block(k) for k in range(len(contact.grids))
               if solved[contact.block(k)].any())
    middle[blk] = solved[blk]
    pressures = np.column_stack([solved, spread, middle, np.zeros(contact.npoints)])
    strains = SurfaceStrains(model, contact)
    together = brief_stresses_of(model, contact, pressures, strains)
    for k, brief in enumerate(together[:3]):
        alone = ring_stresses(model, contact, pressures[:, k], submodels=False)
        for g in (0, 1):
            np.testing.assert_allclose(brief.roots[g].angle, alone.roots[g].angle, atol=1e-14)
            assert np.abs(brief.roots[g].s1 - alone.roots[g].s1).max() < 1e-9 * alone.roots[g].max
        assert np.abs(brief.surface - alone.surface).max() < 1e-9 * alone.surface.max()
    assert len(together[2].roots[0].s1) < len(together[0].roots[0].s1)   # fewer sectors
    assert len(together[3].roots[0].s1) == 0 and together[3].bulk_von_mises == 0.0

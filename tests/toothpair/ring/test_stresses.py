"""A solved position's stresses (:mod:`fegear.toothpair.ring.stresses`): its root stresses the
largest of its teeth's, the contact half-width read off a Hertzian pressure, and the contact
and roots the same without the submodels."""

from dataclasses import replace

import numpy as np
import pytest

from fegear.toothpair import solve_positions
from fegear.toothpair.ring.stresses import local_half_width


def test_without_submodels_the_contact_and_roots_are_the_same(baseline_ring, baseline_200):
    # the relief search leaves the contact submodels out: everything it reads (loads,
    # pressures, edge loads, rotation) and the root stresses are those of the full solve;
    # only the von Mises stress at the contact falls back to the surface estimate
    case = replace(baseline_ring.case, torque=200.0)
    bare = solve_positions(case, (case.beta,), model=baseline_ring, submodels="none")[0]
    full = baseline_200
    assert bare.rotation == full.rotation and bare.root_stress == full.root_stress
    for a, b in zip(bare.teeth, full.teeth):
        assert (a.load_N, a.p_max_MPa, a.flank_p_MPa, a.edge_load_N, a.root1_MPa) == \
            (b.load_N, b.p_max_MPa, b.flank_p_MPa, b.edge_load_N, b.root1_MPa)
    assert not bare.detail.stresses.submodels and full.detail.stresses.submodels
    surface = float(bare.detail.stresses.surface.max())
    assert bare.von_mises_max == pytest.approx(max(surface,
                                                   bare.detail.stresses.bulk_von_mises))
    assert bare.von_mises_max == pytest.approx(full.von_mises_max, rel=0.05)


def test_a_position_s_root_stresses_are_the_largest_of_its_teeth(baseline_200):
    """The root stress a position reports per gear is the largest σ1 of the root zones it
    computed, and no tooth's (read within half a pitch of its tension fillet) exceeds it; on
    the baseline the largest is a loaded tooth's."""
    sol, stresses = baseline_200, baseline_200.detail.stresses
    assert sol.root_stress == (stresses.roots[0].max, stresses.roots[1].max)
    for gear, key in enumerate(("root1_MPa", "root2_MPa")):
        teeth = [getattr(t, key) for t in sol.teeth]
        assert max(teeth) == sol.root_stress[gear]
        zone = stresses.roots[gear]
        assert zone.max == zone.s1.max() and min(teeth) >= 0.0


@pytest.mark.parametrize("k", [1, 2, 3])
def test_the_half_width_of_a_hertzian_pressure_is_its_b(baseline_200, k):
    """A Hertzian pressure p0 √(1 − (s/b)²) laid on a loaded tooth's grid, over the middle 80 %
    of its loaded stretch: the half-width read off it (where it stays above half its peak,
    over √3) is b within a quarter of the grid's spacing there (a sixth to a quarter of b at
    `coarse`)."""
    d = baseline_200.detail
    blk, s = d.contact.block(k), d.contact.grids[k].s
    loaded = s[d.solution.pressure[blk] > 0]
    centre, b = 0.5 * (loaded[0] + loaded[-1]), 0.4 * (loaded[-1] - loaded[0])
    pressure = np.zeros(d.contact.npoints)
    pressure[blk] = 1000.0 * np.sqrt(np.clip(1.0 - ((s - centre) / b) ** 2, 0.0, None))
    peak = blk.start + int(np.argmax(pressure[blk]))
    spacing = np.diff(s)[np.abs(s[:-1] - centre) <= b].max()
    assert local_half_width(d.contact, pressure, peak) == pytest.approx(b, abs=0.25 * spacing)

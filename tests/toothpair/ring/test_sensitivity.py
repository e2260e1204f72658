"""The headlines' rates with the deviations (:mod:`fegear.toothpair.ring.sensitivity`): the
derivative of the bordered contact system with its active set kept is the finite difference
of the whole contact solve on the same grids, within 1 % (the issue's bound; about 1e-5
measured), for the pitch, profile slope and form of a tooth in mesh on either gear and for the
centre distance; a runout's is the largest over its phase; the mating teeth's pitches, which
bring the same flanks together, have one rate."""

import math
from dataclasses import replace

import numpy as np
import pytest

from fegear.geometry import Deviations, Placed, Runout, ToothDeviation
from fegear.toothpair.ring.contact import solve_ring_contact
from fegear.toothpair.ring.influence import ColumnRule, assemble_contact
from fegear.toothpair.ring.sensitivity import HEADLINES, pressure_headlines, solved_sensitivities

STEP = 0.05   # µm: the finite differences' half step


@pytest.fixture(scope="module")
def sens(baseline_200):
    return {s.name: s for s in solved_sensitivities(baseline_200)}


@pytest.fixture(scope="module")
def resolved(baseline_200):
    """The headlines of the whole contact solved again with deviations, on the same grids."""
    d = baseline_200.detail
    contact = assemble_contact(d.model, d.contact.grids, d.contact.beta, d.contact.turn,
                               ColumnRule())

    def solved(dev):
        c = replace(contact, placed=Placed(dev, d.case.params, contact.beta),
                    feet=contact.feet.copy())
        sol = solve_ring_contact(d.model, c, d.case.torque * 1e3, d.solution.rotation,
                                 start=d.solution.pressure > 0)
        return pressure_headlines(d.model, c, sol.pressure)
    return solved


def _tooth(gear, tooth, kind, um):
    return Deviations(**{f"gear{gear}": {tooth: ToothDeviation(**{kind: um})}})


@pytest.mark.parametrize("gear, tooth, kind", [(1, 10, "pitch"), (1, 11, "slope"),
                                               (1, 10, "form"), (2, 11, "pitch"),
                                               (2, 12, "form"), (None, None, "cd")])
def test_a_rate_is_the_finite_difference_of_the_whole_solve(sens, resolved, gear, tooth, kind):
    if kind == "cd":
        name, up, down = ("centre distance", Deviations(centre_distance=STEP),
                          Deviations(centre_distance=-STEP))
    else:
        name = f"gear {gear} tooth {tooth} {kind}"
        up, down = _tooth(gear, tooth, kind, STEP), _tooth(gear, tooth, kind, -STEP)
    hi, lo = resolved(up), resolved(down)
    rate = sens[name].per_um
    assert any(abs(rate[k]) > 1.0 for k in HEADLINES)   # a tooth in mesh: it moves them
    for key in HEADLINES:
        fd = (hi[key] - lo[key]) / (2 * STEP)
        assert rate[key] == pytest.approx(fd, rel=0.01, abs=0.01 * max(abs(fd), 1.0)), key


def test_a_runout_s_rate_is_the_largest_over_its_phase(sens, resolved):
    s = sens["gear 1 runout"]
    # per µm of F_r at the phase given (the eccentricity F_r/2 there), against a few others
    at = {}
    for phase in (s.phase_deg, s.phase_deg + 60.0, s.phase_deg + 180.0):
        hi = resolved(Deviations(runout1=Runout(2 * STEP, phase)))
        at[phase] = (hi["root_stress_gear1_MPa"] - resolved(Deviations())[
            "root_stress_gear1_MPa"]) / (2 * STEP)
    assert at[s.phase_deg] == pytest.approx(s.per_um["root_stress_gear1_MPa"], rel=0.02)
    assert at[s.phase_deg] > at[s.phase_deg + 60.0] > at[s.phase_deg + 180.0]
    assert np.isclose(at[s.phase_deg + 180.0], -at[s.phase_deg], rtol=0.05)


def test_mating_pitches_bring_the_same_flanks_together(sens, baseline_200):
    # gear 1's most loaded tooth turned forwards and the gear-2 tooth it presses turned back
    # are one relative motion of the two flanks: the same rate, within the lever arms' ratio
    loaded = max(baseline_200.teeth, key=lambda t: t.load_N)
    one = sens[f"gear 1 tooth {loaded.tooth} pitch"].per_um
    two = sens[f"gear 2 tooth {loaded.tooth2} pitch"].per_um
    for key in HEADLINES:
        assert one[key] == pytest.approx(two[key], rel=0.05, abs=0.2)
    assert math.isfinite(sens["gear 2 runout"].phase_deg)

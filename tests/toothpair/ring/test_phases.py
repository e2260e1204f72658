"""The ring's symmetry (:mod:`fegear.toothpair.ring.phases`): a contact assembled at β and
turned by whole pitches is the contact assembled there, number for number, and a revolution
solved on its phases' kept contacts is the one whose every position is placed and assembled
anew."""

import math

import numpy as np
import pytest

from fegear.geometry import Deviations, Placed, ToothDeviation, pitch_phase
from fegear.toothpair import prepare_job
from fegear.toothpair.case import HEADLINE
from fegear.toothpair.positions import drive
from fegear.toothpair.ring.contact import rigid_gap
from fegear.toothpair.ring.influence import ColumnRule, assemble_contact
from fegear.toothpair.ring.phases import Phases, turned, turned_grid
from fegear.toothpair.ring.solver import RingSolver, SolverModes


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


def test_phases_tell_the_place_within_a_pitch_and_the_pitch(baseline_ring):
    z2 = baseline_ring.case.params.z2
    pitch = 2 * math.pi / z2
    phase, k = pitch_phase(0.3 * pitch, z2)
    assert pitch_phase(0.3 * pitch + 5 * pitch, z2) == (phase, k + 5)
    assert pitch_phase(0.3 * pitch - 2 * pitch, z2) == (phase, k - 2)
    assert pitch_phase(0.31 * pitch, z2)[0] != phase


# A position placed anew has grids whose ends its own rotation sets, a deviated tooth's window
# widened by its deviation, probes on the teeth it does not expect to close; a phase's kept
# contact has fine grids on every paired tooth and one more either side, each as wide as the
# largest deviation needs. Both are grids of the same rule, where a round's tangent point
# inside a wider window refines the grid about it. Measured at `coarse`: the perfect pair
# 2e-4 at most; deviated (5 µm on tooth 11; a 6 µm runout with 4 µm less centre distance),
# roots 3.4e-4 / 7.4e-4, peaks on a round 1.2e-3 / 1.6e-3, each tooth's load 4e-4 of the
# torque's, and the flank pressure 1.8e-2 / 2.3e-2 where it is a light tooth's (the deviated
# tooth touching alone on the ring's far side under 209 N, 4 % of the load, few points across
# its contact at `coarse`: its own error estimate covers it).
AGREE = {"root_stress_gear1_MPa": (3e-4, 1e-3), "root_stress_gear2_MPa": (3e-4, 1e-3),
         "contact_pressure_MPa": (3e-4, 2e-3), "von_mises_max_MPa": (3e-4, 2e-3),
         "flank_contact_pressure_MPa": (3e-4, 3e-2)}


def _revolution(inputs, keep_phases):
    job = prepare_job({"shift": 0.016, "rotation": 0.002, "quality": "coarse",
                       "revolution": True, "positions": 2, "no-estimate": True, **inputs})
    solver = RingSolver(None, SolverModes(keep_phases=keep_phases))
    return drive(job.case, job.betas, solver), solver


# the deviated revolutions slow (8-16 s each): in the default run a deviated revolution's worst
# position is checked against a solve there placed anew (tests/toothpair/analyses/test_revolution.py)
@pytest.mark.parametrize("deviated, inputs", [
    (0, {}),
    pytest.param(1, {"pitch-deviation": ["1:11=5"]}, marks=pytest.mark.slow),
    pytest.param(1, {"runout": ["1=6@30"], "centre-distance-deviation": -4},
                 marks=pytest.mark.slow)])
def test_a_revolution_on_kept_phases_is_the_one_placed_anew(deviated, inputs):
    kept, solver = _revolution(inputs, True)
    anew, _ = _revolution(inputs, False)
    assert len(solver.phases) == 2
    for a, b in zip(kept, anew):
        total = sum(t.load_N for t in b.teeth)
        loads = {t.tooth: t.load_N for t in b.teeth if t.load_N > 0}
        assert {t.tooth: t.load_N for t in a.teeth if t.load_N > 0} == pytest.approx(
            loads, abs=1e-3 * total)
        for key in HEADLINE:
            assert a.headline()[key] == pytest.approx(b.headline()[key],
                                                      rel=AGREE[key][deviated]), key


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


def test_a_pitch_renumbered_is_the_pitch_solved_on_its_phase(monkeypatch):
    # where the deviations move only open points, the last solution of the phase meets this
    # pitch's contact conditions, and the positive definite compliance admits no other
    checked = []
    repeat = Phases.repeat

    def solved_too(self, model, case, state):
        out = repeat(self, model, case, state)
        if out is not None:
            solved = self.solve(model, case, state)
            assert solved is not None
            checked.append((out, solved[1]))
        return out

    monkeypatch.setattr(Phases, "repeat", solved_too)
    _revolution({"pitch-deviation": ["1:11=5"]}, True)
    assert len(checked) > 40
    for out, sol in checked:
        assert sol.rotation == pytest.approx(out.rotation, rel=1e-9)
        top = sol.pressure.max()
        assert np.abs(sol.pressure - out.detail.solution.pressure).max() < 1e-7 * top


def test_pitches_that_see_the_same_deviations_are_one_contact_problem(settled):
    from fegear.geometry import Runout
    from fegear.toothpair.ring.phases import Kept, seen_teeth

    contact = settled.contact
    p = settled.case.params
    teeth = seen_teeth(contact, p.z2)
    assert teeth[0] == tuple(g.tooth for g in contact.grids)
    under = np.round(contact.feet * p.z2 / (2 * math.pi)).astype(int) % p.z2
    assert set(under) < set(teeth[1])          # one either side too
    kept = Kept(0, contact, 0.0, np.zeros(contact.npoints, bool), 1.0, {}, teeth)
    z = (p.z1, p.z2)
    far = (teeth[0][0] + p.z1 // 2) % p.z1     # a gear-1 tooth far from the kept contact
    dev = Deviations({far: ToothDeviation(pitch=5)})
    exact = kept.seen(Deviations(), 0, z)
    assert kept.seen(dev, 0, z) == exact
    # turned on until the deviated tooth stands where the kept contact's first grid is
    pitches = (teeth[0][0] - far) % p.z1
    assert kept.seen(dev, pitches, z) != exact
    assert kept.seen(dev, pitches, z) == kept.seen(dev, pitches + p.z1, z)
    mate = Deviations(gear2={(teeth[1][0] - 3) % p.z2: ToothDeviation(slope=2)})
    assert kept.seen(mate, 0, z) == exact and kept.seen(mate, 3, z) != exact
    # a runout's offset turns with its gear: no two pitches are known to be alike
    assert kept.seen(Deviations(runout1=Runout(6, 30)), 0, z) is None

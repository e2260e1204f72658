"""The ring's symmetry used (:mod:`fegear.toothpair.ring.phases`): a revolution solved on its
phases' kept contacts is the one whose every position is placed and assembled anew, and a
pitch that repeats or sees the deviations of one solved is that one renumbered."""

import math

import numpy as np
import pytest

from fegear.geometry import Deviations, ToothDeviation, pitch_phase
from fegear.toothpair import prepare_job
from fegear.toothpair.case import HEADLINE, phase_major
from fegear.toothpair.positions import drive
from fegear.toothpair.ring import RingSolver, SolverModes
from fegear.toothpair.ring.phases import Phases


@pytest.fixture(scope="module")
def settled(baseline_200):
    return baseline_200.detail


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
# position is checked against a solve there placed anew
# (tests/toothpair/analyses/test_revolution.py)
@pytest.mark.parametrize("deviated, inputs", [
    pytest.param(0, {}, marks=pytest.mark.slow),   # 11 s: the perfect pair's turn
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


def test_a_phase_after_a_solved_one_is_kept_at_once(monkeypatch):
    """A phase's first position after a solved one is kept about that one's rotation: the
    grids of its own, which the kept ones would replace, are never placed; and it is the
    position placed anew within the kept contacts' agreement (:data:`AGREE`)."""
    import fegear.toothpair.ring.solver as ring_solver

    placed = []
    place = ring_solver.place_grids
    monkeypatch.setattr(ring_solver, "place_grids",
                        lambda *a, **k: placed.append(a[1].beta) or place(*a, **k))
    job = prepare_job({"shift": 0.016, "rotation": 0.002, "quality": "coarse", "z2": 25,
                       "z1": 24, "pitch-deviation": ["1:11=5"], "no-estimate": True})
    betas = [0.0, 0.4 * 2 * math.pi / 25]            # two phases, one chain
    solver = RingSolver(None, SolverModes(keep_phases=True))
    kept = drive(job.case, betas, solver)
    assert len(solver.phases) == 2
    assert betas[0] in placed and betas[1] not in placed
    anew = drive(job.case, betas, RingSolver(None, SolverModes()))
    for key in HEADLINE:
        assert kept[1].headline()[key] == pytest.approx(anew[1].headline()[key],
                                                        rel=AGREE[key][1]), key


def test_positions_read_on_kept_contacts_are_the_ones_formed_whole():
    """A revolution's positions on kept contacts read without their fields
    (:attr:`~fegear.toothpair.ring.solver.SolverModes.read_kept`) are those formed whole:
    headlines, loads, rotations and stiffness to rounding. None of them holds fields or
    half-plane references; the pictured one (the largest gear-1 root stress) is then formed
    whole (its fields, references and equilibrium residuals), and the cycle's peaks get their
    submodels, as the whole ones do."""
    job = prepare_job({"shift": 0.016, "rotation": 0.002, "quality": "coarse", "z2": 25,
                       "z1": 24, "pitch-deviation": ["1:11=5"], "runout": ["1=4@0"],
                       "revolution": True, "positions": 2, "no-estimate": True})
    # two places, each over its first five pitches (a runout: no pitch repeats another)
    betas = [job.betas[k] for k in phase_major(len(job.betas), 24) if k // 2 < 5]
    whole_solver = RingSolver(None, SolverModes(keep_phases=True))
    whole = drive(job.case, betas, whole_solver)
    solver = RingSolver(None, SolverModes(keep_phases=True, read_kept=True))
    read = drive(job.case, betas, solver)
    assert not any(any(s.detail.stresses.fields) for s in read)
    for a, b in zip(read, whole, strict=True):
        for key in HEADLINE:
            assert a.headline()[key] == pytest.approx(b.headline()[key], rel=1e-9), key
        assert [t.load_N for t in a.teeth] == pytest.approx([t.load_N for t in b.teeth])
        assert [t.root1_MPa for t in a.teeth] == pytest.approx([t.root1_MPa for t in b.teeth])
        assert (a.rotation, a.first_touch, a.tangent_stiffness) == pytest.approx(
            (b.rotation, b.first_touch, b.tangent_stiffness), rel=1e-12)
    k = max(range(len(read)), key=lambda i: read[i].root_stress[0])
    assert all(t.halfplane_flank_MPa is None for t in read[k].teeth)
    assert any(t.halfplane_flank_MPa for t in whole[k].teeth)
    pictured = solver.with_pictured(read)
    assert [p is r for p, r in zip(pictured, read)].count(False) == 1
    assert any(pictured[k].detail.stresses.fields)
    for a, b in zip(pictured[k].teeth, whole[k].teeth, strict=True):
        assert (a.halfplane_p_MPa, a.halfplane_flank_MPa, a.bending_curvature) == \
            pytest.approx((b.halfplane_p_MPa, b.halfplane_flank_MPa, b.bending_curvature))
    read, whole = solver.at_peaks(pictured), whole_solver.at_peaks(whole)
    assert read[k].detail.stresses.submodels
    assert read[k].checks.residuals == pytest.approx(whole[k].checks.residuals, abs=1e-12)
    assert read[k].von_mises_max == pytest.approx(whole[k].von_mises_max, rel=1e-9)
    assert [s.von_mises_estimated for s in read] == [s.von_mises_estimated for s in whole]


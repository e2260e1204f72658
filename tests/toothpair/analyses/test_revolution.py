"""A whole revolution of gear 1 (``fegear solve --revolution``): a perfect pair gives every
tooth the same stresses and a rotation of mesh orders only; a deviated tooth is the worst, at
the position a single solve there agrees with; a gear-1 runout turns the rotation's first
order with its phase; the files hold what the summary says."""

import csv
import math
from dataclasses import replace

import numpy as np
import pytest

from fegear.geometry import Deviations, Placed, Runout, ToothContact, gear1_profile
from fegear.toothpair import prepare_job, solve_job_positions, solve_pair
from fegear.toothpair.analyses import Writing
from fegear.toothpair.analyses.revolution.report import revolution_table, write_revolution_outputs
from fegear.toothpair.analyses.revolution.solve import amplitudes, loaded_rotation
from fegear.toothpair.case import phase_major, revolution_positions
from fegear.toothpair.job import solve_job

BASE = {"shift": 0.016, "rotation": 0.002, "quality": "coarse", "revolution": True,
        "positions": 2, "no-estimate": True}
DEVIATED = {**BASE, "pitch-deviation": ["1:11=5"], "runout": ["1=4@0"]}


@pytest.fixture(scope="module")
def perfect():
    return solve_job(prepare_job(BASE))


@pytest.fixture(scope="module")
def deviated():
    return solve_job(prepare_job(DEVIATED))


def _spread(values: dict, cut=()) -> float:
    v = np.array([x for t, x in values.items() if t not in cut])
    return (v.max() - v.min()) / v.max()


def test_a_revolution_covers_one_turn_of_gear_1(perfect):
    p = perfect.job.case.params
    betas = perfect.job.betas
    assert len(betas) == 2 * p.z1
    assert math.isclose((betas[-1] + betas[1] - 2 * betas[0]) * p.z2 / p.z1, 2 * math.pi)
    assert betas == revolution_positions(0.0, 2, p.z1, p.z2)
    # solved phase by phase, handed back in the order of the rolling angles
    assert [s.case.beta for s in perfect.solutions] == list(betas)
    assert phase_major(6, 3) == [0, 2, 4, 1, 3, 5]


def test_a_perfect_pair_gives_every_tooth_the_same_largest_stresses(perfect):
    per = perfect.summary["revolution"]["per_tooth"]
    p = perfect.job.case.params
    # gear 1 turns once against identical teeth: its pass repeats, none is cut
    assert per["cut"]["gear1"] == [] and len(per["root_stress_gear1_MPa"]) == p.z1
    # each position settles to the contact's tolerance from the one before: the roots agree
    # to 1e-4, the peak pressure on a tip round to 1e-3
    cut = per["cut"]["gear2"]
    for key, tol, skip in (("root_stress_gear1_MPa", 1e-4, ()),
                           ("contact_pressure_MPa", 1e-3, ()),
                           ("root_stress_gear2_MPa", 1e-4, cut)):
        assert _spread(per[key], skip) < tol, key
    # gear 2 turns z1/z2 of a turn: the teeth the ends cut are seen in part, below the rest
    whole = max(v for t, v in per["root_stress_gear2_MPa"].items() if t not in cut)
    assert cut and min(per["root_stress_gear2_MPa"][t] for t in cut) < whole * (1 - 1e-3)


def test_a_perfect_pairs_rotation_holds_only_mesh_orders(perfect):
    z1 = perfect.job.case.params.z1
    a = amplitudes(loaded_rotation(perfect.solutions))
    mesh = a[z1]
    assert mesh > 1.0   # µrad: the mesh's own stiffness variation
    others = [h for h in range(1, len(a)) if h % z1]
    assert max(a[h] for h in others) < 1e-3 * mesh


def test_the_deviated_tooth_is_the_worst_and_the_worst_is_a_solve_there(deviated):
    rev = deviated.summary["revolution"]
    worst = rev["worst"]["root_stress_gear1_MPa"]
    assert (worst["gear"], worst["tooth"]) == (1, 11)
    per = rev["per_tooth"]["root_stress_gear1_MPa"]
    assert per[11] > 1.2 * float(np.median(list(per.values())))
    # a gear-1 runout: gear 2 is perfect, so gear 1's passes are whole
    assert rev["per_tooth"]["cut"]["gear1"] == []
    # the position of the worst, solved on its own, gives the same stress: the revolution
    # solved it on its phase's kept grids, wider than its own (tests/toothpair/ring/
    # test_phases.py: roots within 5e-4 of a position placed anew)
    sol = max(deviated.solutions, key=lambda s: s.headline()["root_stress_gear1_MPa"])
    assert math.degrees(sol.case.beta) == pytest.approx(worst["at_position_deg"])
    alone = solve_pair(sol.case)
    assert alone.headline()["root_stress_gear1_MPa"] == pytest.approx(worst["max"], rel=5e-4)
    text = revolution_table(rev)
    assert "1:11" in text and "most loaded tooth 11" in text


def test_a_deviated_revolution_is_not_the_perfect_one_beyond_its_teeth(perfect, deviated):
    # the 4 µm runout's first order dominates the deviated rotation; the perfect has none
    a = amplitudes(loaded_rotation(deviated.solutions))
    b = amplitudes(loaded_rotation(perfect.solutions))
    assert a[1] > 10.0 and b[1] < 1e-3
    assert _largest_order(deviated) == 1


def test_a_jobs_positions_are_a_revolution_solved_as_the_job_does(perfect, deviated):
    # the design search's and the relief's nominal pair: the same driver as `fegear solve
    # --revolution`, so a perfect pair's pitches repeat its first (renumbered, not solved
    # again) and a deviated pair's positions are the job's
    sols = solve_job_positions(deviated.job, submodels="none")
    for a, b in zip(sols, deviated.solutions, strict=True):
        assert a.case.beta == b.case.beta and a.rotation == b.rotation
        assert np.array_equal(a.root_stress, b.root_stress)
        assert [t.p_max_MPa for t in a.teeth] == [t.p_max_MPa for t in b.teeth]
    job = perfect.job
    sols = solve_job_positions(job, submodels="none")
    per = len(job.betas) // job.case.params.z1
    for a, b in zip(sols, sols[per:]):
        assert a.headline()["root_stress_gear1_MPa"] == b.headline()["root_stress_gear1_MPa"]
        assert a.rotation == b.rotation


def _largest_order(solved) -> int:
    """The order of the largest harmonic of a revolution's summary."""
    return max(solved.summary["revolution"]["spectrum"],
               key=lambda h: h["amplitude_urad"])["order"]


def _first_touch(params, dev: Deviations, betas) -> np.ndarray:
    """The unloaded first touch (µm of arc at r0) at each of ``betas``: the smallest loaded-side
    clearance of any tooth with the deviations."""
    states = ToothContact(params, gear1_profile(params)).states(betas, directions=(+1,))
    return np.array([min(t.plus_um for t in Placed(dev, params, b).clearances(st).teeth
                         if t.plus_um is not None) for b, st in zip(betas, states)])


def test_a_gear_1_runout_turns_the_first_order_with_its_phase(perfect):
    # 88 positions a turn: a quarter turn of the runout's high point is 22 positions later
    params = perfect.job.case.params
    betas = perfect.job.betas
    at0 = _first_touch(params, Deviations(runout1=Runout(4.0, 0.0)), betas)
    at90 = _first_touch(params, Deviations(runout1=Runout(4.0, 90.0)), betas)
    assert np.allclose(np.roll(at0, len(betas) // 4), at90, atol=1e-6) or \
        np.allclose(np.roll(at0, -len(betas) // 4), at90, atol=1e-6)
    # its first order: the eccentricity (2 µm) moves the teeth at the mesh by up to 2 µm,
    # along the flank's normal at most 2 µm / cos of its pressure angle
    first = amplitudes(at0)[1]
    assert 1.0 < first < 2.0 / math.cos(math.radians(60))


def test_the_files_hold_what_the_summary_says(deviated, tmp_path):
    rev = deviated.summary["revolution"]
    files = write_revolution_outputs(rev, Writing(deviated, tmp_path, "a title", fields=False))
    with open(files["revolution_csv"]) as f:
        rows = list(csv.DictReader(f))
    assert len(rows) == len(deviated.solutions)
    turn = [float(r["gear1_turn_deg"]) for r in rows]
    assert turn[0] == 0.0 and 355.0 < turn[-1] < 360.0
    with open(files["revolution_teeth_csv"]) as f:
        teeth = {(int(r["gear"]), int(r["tooth"])): float(r["root_stress_MPa"])
                 for r in csv.DictReader(f)}
    assert teeth[(1, 11)] == pytest.approx(rev["worst"]["root_stress_gear1_MPa"]["max"])
    with open(files["revolution_spectrum_csv"]) as f:
        spectrum = {int(r["order"]): float(r["amplitude_urad"]) for r in csv.DictReader(f)}
    for h in rev["spectrum"]:
        assert spectrum[h["order"]] == pytest.approx(h["amplitude_urad"])
    for name in ("revolution_png", "revolution_teeth_png"):
        assert files[name].stat().st_size > 10_000


def test_the_series_has_a_frame_a_pitch_at_its_largest_root_stress(deviated, tmp_path):
    # two pitches of the revolution, as the writer takes them
    sols, rows = deviated.solutions[:4], deviated.rows[:4]
    rev = {**deviated.summary["revolution"], "pitches": 2}
    files = write_revolution_outputs(rev, Writing(replace(deviated, solutions=sols, rows=rows),
                                                  tmp_path, "t", pictures=False))
    pvd = files["revolution_pvd"].read_text()
    steps = sorted({float(x.split('"')[1]) for x in pvd.split("timestep=")[1:]})
    want = [math.degrees(max(sols[k:k + 2], key=lambda s: s.headline()[
        "root_stress_gear1_MPa"]).case.beta) for k in (0, 2)]
    assert steps == pytest.approx(want)
    assert len(list((tmp_path / "revolution").glob("*.vtu"))) == 4   # 2 frames, 2 gears



def test_the_chains_hand_back_details_only_where_they_are_read():
    # each pitch's largest gear-1 root stress (the series) and the peaks keep their details
    # (the contact, the stresses); the other positions come back with their numbers alone
    from fegear.running import SERIAL
    from fegear.toothpair.positions import positions_of
    from fegear.toothpair.ring import RingSolver, SolverModes

    job = prepare_job({**BASE, "z2": 25, "z1": 24, "positions": 4,
                       "pitch-deviation": ["1:11=5"]})
    solver = RingSolver(None, SolverModes(keep_phases=True, read_kept=True))
    sols = positions_of(solver, True)(job.case, job.betas, SERIAL)
    peaks = [k + max(range(4), key=lambda i: sols[k + i].root_stress[0])
             for k in range(0, len(sols), 4)]
    assert all(sols[k].detail is not None for k in peaks)
    light = [s for s in sols if s.detail is None]
    assert len(light) >= len(sols) // 3 and all(s.teeth and s.headline() for s in light)
    pictured = solver.at_peaks(solver.with_pictured(sols))   # what is read after the chains
    assert sum(not s.von_mises_estimated for s in pictured) >= 1

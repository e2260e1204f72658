"""A load spectrum's levels (``fegear solve --spectrum``): each level is the pair solved at
that torque (none scaled; the lighter ones on the heaviest one's contact at each position),
Miner's sum read back from the levels' stresses and the S-N line agrees with the summary's,
and bad spectra are refused before anything is written."""

import math
from dataclasses import replace

import pytest
from in_process import fegear

from fegear.rating import BENDING, CONTACT, GearMaterial, rate
from fegear.toothpair import prepare_job, solve_job
from fegear.toothpair.analyses import RATING
from fegear.toothpair.analyses.rating.report import rating_rows, rating_table
from fegear.toothpair.positions import drive, drive_torques, families
from fegear.toothpair.ring.solver import RingSolver, SolverModes

SPECTRUM = "torque,cycles\n60,1e8\n120,5e6\n160,3e5\n200,2e4\n"
#: a material weak enough that every mode takes damage from the spectrum
WEAK = 'treatment = "through-hardened"\nsigma_Hlim = 480\nsigma_FE = 220\n'
BASE = {"quality": "coarse", "positions": 4, "no-estimate": True}
#: the levels' solver: the roots and the pressures read alone
ROOTS = SolverModes(roots_only=True)


@pytest.fixture(scope="module")
def rated(tmp_path_factory):
    folder = tmp_path_factory.mktemp("spectrum")
    (folder / "duty.csv").write_text(SPECTRUM)
    (folder / "weak.toml").write_text(WEAK)
    job = prepare_job({**BASE, "spectrum": str(folder / "duty.csv"), "speed": 1500.0,
                       "KA": 1.25, "material": str(folder / "weak.toml")})
    return solve_job(job).summary["rating"]


def test_each_level_is_the_pair_solved_at_its_torque(rated):
    # the heaviest level is placed and settled as the pair alone is: the same numbers; a
    # lighter one is solved on its contact at each position, on grids up to twice as coarse as
    # its own: the same within the grids' sampling of the peaks (measured 8e-4 on the roots and
    # 0.5 % on the pressures)
    heaviest = max(level["solved_torque_Nm"] for level in rated["levels"])
    for level in rated["levels"][::3]:   # 75 and 250 N·m
        torque = level["solved_torque_Nm"]
        alone = solve_job(prepare_job({**BASE, "torque": torque}))
        assert torque == pytest.approx(1.25 * level["torque_Nm"])
        rows = alone.summary["cycle"]["rows"]
        roots, pressures = (1e-9, 1e-9) if torque == heaviest else (2e-3, 1e-2)
        assert level["root1_MPa"] == pytest.approx(max(r["root_stress_gear1_MPa"]
                                                       for r in rows), rel=roots)
        assert level["root2_MPa"] == pytest.approx(max(r["root_stress_gear2_MPa"]
                                                       for r in rows), rel=roots)
        assert level["flank1_MPa"] == pytest.approx(max(
            t.flank_p_MPa for sol in alone.solutions for t in sol.teeth), rel=pressures)


def test_a_level_at_the_cycles_torque_is_the_cycle(tmp_path):
    # 160 N·m times KA 1.25 is the solve's own 200 N·m: the rating reads the cycle's numbers,
    # those of the static verdict, not a second solve's
    (tmp_path / "duty.csv").write_text(SPECTRUM)
    solved = solve_job(prepare_job({**BASE, "spectrum": str(tmp_path / "duty.csv"),
                                    "KA": 1.25}))
    level = solved.summary["rating"]["levels"][2]
    assert level["solved_torque_Nm"] == solved.job.case.torque
    assert level["root1_MPa"] == max(s.root_stress[0] for s in solved.solutions)
    assert level["flank1_MPa"] == max(t.flank_p_MPa for s in solved.solutions
                                      for t in s.teeth)


@pytest.fixture(scope="module")
def coarse_cycle():
    job = prepare_job(BASE)
    return job.case, job.betas


def test_the_lighter_levels_are_solved_on_the_heaviest_ones_contact(coarse_cycle):
    # 75 N·m is within a quarter of 250 and shares its contacts; 20 N·m is not, and is the
    # pair solved alone at its torque
    case, betas = coarse_cycle
    sols = drive_torques(case, betas, [250.0, 75.0, 20.0], RingSolver(None, ROOTS))
    assert [s.case.torque for s in sols[1]] == [75.0] * len(betas)
    for heavy, light, least in zip(*sols):
        assert light.detail.contact.grids is heavy.detail.contact.grids
        assert least.detail.contact.grids is not heavy.detail.contact.grids
    alone = drive(replace(case, torque=20.0), betas,
                  RingSolver(sols[0][0].detail.model, ROOTS))
    for a, b in zip(sols[2], alone):
        assert a.root_stress == pytest.approx(b.root_stress, rel=1e-12)
        assert a.rotation == pytest.approx(b.rotation, rel=1e-12)


class _Refusing(RingSolver):
    """A ring solver whose contacts hold no other torque."""

    def again(self, case, state, attempt):
        return None


def test_a_torque_the_contact_does_not_hold_is_solved_as_alone(coarse_cycle):
    case, betas = coarse_cycle
    sols = drive_torques(case, betas, [250.0, 75.0], _Refusing(None, ROOTS))
    alone = drive(replace(case, torque=75.0), betas,
                  RingSolver(sols[0][0].detail.model, ROOTS))
    for a, b in zip(sols[1], alone):
        assert a.root_stress == pytest.approx(b.root_stress, rel=1e-12)
        assert max(t.flank_p_MPa for t in a.teeth) == pytest.approx(
            max(t.flank_p_MPa for t in b.teeth), rel=1e-12)


def test_torques_go_by_families_of_a_quarter_of_their_heaviest():
    assert families([60.0, 120.0, 160.0, 200.0]) == [[3, 2, 1, 0]]
    assert families([10.0, 100.0, 30.0, 20.0]) == [[1, 2], [3, 0]]
    assert families([50.0]) == [[0]]


def material_of(text: str) -> GearMaterial:
    values = dict(line.split(" = ") for line in text.strip().splitlines())
    return GearMaterial("weak", values["treatment"].strip('"'), float(values["sigma_Hlim"]),
                        float(values["sigma_FE"]), "test")


def test_miners_sum_read_back_from_the_levels_stresses(rated):
    steel = material_of(WEAK)
    z1, z2 = 44, 45
    cycles = [float(line.split(",")[1]) for line in SPECTRUM.splitlines()[1:]]
    for mode, key, limit, curve, per in (
            ("bending gear 1", "root1_MPa", steel.sigma_FE, BENDING, 1.0),
            ("bending gear 2", "root2_MPa", steel.sigma_FE, BENDING, z1 / z2),
            ("pitting gear 1", "flank1_MPa", steel.sigma_Hlim, CONTACT, 1.0)):
        line = curve[steel.treatment]
        total = 0.0
        for level, n in zip(rated["levels"], cycles):
            ratio = level[key] / limit
            if ratio <= 1.0:
                continue
            assert ratio <= line.static
            # the line through the table's first point and its knee, read in logs
            lasts = line.knee * math.exp(-math.log(ratio) / math.log(line.static)
                                         * math.log(line.knee / line.first))
            total += n * per / lasts
        m = rated["modes"][mode]
        assert total > 0, mode   # the weak material: every mode is damaged
        assert m["miner"] == pytest.approx(total, rel=1e-9), mode
        hours = sum(cycles) / (1500.0 * 60.0)
        if total > 0:
            assert m["life_h"] == pytest.approx(hours / total, rel=1e-9)


def test_the_verdict_names_the_smallest_safety_factor(rated):
    worst = min(rated["modes"].items(), key=lambda kv: kv[1]["safety"])
    assert worst[0] in rated["verdict"]
    assert rated["verdict"].startswith("PASS" if worst[1]["miner"] <= 1 else "FAIL")
    assert "weak" in rating_table(rated)
    assert len(rating_rows(rated)) == 4 * len(rated["modes"])


def _solve(tmp_path, capsys, *args):
    """``fegear solve`` in this process (tests/in_process.py: a process of its own cost 1 s a
    test; tests/cli/test_cli.py starts one for a user error of solve's)."""
    out = tmp_path / "out"
    return fegear(capsys, "solve", "--quality", "coarse", "--no-estimate", *args, "--out",
                  str(out)), out


@pytest.mark.parametrize("text, args, fragment", [
    ("", ["--positions", "4"], "at least one level"),
    ("torque,cycles\n100,-3\n", ["--positions", "4"], "cycles >= 0 at line 2"),
    ("torque,cycles\n100000,3\n", ["--positions", "4"], "the most the pair takes"),
    ("torque,share\n100,1\n", ["--positions", "4"], "--speed and --life"),
    ("torque,cycles\n100,3\n", ["--positions", "4", "--pitch-deviation", "1:11=5"],
     "with --revolution for a pair with deviations"),
])
def test_bad_spectra_exit_2_with_one_line_and_nothing_written(tmp_path, capsys, text, args,
                                                              fragment):
    path = tmp_path / "duty.csv"
    path.write_text(text)
    r, out = _solve(tmp_path, capsys, "--spectrum", str(path), *args)
    assert r.code == 2, r.lines
    assert len(r.lines) == 1 and "--spectrum" in r.lines[0] and fragment in r.lines[0], r.lines
    assert not out.exists()


def test_a_spectrum_without_positions_takes_the_default_cycle_and_says_so(tmp_path):
    # a rating always needs a cycle: without --positions or --revolution it takes one
    # pitch's 24 positions, and the summary says it chose them (issue 67)
    from fegear.toothpair.job import PER_PITCH, RATING_CYCLE

    (tmp_path / "duty.csv").write_text("torque,cycles\n100,1e6\n")
    job = prepare_job({"quality": "coarse", "no-estimate": True,
                       "spectrum": str(tmp_path / "duty.csv")})
    assert job.betas == prepare_job({"quality": "coarse", "positions": PER_PITCH}).betas
    assert PER_PITCH == 24 and RATING_CYCLE.startswith("24 positions over one pitch")
    cycle = solve_job(job).summary["cycle"]
    assert cycle["positions"] == 24 and cycle["default"] == RATING_CYCLE
    assert "default" not in solve_job(prepare_job(BASE)).summary["cycle"]   # one given


def test_the_rating_options_want_a_spectrum(tmp_path, capsys):
    r, out = _solve(tmp_path, capsys, "--positions", "4", "--KA", "1.5")
    assert r.code == 2 and len(r.lines) == 1, r.lines
    assert "--KA = 1.5" in r.lines[0] and "with --spectrum only" in r.lines[0]
    assert not out.exists()


def test_an_unloaded_mode_reads_as_an_unlimited_factor():
    # a mode no level loads has no limit: its safety factor is "inf" in the summary (JSON
    # has no infinity) and ∞ in the table
    from fegear.rating import material
    from fegear.toothpair.analyses.rating.solve import json_ready

    modes = rate([{"root1": {None: 100.0}, "root2": {None: 0.0}, "flank1": {None: 300.0},
                   "flank2": {None: 300.0}}], [1e6], (44, 45), material("42CrMo"))
    rated = json_ready({"material": {"name": "42CrMo", "treatment": "through-hardened",
                                  "sigma_Hlim_MPa": 745.0, "sigma_FE_MPa": 558.0,
                                  "source": "s"}, "KA": 1.0, "KV": 1.0,
                     "levels": [{"torque_Nm": 10.0, "solved_torque_Nm": 10.0, "cycles": 1e6,
                                 "root1_MPa": 100.0, "root2_MPa": 0.0, "flank1_MPa": 300.0}],
                     **modes})
    assert rated["modes"]["bending gear 2"]["safety"] == "inf"
    row = next(x for x in rating_table(rated).splitlines() if x.startswith("| bending gear 2"))
    assert row.endswith("| ∞ |")


def test_over_a_revolution_the_deviated_tooth_limits(tmp_path):
    # tooth 11 of gear 1 stands 5 µm ahead: it carries more, and its root and flank are the
    # ones that wear first (a revolution rates every tooth over its whole pass)
    (tmp_path / "duty.csv").write_text(SPECTRUM)
    (tmp_path / "weak.toml").write_text(WEAK)
    job = prepare_job({"quality": "coarse", "no-estimate": True, "revolution": True,
                       "positions": 2, "pitch-deviation": "1:11=5",
                       "spectrum": str(tmp_path / "duty.csv"),
                       "material": str(tmp_path / "weak.toml")})
    rated = solve_job(job).summary["rating"]
    assert not rated["every_tooth"]
    for mode in ("bending gear 1", "pitting gear 1"):
        assert rated["modes"][mode]["tooth"] == 11, mode
    name, worst = min(rated["modes"].items(), key=lambda kv: kv[1]["safety"])
    assert f"{name} (tooth {worst['tooth']})" in rated["verdict"]


def test_over_a_revolution_the_lighter_levels_are_solved_on_the_heaviest_ones_phases(
        tmp_path, monkeypatch):
    # over a revolution the heaviest level keeps each phase's contact; the lighter one is
    # solved on those contacts (none kept at its torque), its own pitches repeated, and
    # agrees with the level rated over the revolution alone within the grids' sampling
    # (neither level at the job's own 200 N·m, which the rating reads from the job's solve)
    from fegear.toothpair.ring import solver
    from fegear.toothpair.ring.phases import Phases

    keeps, placed = [], []
    keep, place = Phases.keep, solver.place_grids

    def counted(self, model, case, *args, **kwargs):
        kept = keep(self, model, case, *args, **kwargs)
        keeps.append((case.torque, kept is not None))
        return kept

    def placing(model, case, *args, **kwargs):
        placed.append(case.torque)
        return place(model, case, *args, **kwargs)

    monkeypatch.setattr(Phases, "keep", counted)
    monkeypatch.setattr(solver, "place_grids", placing)

    def levels(spectrum: str) -> list[dict]:
        folder = tmp_path / str(len(keeps))
        folder.mkdir()
        (folder / "duty.csv").write_text(spectrum)
        return solve_job(prepare_job({**BASE, "revolution": True, "positions": 2,
                                      "pitch-deviation": "1:11=5",
                                      "spectrum": str(folder / "duty.csv")})
                         ).summary["rating"]["levels"]

    both = levels("torque,cycles\n150,5e6\n250,2e4\n")
    assert {torque for torque, kept in keeps if kept} == {200.0, 250.0}   # the job's, the head's
    assert 150.0 not in placed and 250.0 in placed
    alone = levels("torque,cycles\n150,5e6\n")[0]
    assert 150.0 in placed and (150.0, True) in keeps
    light = next(level for level in both if level["solved_torque_Nm"] == 150.0)
    for key in ("root1_MPa", "root2_MPa"):
        assert light[key] == pytest.approx(alone[key], rel=2e-3), key
    for key in ("flank1_MPa", "flank2_MPa"):
        assert light[key] == pytest.approx(alone[key], rel=1e-2), key


FACE_SPECTRUM = "torque,cycles\n120,5e6\n200,2e4\n"


def _face_rating(folder, **face):
    folder.mkdir(exist_ok=True)
    (folder / "duty.csv").write_text(FACE_SPECTRUM)
    return solve_job(prepare_job({**BASE, "positions": 3, "spectrum": str(folder / "duty.csv"),
                                  **face})).summary


def test_an_even_face_rates_as_the_2d_pair(tmp_path):
    # each level solved across an even face: every section is the 2D pair at that torque, so
    # the heaviest level's stresses are those of the pair solved alone at it, within the
    # contact solve's tolerance (a solver that keeps its contacts settles each position on its
    # own path: measured 8e-7); the lighter one, solved on the heaviest one's contact, within
    # the grids' sampling of its peaks, as in the plane (measured 5e-5 on the roots)
    rating = _face_rating(tmp_path, misalignment=0.0)["rating"]
    assert rating["across_face"] and rating["every_tooth"]
    heaviest = max(level["solved_torque_Nm"] for level in rating["levels"])
    for level in rating["levels"]:
        torque = level["solved_torque_Nm"]
        alone = solve_job(prepare_job({**BASE, "positions": 3, "torque": torque}))
        rows = alone.summary["cycle"]["rows"]
        roots, pressures = (1e-5, 1e-5) if torque == heaviest else (2e-3, 1e-2)
        assert level["root1_MPa"] == pytest.approx(max(r["root_stress_gear1_MPa"]
                                                       for r in rows), rel=roots)
        assert level["flank1_MPa"] == pytest.approx(max(
            t.flank_p_MPa for sol in alone.solutions for t in sol.teeth), rel=pressures)


def test_a_lighter_level_across_the_face_is_solved_on_the_heaviest_ones_contact(
        tmp_path, monkeypatch):
    # 120 N·m is within a quarter of 200: one drive across the face for both, the lighter
    # level's sections solved on the contacts kept at 200 N·m; against 120 N·m driven across
    # the face alone, its stresses within the grids' sampling of the peaks
    from fegear.toothpair import face_drive

    drives = []
    drive = face_drive.drive_across

    def counted(job, *args, **kwargs):
        if kwargs.get("lighter") is not None:   # the rating's drives (not the face table's)
            drives.append((job.case.torque, tuple(kwargs["lighter"])))
        return drive(job, *args, **kwargs)

    monkeypatch.setattr(face_drive, "drive_across", counted)
    both = _face_rating(tmp_path, misalignment=8.0)["rating"]["levels"]
    assert drives == [(200.0, (120.0,))]
    (tmp_path / "one").mkdir()
    (tmp_path / "one" / "duty.csv").write_text("torque,cycles\n120,5e6\n")
    alone = solve_job(prepare_job({**BASE, "positions": 3, "misalignment": 8.0,
                                   "spectrum": str(tmp_path / "one" / "duty.csv")}))
    one = alone.summary["rating"]["levels"][0]
    assert drives[1:] == [(120.0, ())]
    light = next(level for level in both if level["solved_torque_Nm"] == 120.0)
    for key in ("root1_MPa", "root2_MPa"):
        assert light[key] == pytest.approx(one[key], rel=2e-3), key
    for key in ("flank1_MPa", "flank2_MPa"):
        assert light[key] == pytest.approx(one[key], rel=1e-2), key


def test_a_misaligned_life_is_rated_at_the_worst_section(tmp_path):
    # at the job's own torque the level's root stress is the face's worst section's over the
    # cycle, above the 2D pair's; the lighter level is raised too, and the life shorter
    summary = _face_rating(tmp_path, misalignment=8.0)
    rating, face = summary["rating"], summary["face"]
    flat = _face_rating(tmp_path / "flat")
    own = next(level for level in rating["levels"] if level["solved_torque_Nm"] == 200.0)
    assert own["root1_MPa"] == pytest.approx(face["worst"]["root_stress_gear1_MPa"]["value"],
                                             rel=1e-9)
    for level, even in zip(rating["levels"], flat["rating"]["levels"]):
        assert level["root1_MPa"] > 1.05 * even["root1_MPa"]
        assert level["root2_MPa"] > even["root2_MPa"]
    assert "across the face, each tooth's stresses at its worst section" in \
        RATING.printed(rating, summary)

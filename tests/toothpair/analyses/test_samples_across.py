"""A tolerance class's pairs across the face (``fegear solve --grade … --misalignment …``): a
sample reads as the same pair solved alone across the face from its deviations file, its
helix and its misalignment; the room a pair keeps across the face is its backlash where
nothing varies across it; a sample whose face takes up the backlash is counted as jammed;
the summary and the printed table read K_Hβ as the stresses; the class's inputs across the
face are refused by name where they do not fit."""

from dataclasses import replace

import numpy as np
import pytest

from fegear.errors import ParameterError
from fegear.geometry import PairParameters, ToothContact, gear1_profile, runout_text
from fegear.tolerance import Draw, grade_of
from fegear.toothpair import SolveCase, prepare_job, solve_job
from fegear.toothpair.analyses import SAMPLES
from fegear.toothpair.analyses.samples.plot import samples_figure
from fegear.toothpair.analyses.samples.report import ClassReading, samples_summary
from fegear.toothpair.analyses.samples.solve import SampleCase, solve_samples
from fegear.toothpair.case import HEADLINE, revolution_positions
from fegear.toothpair.face import Face
from fegear.toothpair.face_room import ROOM_ANGLES, FaceRoom, room_of
from fegear.toothpair.ring.solver import RingSolver, SolverModes
from fegear.toothpair.safety import DEFAULT_ALLOWABLES
from fegear.toothpair.teeth import INTERFERENCE_UM

#: backlash enough that class 5 turns across a 4 µm misalignment in most of its pairs
BASE = {"shift": 0.03, "rotation": 0.002, "quality": "coarse", "no-estimate": True}
PAIR = PairParameters(shift=0.03, rotation=0.002)
CASE = SolveCase(PAIR, torque=200.0, quality="coarse")


@pytest.fixture(scope="module")
def graded():
    """Class 5's first 4 pairs across the face at 4 µm ± 2 µm, at two positions."""
    job = prepare_job({**BASE, "grade": 5, "samples": 4, "positions": 2, "misalignment": 4.0,
                       "misalignment-band": 2.0, "face-sections": 5})
    return job, solve_job(job)


def _deviations_file(path, deviations, face) -> None:
    """A sample's teeth as a deviations file (a row a tooth: pitch, profile and helix)."""
    lines = ["gear,tooth,fp [µm],fHa [µm],ffa [µm],fHb [µm],ffb [µm]"]
    for gear, helix in ((1, face.helix1), (2, face.helix2)):
        teeth = deviations.teeth(gear)
        for tooth, slope, form in helix:
            d = teeth[tooth]
            lines.append(f"{gear},{tooth},{d.pitch!r},{d.slope!r},{d.form!r},{slope!r},"
                         f"{form!r}")
    path.write_text("\n".join(lines) + "\n")


def _reads_as_alone(job, row, folder, **inputs) -> None:
    """Sample ``row`` of ``job``'s class reads as the same pair solved alone across the face
    (its deviations file, runouts, centre distance and misalignment; ``inputs`` beside them):
    the same kept contact's rule, other anchors (as in the plane: the roots to 2e-3, a peak
    pressure moves with where the points fall)."""
    k = row["sample"]
    deviations, drawn = job.draw.pair(k), job.draw.face(k)
    face = replace(job.face, helix1=drawn.helix.gear1, helix2=drawn.helix.gear2)
    path = folder / f"sample{k}.csv"
    _deviations_file(path, deviations, face)
    alone = solve_job(prepare_job({
        **BASE, **inputs, "face-sections": 5, "deviations": str(path),
        "runout": [runout_text(1, deviations.runout1), runout_text(2, deviations.runout2)],
        "centre-distance-deviation": deviations.centre_distance,
        "misalignment": drawn.misalignment})).summary["face"]
    for key in HEADLINE:
        rel = 2e-3 if key.startswith("root") else 1e-2
        assert row[key] == pytest.approx(alone["worst"][key]["value"], rel=rel), (k, key)
    assert row["K_Hbeta"] == pytest.approx(alone["K_Hbeta"], rel=1e-2), k


def test_a_sample_reads_as_the_same_pair_solved_alone_across_the_face(graded, tmp_path):
    job, solved = graded
    s = solved.summary["samples"]
    rows = [r for r in s["rows"] if r["status"] == "solved"]
    assert len(rows) >= 2 and job.draw.across
    for row in rows[:2]:
        assert row["misalignment_um"] == job.draw.face(row["sample"]).misalignment != 4.0
        _reads_as_alone(job, row, tmp_path, positions=2)
        assert row["stresses_at"] == "worst section"


@pytest.mark.slow
def test_over_a_revolution_a_sample_reads_as_the_same_pair_turned_alone_across_the_face(
        tmp_path):
    # each pair of the class at every pitch of a turn across its own face, on the contacts
    # kept for the phases: its worst section over the turn is the same pair's revolution
    # across the face, solved alone
    job = prepare_job({**BASE, "grade": 5, "samples": 2, "positions": 2, "revolution": True,
                       "misalignment": 4.0, "misalignment-band": 2.0, "face-sections": 5})
    rows = [r for r in solve_job(job).summary["samples"]["rows"] if r["status"] == "solved"]
    assert rows
    for row in rows:
        _reads_as_alone(job, row, tmp_path, positions=2, revolution=True)


def test_the_summary_and_the_table_read_k_hbeta_and_the_class_across_the_face(graded):
    job, solved = graded
    s = solved.summary["samples"]
    rows = [r for r in s["rows"] if r["status"] == "solved"]
    kh = s["load_factor"]
    assert kh["worst"] == max(r["K_Hbeta"] for r in rows) > 1.0
    # the exact pair's numbers are its worst sections', as the face's analysis reads them
    face = solved.summary["face"]
    assert kh["nominal"] == pytest.approx(face["K_Hbeta"], rel=1e-9)
    key = "root_stress_gear1_MPa"
    assert s["stresses"][key]["nominal"] == pytest.approx(face["worst"][key]["value"],
                                                           rel=1e-9)
    median = next(q for q in kh["turning"] if q["q"] == 0.5)
    assert median["value"] == pytest.approx(np.median([r["K_Hbeta"] for r in rows]))
    assert s["across"]["misalignment_band_um"] == 2.0 and s["grade"]["helix1"]["F_bT_um"] == 7.5
    printed = SAMPLES.printed(s, solved.summary)
    assert "K_Hβ [-]" in printed and "f_HβT 5.5/5.5" in printed and "4 ± 2" in printed
    assert "each of them at its worst section" in printed
    assert {"samples.K_Hbeta.P95", "samples.root_stress_gear1_MPa.P95"} <= set(
        SAMPLES.columns(s))
    # the picture says its safety factors are the worst sections', with the band
    figure = samples_figure(s, job.allowables, "a title")
    assert "across the face at its worst section, misalignment 4 ± 2 µm" in \
        figure.get_suptitle()


def test_the_samples_panels_keep_apart_with_hundreds_of_pairs_a_bar(graded):
    """Each panel's axis label and tick labels stay clear of its neighbour's, with counts of
    three digits (a thousand pairs drew "pairs" over the next panel's ticks)."""
    from labels import panels_overlapping

    job, solved = graded
    s = solved.summary["samples"]
    many = {**s, "rows": s["rows"] * 300}   # the same pairs, each counted 300 times
    figure = samples_figure(many, job.allowables, "a title")
    assert max(p.get_height() for p in figure.axes[0].patches) >= 300
    assert panels_overlapping(figure) == []


def test_the_samples_legend_counts_one_pair_as_one(graded):
    job, solved = graded
    s = solved.summary["samples"]
    one = {**s, "samples": 1, "rows": [next(r for r in s["rows"] if r["status"] == "solved")]}
    figure = samples_figure(one, job.allowables, "a title")
    assert "1 pair solved" in [t.get_text() for t in figure.axes[0].get_legend().get_texts()]
    assert "\n1 pair of ISO 1328-1 class" in figure.get_suptitle()
    assert "\n1 pair of ISO 1328-1:2013 class" in SAMPLES.printed(one, solved.summary)


# slow (10 s: each pair's moved clearances over a whole turn)
@pytest.mark.slow
def test_a_deviated_pairs_room_is_its_backlash_over_the_turn_and_closes_with_its_face():
    """room_of of a deviated pair with nothing across the face is its backlash in the plane:
    at each rolling angle of a whole turn the least loaded clearance plus the least coast one,
    as the deviated solve moves them (moved_clearances, the tooth by tooth search), least over
    the turn; its face takes up that room (scaled to its limit: none left), and the class's
    check reads the same room."""
    from fegear.geometry import moved_clearances

    draw = Draw(grade_of(5, PAIR, face_width=CASE.thickness), 2, 0, 12.0, 10.0)
    betas = revolution_positions(0.0, ROOM_ANGLES, PAIR.z1, PAIR.z2)
    states = ToothContact(PAIR, gear1_profile(PAIR)).states(betas)
    batch = FaceRoom(CASE, list(zip(betas, states)), np.inf, 9)
    rooms = []
    for k in range(draw.count):
        case = replace(CASE, deviations=draw.pair(k))
        drive, coast = (moved_clearances(case.deviations, PAIR, states, d) for d in (+1, -1))
        backlash = min(min(t.plus_um for t in d.teeth if t.plus_um is not None)
                       + min(t.minus_um for t in c.teeth if t.minus_um is not None)
                       for d, c in zip(drive, coast))
        assert room_of(Face(), case).um == pytest.approx(backlash, abs=1e-9), k
        drawn = draw.face(k)
        face = Face(misalignment=drawn.misalignment, tilt=2.0, crowning=3.0,
                    helix1=drawn.helix.gear1, helix2=drawn.helix.gear2)
        room = room_of(face, case)
        assert room.um < backlash
        limit = replace(face, misalignment=face.misalignment * room.scale,
                        tilt=face.tilt * room.scale,
                        helix1=tuple((t, s * room.scale, f * room.scale)
                                     for t, s, f in face.helix1),
                        helix2=tuple((t, s * room.scale, f * room.scale)
                                     for t, s, f in face.helix2))
        assert room_of(limit, case).um == pytest.approx(0.0, abs=1e-9), k
        assert batch.room(case.deviations, face).um == pytest.approx(room.um, abs=1e-9)
        assert (batch.jammed(case.deviations, face) is None) == (room.um >= -INTERFERENCE_UM)
        rooms.append(room.um)
    assert min(rooms) < -INTERFERENCE_UM < max(rooms)   # both kinds among them


def test_a_sample_that_jams_across_the_face_is_counted_as_jammed():
    # 18 µm ± 8 µm on a pair whose exact room is 25.7 µm of it: class 5's first four pairs
    # turn in the plane, and two of them jam across the face
    draw = Draw(grade_of(5, PAIR, face_width=CASE.thickness), 4, 0, 18.0, 8.0)
    face = Face(sections=5, misalignment=18.0)
    solver = RingSolver(None, SolverModes(keep_phases=True))
    across = solve_samples(SampleCase(CASE, (0.0,), draw, DEFAULT_ALLOWABLES, face=face),
                           solver)
    jammed = [r for r in across.rows if r["status"] == "jammed"]
    assert jammed and all("across the face" in r["why"] for r in jammed)
    for row in jammed:
        k = row["sample"]
        drawn = draw.face(k)
        own = replace(face, helix1=drawn.helix.gear1, helix2=drawn.helix.gear2,
                      misalignment=drawn.misalignment)
        assert room_of(own, replace(CASE, deviations=draw.pair(k))).um < -INTERFERENCE_UM
    plane = [r["status"] for r in solve_samples(
        SampleCase(CASE, (0.0,), replace(draw, grade=grade_of(5, PAIR)), DEFAULT_ALLOWABLES),
        RingSolver(None, SolverModes(keep_phases=True))).rows]
    assert all(plane[r["sample"]] == "solved" for r in jammed)   # each turns in the plane
    assert len(jammed) == 2
    s = samples_summary(across.rows, list(across.across), ClassReading(
        draw=draw, quantile=0.95, allowables=DEFAULT_ALLOWABLES, face=face))
    assert s["jammed"] == len(jammed) and s["load_factor"]["quantiles"][-1]["jams"]


@pytest.mark.parametrize("values, name", [
    ({"misalignment-band": 3.0, "misalignment": 2.0}, "misalignment-band"),   # no grade
    ({"grade": 5, "misalignment-band": 3.0}, "misalignment-band"),            # no face
    ({"grade": 5, "misalignment": 2.0, "misalignment-band": -1.0}, "misalignment-band"),
    ({"grade": 5, "misalignment": 150.0, "misalignment-band": 60.0}, "misalignment-band"),
    ({"grade": 5, "helix-form-deviation": "1:3=2"}, "helix-form-deviation"),
    ({"grade": 5, "misalignment": 2.0, "deviations": "HELIX"}, "deviations"),
])
def test_bad_class_inputs_across_the_face_are_refused_by_name(values, name, tmp_path):
    helix = tmp_path / "helix.csv"
    helix.write_text("gear,tooth,fHb [µm]\n1,3,2\n")
    values = {k: str(helix) if v == "HELIX" else v for k, v in values.items()}
    with pytest.raises(ParameterError) as err:
        prepare_job({**BASE, **values})
    assert err.value.name == name


def test_a_class_across_the_face_draws_its_helix_and_in_the_plane_does_not():
    job = prepare_job({**BASE, "grade": 5, "tilt": 3.0})
    assert job.face.tilt == 3.0 and job.draw.across and job.draw.misalignment_um == 0.0
    assert job.draw.grade.helix1.b == job.case.thickness
    assert not prepare_job({**BASE, "grade": 5}).draw.across

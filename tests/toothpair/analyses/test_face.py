"""The solve across the face as a job (``fegear solve --misalignment …``): its inputs refused
by name; an even face's stresses are the 2D pair's (ratio one) and K_Hβ one; a misaligned face
is worst at the end it closes, with method C formed from the mismatch and the approach it
states; face.csv holds a row a tooth and section."""

import csv

import numpy as np
import pytest

from fegear.errors import ParameterError
from fegear.toothpair import prepare_job, solve_job
from fegear.toothpair.analyses import FACE
from fegear.toothpair.analyses.face.solve import method_c
from fegear.toothpair.present.output import write_job

BASE = {"quality": "coarse", "no-estimate": True}


@pytest.mark.parametrize("values, name", [
    ({"end-length": 1.0}, "end-length"),
    ({"end-relief": 2.0, "end-length": 2.6}, "end-length"),
    ({"misalignment": 250.0}, "misalignment"),
    ({"face-sections": 2}, "face-sections"),
    ({"crowning": -1.0}, "crowning"),
    ({"grade": 5, "helix-slope-deviation": "1:3=2"}, "helix-slope-deviation"),
    ({"helix-form-deviation": "1:44=2"}, "helix-form-deviation"),
    ({"helix-slope-deviation": "3:4=2"}, "helix-slope-deviation"),
])
def test_bad_face_inputs_are_refused_by_name(values, name):
    with pytest.raises(ParameterError) as exc:
        prepare_job({**BASE, **values})
    assert exc.value.name == name


@pytest.mark.parametrize("values, name", [
    ({"crowning": 101.0}, "crowning"),
    ({"crowning": 60.0, "end-relief": 41.0}, "crowning"),
    ({"end-relief": 51.0, "m": 1.0}, "end-relief"),
])
def test_a_lead_deeper_than_the_tooth_takes_is_refused(values, name):
    """Crowning and end relief together reach at most 50 m µm at an end (the tip relief's
    bound): refused by name with the module's bound; the bound itself is taken."""
    with pytest.raises(ParameterError) as exc:
        prepare_job({**BASE, **values})
    assert exc.value.name == name
    assert f"<= 50 m = {50 * values.get('m', 2.0):g} µm" in str(exc.value)
    assert prepare_job({**BASE, "crowning": 60.0, "end-relief": 40.0}).face.crowning == 60.0


def test_no_face_input_no_face():
    assert prepare_job(BASE).face is None
    assert prepare_job({**BASE, "crowning": 3.0}).face.crowning == 3.0


def test_an_even_face_is_the_2d_pair():
    s = solve_job(prepare_job({**BASE, "misalignment": 0.0, "face-sections": 5})).summary
    face = s["face"]
    assert face["K_Hbeta"] == pytest.approx(1.0, abs=1e-9)
    for key in ("root_stress_gear1_MPa", "root_stress_gear2_MPa", "contact_pressure_MPa",
                "flank_contact_pressure_MPa"):
        assert face["worst"][key]["ratio"] == pytest.approx(1.0, abs=1e-9), key


def test_a_misaligned_face_is_worst_where_it_closes(tmp_path):
    solved = solve_job(prepare_job({**BASE, "misalignment": 6.0, "face-sections": 5}))
    face = solved.summary["face"]
    root = face["worst"]["root_stress_gear1_MPa"]
    assert root["zeta"] == 0.5 and root["ratio"] > 1.05
    row = face["positions"][0]
    assert row["mismatch_um"] == pytest.approx(-6.0 * 1.0, rel=0.5)   # about f along the load
    assert row["K_Hbeta_method_c"] == method_c(row["mismatch_um"], row["approach_um"])
    assert face["K_Hbeta"] > face["K_Hbeta_method_c"] > 1.0
    # the verdict and the report page read the worst sections' stresses
    verdict = FACE.verdict(face)
    least = min(v for v in face["safety"].values() if v is not None)
    assert verdict.passed == (least >= 1.0) and f"{least:.2f}" in verdict.line
    assert face["safety"]["safety_bending_gear1"] == pytest.approx(
        solved.job.allowables.bending / root["value"])
    (slot, safety), (sections, html) = FACE.page(face)
    assert sections == "sections" and "misalignment 6 µm" in html and "K_Hβ" in html
    # the page's safety factors across the face: each at its stress's worst section
    s_f1 = face["safety"]["safety_bending_gear1"]
    assert slot == "safety" and f"<td>{s_f1:.2f}</td><td>{root['value']:.1f}</td>" in safety
    files = write_job(solved, tmp_path, pictures=False)
    with open(files["face_csv"]) as f:
        rows = list(csv.DictReader(f))
    assert len(rows) == 5 * len(row["line_loads_N_per_mm"])
    assert {r["section"] for r in rows} == {"0", "1", "2", "3", "4"}
    # the slices for ParaView: each loaded tooth's grid at every section, its pressures
    import meshio

    mesh = meshio.read(files["face_vtu"])
    z = np.unique(mesh.points[:, 2])
    assert np.allclose(z, (np.array(face["zeta"]) + 0.5) * face["width_mm"])
    pressure = mesh.point_data["contact_pressure_MPa"]
    assert pressure.max() == pytest.approx(face["worst"]["contact_pressure_MPa"]["value"],
                                           rel=1e-12)   # one position: the top one
    assert {str(t) for t in np.unique(mesh.cell_data["tooth"][0])} >= set(
        row["line_loads_N_per_mm"])


def test_helix_slope_on_the_loaded_teeth_closes_the_second_end():
    """f_Hβ + on every loaded gear-1 tooth moves its flank towards its mate at the second end:
    that end is the worst, as a misalignment closing it is, and method C reads the tooth's
    own mismatch (about f_Hβ)."""
    job = prepare_job({**BASE, "helix-slope-deviation": "1:9=6,1:10=6,1:11=6,1:12=6",
                       "face-sections": 5})
    assert job.face.helix1 == tuple((t, 6.0, 0.0) for t in (9, 10, 11, 12))
    face = solve_job(job).summary["face"]
    assert face["inputs"]["helix_gear1"] == [[t, 6.0, 0.0] for t in (9, 10, 11, 12)]
    _, (_, html) = FACE.page(face)
    assert "helix deviations on 4 gear-1 teeth" in html and "an even face" not in html
    root = face["worst"]["root_stress_gear1_MPa"]
    assert root["zeta"] == 0.5 and root["ratio"] > 1.05
    assert face["positions"][0]["mismatch_um"] == pytest.approx(-6.0)
    assert face["K_Hbeta_method_c"] > 1.0


def test_helix_form_of_a_deviations_file_loads_mid_face(tmp_path):
    """A deviations file's ffb column (every gear-2 tooth 5 µm towards its mate at mid-face):
    the middle of the face carries most, its ends least."""
    f = tmp_path / "helix.csv"
    f.write_text("gear,tooth,ffb [µm]\n" + "".join(f"2,{t},5\n" for t in range(45)))
    job = prepare_job({**BASE, "deviations": str(f), "face-sections": 5})
    assert not job.case.deviations and len(job.face.helix2) == 45
    face = solve_job(job).summary["face"]
    assert face["worst"]["root_stress_gear1_MPa"]["zeta"] == 0.0
    loads = max(face["positions"][0]["line_loads_N_per_mm"].values(), key=sum)
    assert loads[2] > loads[1] > loads[0] and loads[2] > loads[3] > loads[4]


def test_the_room_is_the_backlash_and_closes_with_the_misalignment():
    """With no input across the face the room is the pair's backlash (the loaded and coast
    clearances at one β); a misalignment takes it up at about r0 over the normal's arm per
    µm, and at its scale's limit the room is nil."""
    import dataclasses

    from fegear.toothpair.face_room import room_of

    job = prepare_job({**BASE, "misalignment": 5.0})
    flat = room_of(dataclasses.replace(job.face, misalignment=0.0), job.case)
    assert flat.scale == float("inf") and 9.0 < flat.um < 12.0   # the baseline's, µm of arc
    five = room_of(job.face, job.case)
    assert flat.um - five.um == pytest.approx(5.0, rel=0.1)
    at_limit = room_of(dataclasses.replace(job.face, misalignment=5.0 * five.scale), job.case)
    assert at_limit.um == pytest.approx(0.0, abs=1e-9)


@pytest.mark.parametrize("values, name, limit", [
    ({"misalignment": 20.0}, "misalignment", "|misalignment| <= 9.95 µm"),
    ({"misalignment": -20.0}, "misalignment", "|misalignment| <= 9.95 µm"),
    ({"tilt": 40.0}, "tilt", "|tilt| <= 12.3 µm"),
    ({"helix-slope-deviation": "1:9=25,1:10=25,1:11=25,1:12=25"}, "helix-slope-deviation",
     "at most 0.714 times"),
])
def test_a_face_that_jams_the_pair_is_refused_by_name(values, name, limit):
    """Inputs that close the loaded flanks at one section and the coast flanks at another
    by more than the backlash: refused naming the input and the largest value it can take."""
    with pytest.raises(ParameterError, match="the pair jams") as exc:
        prepare_job({**BASE, **values})
    assert exc.value.name == name and limit in exc.value.admissible
    prepare_job({**BASE, **{k: v / 5 if isinstance(v, float) else
                            "1:9=10,1:10=10,1:11=10,1:12=10" for k, v in values.items()}})


def test_gear_2_s_helix_deviations_count_in_the_room():
    """10 µm of helix slope on every tooth of gear 1 leaves the baseline its room; the same
    on gear 2's teeth as well closes the loaded flanks at the second end by more than the
    backlash: refused, quoting the first entries."""
    one = ",".join(f"1:{t}=10" for t in range(44))
    prepare_job({**BASE, "helix-slope-deviation": one})
    both = one + "," + ",".join(f"2:{t}=10" for t in range(45))
    with pytest.raises(ParameterError, match="the pair jams") as exc:
        prepare_job({**BASE, "helix-slope-deviation": both})
    assert exc.value.value == "1:0=10,1:1=10,1:2=10,… (89 entries)"


def test_a_measured_lead_is_its_helix_slope_where_it_is_one(tmp_path):
    """A lead trace from −f/2 at the first end to +f/2 at the second is a helix slope f: the
    same offsets at every section, the same solve; a trace that closes the loaded flank by
    more than the backlash is refused naming --lead."""
    import dataclasses

    from fegear.toothpair.face import Face

    f = tmp_path / "lead.csv"
    f.write_text("gear,tooth,z [mm],deviation [µm]\n1,10,0,-3\n1,10,5,3\n")
    job = prepare_job({**BASE, "lead": str(f), "face-sections": 5})
    assert job.face.leads1 == ((10, (0.0, 5.0), (-3.0, 3.0)),)
    zeta = np.linspace(-0.5, 0.5, 5)
    sloped = Face(5, helix1=((10, 6.0, 0.0),))
    assert np.allclose(job.face.per_tooth(zeta, 5.0)[0][10], sloped.per_tooth(zeta, 5.0)[0][10])
    a = solve_job(job).summary["face"]
    b = solve_job(dataclasses.replace(job, face=sloped)).summary["face"]
    assert a["K_Hbeta"] == pytest.approx(b["K_Hbeta"], rel=1e-12)
    f.write_text("gear,tooth,z [mm],deviation [µm]\n" + "".join(
        f"1,{t},0,0\n1,{t},5,40\n" for t in range(44)))
    with pytest.raises(ParameterError, match="the pair jams") as exc:
        prepare_job({**BASE, "lead": str(f)})
    assert exc.value.name == "lead"

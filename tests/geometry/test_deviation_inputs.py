"""Deviations as a user gives them (fegear/geometry/deviation_inputs.py): the short texts of
the command line and study files, and a measuring machine's file with units in its header;
whatever is wrong is one ParameterError naming the option, the line or the column."""

import pytest

from fegear.errors import ParameterError
from fegear.geometry.deviation_inputs import (
    RUNOUT_SPEC,
    ToothEntry,
    check_teeth,
    deviations_of,
    per_tooth,
    read_deviations,
    runout_text,
    runouts,
    tooth_deviations,
)
from fegear.geometry.deviations import Deviations, Runout, ToothDeviation


def test_per_tooth_texts():
    assert per_tooth("pitch-deviation", "1:11=5, 2:30=-3.5") == (
        ToothEntry("pitch-deviation", 1, 11, 5.0), ToothEntry("pitch-deviation", 2, 30, -3.5))
    assert per_tooth("pitch-deviation", None) == ()
    # a list (the option typed twice, a study file's) and a mapping (from Python) read alike
    assert per_tooth("form-deviation", ["1:3=2", "2:4=1"]) == per_tooth(
        "form-deviation", {"1:3": 2, " 2 : 4 ": "1"})
    for bad in ("11=5", "3:1=5", "1:x=5", "1:2=abc", "1:2=nan", "1:2=2000", "1:2", "1:2=3=4"):
        with pytest.raises(ParameterError, match="GEAR:TOOTH=µm") as exc:
            per_tooth("slope-deviation", ["1:1=1", f" {bad} "])
        assert exc.value.name == "slope-deviation"
        assert exc.value.value == bad   # the entry that is not one, not the whole option


def test_an_entry_written_back_reads_as_itself():
    """One place knows the grammar both ways: what a message quotes or a case file writes is
    what the option reads."""
    for um in (5.0, -3.5, 0.1, 1 / 3, 1000.0, 2e-7):
        entry = ToothEntry("slope-deviation", 2, 30, um)
        assert per_tooth("slope-deviation", entry.text) == (entry,)
    assert ToothEntry("pitch-deviation", 1, 11, 30.0).text == "1:11=30"
    assert ToothEntry("pitch-deviation", 1, 11, 30.0).where == "1:11"
    for runout in (Runout(10.0, 90.0), Runout(0.1, -1 / 3), Runout(4.0)):
        assert runouts(runout_text(2, runout)) == {2: runout}
    assert runout_text(1, Runout(10.0, 90.0)) == "1=10@90"


def test_an_entry_is_the_one_a_tooth_s_deviation_is_given_by():
    assert ToothEntry.of(ToothDeviation(pitch=4.0, slope=1.0), 1, 11) == ToothEntry(
        "pitch-deviation", 1, 11, 4.0)
    assert ToothEntry.of(ToothDeviation(form=2.0), 2, 3).text == "2:3=2"
    assert ToothEntry.of(ToothDeviation(curve=((0.0, 1.0), (1.0, 2.0))), 1, 2) is None
    with pytest.raises(ParameterError, match=r"'1:11=2000' is not admissible"):
        ToothEntry("pitch-deviation", 1, 11, 2000.0)
    with pytest.raises(ValueError, match="a per-tooth option"):
        ToothEntry("runout", 1, 11, 2.0)


def test_runout_texts():
    assert runouts("1=10@90,2=4") == {1: Runout(10.0, 90.0), 2: Runout(4.0, 0.0)}
    for bad in ("1=-2", "3=2", "1=x@3", "1=2@y", "1:2", "1=10@"):
        with pytest.raises(ParameterError, match=r"GEAR=µm\[@deg\]") as exc:
            runouts(f"2=1,{bad}")
        assert exc.value.value == bad


def test_the_inputs_of_a_solve_make_one_set_of_deviations(tmp_path):
    f = tmp_path / "m.csv"
    f.write_text("# a gear measuring machine's report\ngear, tooth, fp [µm], fHa [um]\n"
                 "1, 11, 4.0, 1.5\n1, 12, -2, 0\n")
    d = deviations_of({"deviations": str(f), "pitch-deviation": "1:11=5",
                       "form-deviation": "2:3=1", "centre-distance-deviation": 10.0,
                       "runout": "2=8@45"}, 44, 45)
    assert d.teeth(1) == {11: ToothDeviation(5.0, 1.5), 12: ToothDeviation(-2.0)}  # the option
    assert d.teeth(2) == {3: ToothDeviation(form=1.0)}                            # wins
    assert d.centre_distance == 10.0 and d.runout2 == Runout(8.0, 45.0) and d
    assert not deviations_of({}, 44, 45)
    with pytest.raises(ParameterError, match="'1:44' is not admissible.*a tooth 0 ... 43 of "
                       "gear 1") as exc:
        deviations_of({"slope-deviation": "1:44=5"}, 44, 45)
    assert exc.value.name == "slope-deviation"   # the option that named the tooth


def test_single_pitch_deviations_add_up_to_the_teeth_s_positions(tmp_path):
    f = tmp_path / "fpt.csv"
    f.write_text("gear,tooth,fpt [mm]\n" + "".join(f"1,{t},{0.001 if t == 2 else 0}\n"
                                                     for t in range(6)))
    got = read_deviations(f, 6, 7)
    assert {k: v.pitch for k, v in got.items()} == {(1, t): (1.0 if t >= 2 else 0.0)
                                                   for t in range(6)}
    f.write_text("gear,tooth,fpt [µm]\n1,0,1\n1,2,1\n")
    with pytest.raises(ParameterError, match="every tooth 0 ... 5 of gear 1"):
        read_deviations(f, 6, 7)


@pytest.mark.parametrize("text, says", [
    ("", "a header"),
    ("gear,tooth\n1,2\n", "at least one deviation column"),
    ("gear,tooth,fp\n1,2,3\n", r"the unit of column 'fp' in brackets"),
    ("gear,tooth,fp [in]\n1,2,3\n", r"the unit of column 'fp \[in\]'"),
    ("gear,tooth,lead [µm]\n1,2,3\n", "not 'lead"),
    ("gear,tooth,fp [µm]\n1,2\n", "line 2: 3 cells"),
    ("gear,tooth,fp [µm]\n1,2,x\n", "line 2: a number in column 'fp"),
    ("gear,tooth,fp [µm]\n1,2.5,1\n", "line 2: a whole number in column 'tooth'"),
    ("gear,tooth,fp [µm]\n3,2,1\n", "line 2: gear 1"),
    ("gear,tooth,fp [µm]\n1,50,1\n", "not gear 1 tooth 50"),
    ("gear,tooth,fp [µm]\n1,5,5000\n", "-1000 <= pitch-deviation <= 1000"),
    # a tooth measured twice is a mistake to point out, not a row to overwrite (issue 67)
    ("gear,tooth,fp [µm]\n1,11,5\n# again\n1,11,6\n",
     r"one row a tooth \(lines 2 and 4 both give gear 1 tooth 11\)"),
    ("gear,tooth,fp [µm],pitch [µm]\n1,11,5,6\n", r"'fp \[µm\]' and 'pitch \[µm\]' are both fp"),
    ("gear,tooth,fp_um\n1,2,3\n", r"the unit goes in brackets: fp \[um\]"),
])
def test_a_bad_file_is_one_line_naming_what_is_wrong(tmp_path, text, says):
    f = tmp_path / "bad.csv"
    f.write_text(text)
    with pytest.raises(ParameterError, match=says) as exc:
        read_deviations(f, 44, 45)
    assert exc.value.name == "deviations" and "\n" not in str(exc.value)


def test_a_spreadsheet_s_semicolons_and_decimal_commas(tmp_path):
    # the one header grammar of every input file (fegear/files.py), as a spectrum's too
    f = tmp_path / "m.csv"
    f.write_text("Gear;Tooth;FP [mm];fHa [µm]\n1;11;0,004;1,5\n")
    assert read_deviations(f, 44, 45) == {(1, 11): ToothDeviation(4.0, 1.5)}


def test_the_help_and_the_refusal_say_the_angle_of_a_runout_may_be_left_out():
    # `--runout 1=10` is 10 µm at 0°: the grammar the user reads says so (issue 67)
    from fegear.toothpair.inputs import JOB_INPUTS

    assert runouts("1=10") == {1: Runout(10.0, 0.0)}
    for text in (JOB_INPUTS["runout"].help, RUNOUT_SPEC):
        assert "GEAR=µm[@deg]" in text and "without @deg, 0°" in text, text
    with pytest.raises(ParameterError, match=r"GEAR=µm\[@deg\]"):
        runouts("1=x")


def test_a_missing_file_is_named():
    with pytest.raises(ParameterError, match="a readable CSV file"):
        read_deviations("/nonexistent/d.csv", 44, 45)


def test_a_tooth_its_gear_does_not_have_is_refused_as_it_was_given():
    check_teeth(Deviations(gear1={43: ToothDeviation(pitch=5.0)}), 44, 45)
    with pytest.raises(ParameterError, match="'1:44=-2.5' is not admissible.*a tooth 0 ... 43 "
                       "of gear 1") as exc:
        check_teeth(Deviations(gear1={44: ToothDeviation(slope=-2.5)}), 44, 45)
    assert exc.value.name == "slope-deviation"
    with pytest.raises(ParameterError, match="'2:45' is not admissible.*0 ... 44 of gear 2"):
        check_teeth(Deviations(gear2={45: ToothDeviation(curve=((0.0, 1.0), (1.0, 2.0)))}),
                    44, 45)


def test_helix_deviations_from_the_options_and_a_file(tmp_path):
    """fHb and ffb columns and --helix-slope/form-deviation give the teeth's helix deviations
    (the options over the file), which are no deviation in the plane: a file of them alone
    gives the 2D pair no deviation."""
    f = tmp_path / "helix.csv"
    f.write_text("gear,tooth,fHb [µm],ffb [mm]\n1,10,4,0.002\n2,3,-1.5,0\n")
    assert read_deviations(f, 44, 45) == {}
    assert not deviations_of({"deviations": str(f)}, 44, 45)
    helix = tooth_deviations({"deviations": str(f), "helix-slope-deviation": "1:10=5,1:2=1",
                              "helix-form-deviation": "2:7=3"}, 44, 45)[1]
    assert helix.gear1 == ((2, 1.0, 0.0), (10, 5.0, 2.0))
    assert helix.gear2 == ((3, -1.5, 0.0), (7, 0.0, 3.0))
    assert not tooth_deviations({}, 44, 45)[1]


@pytest.mark.parametrize("values, name, says", [
    ({"helix-slope-deviation": "1:44=3"}, "helix-slope-deviation", "a tooth 0 ... 43"),
    ({"helix-form-deviation": "1:4=x"}, "helix-form-deviation", "GEAR:TOOTH=µm"),
    ({"helix-form-deviation": "1:4=2000"}, "helix-form-deviation", "|µm| <= 1000"),
])
def test_a_bad_helix_entry_is_refused_by_its_option(values, name, says):
    with pytest.raises(ParameterError, match=says) as exc:
        tooth_deviations(values, 44, 45)
    assert exc.value.name == name


def test_a_helix_column_out_of_range_names_its_line(tmp_path):
    f = tmp_path / "helix.csv"
    f.write_text("gear,tooth,fHb [µm]\n1,10,4\n1,11,4000\n")
    with pytest.raises(ParameterError, match=r"line 3: 4000.*helix-slope-deviation <= 1000") as exc:
        read_deviations(f, 44, 45)
    assert exc.value.name == "deviations"


def test_a_lead_file_gives_each_tooth_its_trace_in_order(tmp_path):
    """A measured lead: rows a point, any order, units converted; each tooth's trace sorted
    along the face."""
    from fegear.geometry import read_leads

    f = tmp_path / "lead.csv"
    f.write_text("gear,tooth,z [mm],deviation [mm]\n1,10,5,0.004\n1,10,0,-0.003\n"
                 "2,7,2.5,0\n1,10,2.5,0\n2,7,0,1e-3\n")
    leads = read_leads(f, 44, 45, 5.0)
    assert leads.gear1 == ((10, (0.0, 2.5, 5.0), (-3.0, 0.0, 4.0)),)
    assert leads.gear2 == ((7, (0.0, 2.5), (1.0, 0.0)),)


@pytest.mark.parametrize("text, says", [
    ("gear,tooth,z [in],deviation [µm]\n1,10,0,1\n", r"the unit of column 'z \[in\]'"),
    ("gear,tooth,z,deviation [µm]\n1,10,0,1\n", r"the unit of column 'z' in brackets"),
    ("gear,tooth,z [mm],deviation [µm]\n1,50,0,1\n1,50,1,1\n", "not gear 1 tooth 50"),
    ("gear,tooth,z [mm],deviation [µm]\n1,5,0,1\n", r"two or more points a tooth"),
    ("gear,tooth,z [mm],deviation [µm]\n1,5,1,1\n1,5,1,2\n", r"lines 2, 3"),
    ("gear,tooth,z [mm],deviation [µm]\n1,5,0,1\n1,5,7,1\n", r"line 3: 0 <= z <= 5 mm"),
    ("gear,tooth,z [mm],deviation [µm]\n1,5,0,1\n1,5,2,1500\n", r"line 3: \|deviation\|"),
    ("gear,tooth,z [mm]\n1,5,0\n", "a header with"),
    ("gear,tooth,z [mm],deviation [µm]\n1,2.5,0,1\n", "a whole number in column 'tooth'"),
])
def test_a_bad_lead_file_is_one_line_naming_what_is_wrong(tmp_path, text, says):
    from fegear.geometry import read_leads

    f = tmp_path / "lead.csv"
    f.write_text(text)
    with pytest.raises(ParameterError, match=says) as exc:
        read_leads(f, 44, 45, 5.0)
    assert exc.value.name == "lead" and "\n" not in str(exc.value)

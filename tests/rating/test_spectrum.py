"""Spectrum files: CSV and TOML read alike, shares become cycles over the life at the speed,
and every fault is one error naming the file and what it needs; materials by name or file."""

import pytest

from fegear.errors import ParameterError
from fegear.rating import MATERIALS, material, read_spectrum


def _write(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(text)
    return path


def test_csv_and_toml_give_the_same_levels(tmp_path):
    csv = _write(tmp_path, "a.csv", "torque,cycles\n100,1e7\n\n250,2e5\n")
    toml = _write(tmp_path, "a.toml", "[[level]]\ntorque = 100\ncycles = 1e7\n"
                                      "[[level]]\ntorque = 250\ncycles = 2e5\n")
    a, b = read_spectrum(csv), read_spectrum(toml)
    assert a == b
    assert [(lv.torque, lv.cycles) for lv in a.levels] == [(100.0, 1e7), (250.0, 2e5)]
    assert a.cycles == 1e7 + 2e5 and a.hours is None


@pytest.mark.parametrize("name, text", [
    ("n.csv", "torque [N·m],cycles\n100,1e7\n250,2e5\n"),
    ("k.csv", "Torque [kN·m], Cycles [-]\n0.1, 1e7\n0.25, 2e5\n"),
    ("c.csv", "# a duty cycle\ntorque [Nm],cycles\n100,1e7\n250,2e5\n"),
    ("s.csv", "torque;cycles\n100;1e7\n250;2e5\n"),                # a spreadsheet's CSV
    ("d.csv", "torque [kN·m];cycles\n0,1;10000000\n0,25;200000\n"),  # with decimal commas
    ("u.toml", "[[level]]\n'torque [kN·m]' = 0.1\ncycles = 1e7\n"
               "[[level]]\n'torque [kN·m]' = 0.25\ncycles = 2e5\n"),
])
def test_a_spectrum_s_header_takes_units_as_a_deviations_file_does(tmp_path, name, text):
    # one grammar for every input file: a name, its unit in brackets where given, converted
    levels = read_spectrum(_write(tmp_path, name, text)).levels
    assert [(lv.torque, lv.cycles) for lv in levels] == [(pytest.approx(100.0), 1e7),
                                                         (pytest.approx(250.0), 2e5)]


def test_shares_in_per_cent(tmp_path):
    path = _write(tmp_path, "p.csv", "torque,share [%]\n100,75\n300,25\n")
    s = read_spectrum(path, speed_rpm=1500.0, life_h=20000.0)
    total = 1500.0 * 60.0 * 20000.0
    assert [lv.cycles for lv in s.levels] == pytest.approx([0.75 * total, 0.25 * total])


def test_shares_become_revolutions_over_the_life(tmp_path):
    path = _write(tmp_path, "s.csv", "torque,share\n100,0.75\n300,0.25\n")
    s = read_spectrum(path, speed_rpm=1500.0, life_h=20000.0)
    total = 1500.0 * 60.0 * 20000.0
    assert [lv.cycles for lv in s.levels] == pytest.approx([0.75 * total, 0.25 * total])
    assert s.hours == 20000.0


@pytest.mark.parametrize("name, text, fragment", [
    ("e.csv", "", "at least one level"),
    ("e.csv", "torque,cycles\n", "at least one level"),
    ("n.csv", "torque,cycles\n100,-5\n", "cycles >= 0 at line 2"),
    ("z.csv", "torque,cycles\n0,5\n", "a torque > 0 at line 2"),
    ("x.csv", "torque,cycles\n100,many\n", "line 2: a number in column 'cycles', not 'many'"),
    ("h.csv", "load,cycles\n100,5\n", "a header torque,cycles or torque,share"),
    ("c.csv", "torque\n100\n", "a header torque,cycles or torque,share (not torque)"),
    ("u.csv", "torque [lbf·ft],cycles\n100,5\n",
     "the unit of column 'torque [lbf·ft]' in brackets: [N·m], [Nm], [kN·m] or [kNm]"),
    ("n.csv", "torque_Nm,cycles\n100,5\n", "the unit goes in brackets: torque [Nm]"),
    ("a.csv", "Nm,cycles\n100,5\n", "a unit alone: torque [Nm]"),
    ("d.csv", "torque;cycles\n1.000,5;5\n", "this file's decimal mark is the comma"),
    ("k.toml", "[[level]]\n'torque [lbf·ft]' = 1\ncycles = 5\n",
     "level 1: the unit of key 'torque [lbf·ft]'"),
    ("w.toml", "[[level]]\ntorque = 'x'\ncycles = 5\n", "level 1: a number in key 'torque', "
                                                          "not 'x'"),
    ("s.csv", "torque,share\n100,0.5\n200,0.3\n", "shares that add up to 1"),
    ("m.toml", "[[level]]\ntorque = 1\ncycles = 5\n[[level]]\ntorque = 2\nshare = 1.0\n",
     "not both"),
    ("t.txt", "torque,cycles\n1,1\n", "a .csv or .toml file"),
    ("b.toml", "[[level]\n", "valid TOML"),
])
def test_faults_are_refused_with_what_is_needed(tmp_path, name, text, fragment):
    path = _write(tmp_path, name, text)
    with pytest.raises(ParameterError) as err:
        read_spectrum(path, speed_rpm=1000.0, life_h=1000.0)
    assert err.value.name == "spectrum"
    assert fragment in str(err.value)


def test_shares_need_a_speed_and_a_life(tmp_path):
    path = _write(tmp_path, "s.csv", "torque,share\n100,1\n")
    with pytest.raises(ParameterError, match="--speed and --life"):
        read_spectrum(path, speed_rpm=1000.0)


def test_materials_by_name_or_file(tmp_path):
    assert material("42CrMo") is MATERIALS["42CrMo"]
    assert all(m.source for m in MATERIALS.values())
    path = _write(tmp_path, "mine.toml", 'treatment = "case-hardened"\nsigma_Hlim = 1400\n'
                                         "sigma_FE = 900\n")
    m = material(str(path))
    assert (m.name, m.sigma_Hlim, m.sigma_FE) == ("mine", 1400, 900)
    for bad, fragment in (("steel", "42CrMo"), (str(_write(tmp_path, "x.toml", "E = 2\n")),
                                                "not E")):
        with pytest.raises(ParameterError, match=fragment):
            material(bad)
    with pytest.raises(ParameterError) as err:
        material(str(_write(tmp_path, "w.toml", 'treatment = "cast"\nsigma_Hlim = 1\n'
                                                "sigma_FE = 1\n")))
    assert err.value.name == "treatment"

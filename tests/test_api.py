"""The Python face (:mod:`fegear.api`) is ``fegear solve``: the same inputs, checks, numbers
and files."""

import json

import pytest

import fegear
from fegear.cli import main

INPUTS = {"torque": 150.0, "quality": "coarse", "no_estimate": True, "z2": 25, "z1": 24}
ARGV = ["--torque", "150", "--quality", "coarse", "--no-estimate", "--z2", "25", "--z1", "24"]


@pytest.fixture(scope="module")
def result():
    return fegear.solve(**INPUTS)


def test_solve_gives_the_numbers_the_command_prints(result, capsys):
    assert main(["solve", *ARGV, "--json"]) == 0
    cli = json.loads(capsys.readouterr().out)
    for name, value in result.headline.items():
        assert value == cli[name], name          # to the last digit: the same job
    assert {str(k): v for k, v in result.summary["load_share"].items()} == cli["load_share"]
    loaded = result.teeth[result.teeth.load_N > 0]
    assert loaded.load_share.sum() == pytest.approx(1.0, abs=1e-9)
    assert result.estimate is None and result.positions is None and result.worst is None


def test_write_writes_what_out_writes(result, tmp_path):
    """The files of ``fegear solve --out`` (pictures left out here:
    tests/toothpair/present/test_outputs.py draws them)."""
    files = result.write(tmp_path / "py", pictures=False)
    assert sorted(p.name for p in (tmp_path / "py").iterdir()) == [
        "gear1.vtu", "gear1_contact.vtu", "gear2.vtu", "gear2_contact.vtu", "summary.json"]
    summary = json.loads(files["summary"].read_text())
    assert summary["root_stress_gear1_MPa"] == result.headline["root_stress_gear1_MPa"]


def test_a_cycle_reports_its_worst_where_it_occurs():
    c = fegear.cycle(positions=2, **INPUTS)
    table = c.positions
    assert len(table) == 2 and table.index.name == "position_deg"
    worst = c.worst["root_stress_gear1_MPa"]
    assert worst["max"] == table.root_stress_gear1_MPa.max()
    assert table.root_stress_gear1_MPa[worst["at_position_deg"]] == worst["max"]
    assert c.headline["root_stress_gear1_MPa"] == worst["max"]   # the files' position
    assert c.worst["safety_contact"]["min"] == table.safety_contact.min()


def test_a_revolution_names_the_deviated_tooth_as_the_worst():
    r = fegear.revolution(positions=2, pitch_deviation=["1:5=5"], **INPUTS)
    rev = r.revolution
    worst = rev["worst"]["root_stress_gear1_MPa"]
    assert (worst["gear"], worst["tooth"]) == (1, 5)
    teeth = rev["teeth"]
    assert teeth.loc[(1, 5), "root_stress_MPa"] == worst["max"]
    assert len(teeth.loc[1]) == 24 and teeth.loc[1].root_stress_MPa.idxmax() == 5
    assert len(r.positions) == 48 and rev["spectrum"].index.name == "order"
    assert r.summary["inputs"]["deviations"]["gear1"]["5"]["pitch_um"] == 5.0
    assert fegear.solve(**INPUTS).revolution is None


def test_a_class_gives_its_samples_as_data_frames(result):
    r = fegear.solve(grade=4, samples=3, shift=0.03, **INPUTS)
    s = r.samples
    assert list(s["rows"].index) == [0, 1, 2] and s["solved"] + s["jammed"] + s["failed"] == 3
    assert s["quantiles"].loc[("root_stress_gear1_MPa", 0.95)].n == 3
    assert s["safety"].loc["safety_bending_gear1"].nominal > 0
    assert s["verdict"].startswith(("PASS", "FAIL"))
    assert result.samples is None


@pytest.mark.parametrize("inputs, name, text", [
    ({"tip_clearence": 0.01}, "tip-clearence", "did you mean tip_clearance?"),
    ({"tip_clearance": -5.0}, "tip-clearance", "tip_clearance = -5.0 is not admissible"),
    ({"h1": 0.9}, "h1", "h1 = 0.9 is not admissible"),
    # a bool is no number: m=True was solved at m = 1 mm
    ({"m": True}, "m", "m = True is not admissible; admissible: 0 < m <= 100 mm"),
    ({"torque": True}, "torque", "torque = True is not admissible"),
    ({"face_width": False}, "face-width", "face_width = False is not admissible"),
    ({"z1": True}, "z1", "z1 = True is not admissible"),
    ({"position": True}, "position", "position = True is not admissible"),
])
def test_a_refused_design_raises_before_any_work(inputs, name, text, monkeypatch):
    import fegear.api

    monkeypatch.setattr(fegear.api, "solve_job", lambda *a: pytest.fail("the work started"))
    with pytest.raises(fegear.ParameterError) as exc:
        fegear.solve(**inputs)
    assert exc.value.name == name
    assert text in str(exc.value)

"""A design as a file: ``fegear solve --case`` and ``--save-case`` (issue 67, item 9), and
``fegear solve --help`` grouped by task (item 8)."""

import json
from dataclasses import replace

import pytest

from fegear.cli import main
from fegear.cli.solve import HELP_GROUPS
from fegear.toothpair import JOB_INPUTS, case_toml, prepare_job, read_case

#: a light pair, quick to solve
LIGHT = {"z2": 25, "z1": 24, "torque": 20.0, "quality": "coarse", "no-estimate": True}
LIGHT_ARGS = ["--z2", "25", "--z1", "24", "--torque", "20", "--quality", "coarse",
              "--no-estimate"]


def _pinned(case):
    """``case`` with its derived defaults at their values: a saved case writes them out."""
    return replace(case, rim1=case.rims[0], rim2=case.rims[1], tip_round=case.edge_radius)


def _same_job(a, b) -> None:
    assert _pinned(b.case) == _pinned(a.case)
    assert b.betas == a.betas
    assert (b.draw, b.rating, b.revolution, b.estimate) == (a.draw, a.rating, a.revolution,
                                                            a.estimate)
    assert b.record == a.record


@pytest.mark.parametrize("values", [
    LIGHT,
    {**LIGHT, "positions": 6, "pitch-deviation": ["1:11=5", "2:3=-2"],
     "runout": ["1=3@90"], "centre-distance-deviation": -4.0},
    {**LIGHT, "relief": 3.0, "tip-clearance": 0.02, "h1": 0.32, "grade": 6, "samples": 30},
    {**LIGHT, "revolution": True, "positions": 2, "slope-deviation": ["1:4=2.5"]},
], ids=["light", "deviated-cycle", "relieved-class", "revolution"])
def test_a_saved_case_reads_back_as_the_same_job(tmp_path, values):
    job = prepare_job(values)
    path = tmp_path / "design.toml"
    path.write_text(case_toml(job.record, where=tmp_path, title="a test"))
    _same_job(job, prepare_job(read_case(path)))


def test_a_case_finds_its_files_beside_it_and_saves_them_relative(tmp_path, monkeypatch):
    folder = tmp_path / "design"
    folder.mkdir()
    (folder / "duty.csv").write_text("torque,cycles\n10,1e6\n20,1e4\n")
    (folder / "measured.csv").write_text("gear,tooth,fp [µm]\n1,11,4\n")
    (folder / "case.toml").write_text('z2 = 25\nz1 = 24\ntorque = 20.0\nquality = "coarse"\n'
                                      'positions = 4\nspectrum = "duty.csv"\n'
                                      'revolution = true\ndeviations = "measured.csv"\n')
    monkeypatch.chdir(tmp_path)            # the case runs from any folder
    job = prepare_job(read_case(folder / "case.toml"))
    assert job.case.deviations.teeth(1)[11].pitch == 4.0
    assert job.rating is not None and len(job.rating.spectrum.levels) == 2
    text = case_toml(job.record, where=folder)
    assert 'spectrum = "duty.csv"' in text and 'deviations = "measured.csv"' in text


def test_a_case_finds_its_lead_beside_it_and_saves_it_relative(tmp_path, monkeypatch):
    folder = tmp_path / "design"
    folder.mkdir()
    (folder / "lead.csv").write_text("gear,tooth,z [mm],deviation [µm]\n1,10,0,-1\n1,10,5,1\n")
    (folder / "case.toml").write_text('quality = "coarse"\nlead = "lead.csv"\n')
    monkeypatch.chdir(tmp_path)
    job = prepare_job(read_case(folder / "case.toml"))
    assert job.face.leads1 == ((10, (0.0, 5.0), (-1.0, 1.0)),)
    assert 'lead = "lead.csv"' in case_toml(job.record, where=folder)


def test_solve_saves_its_case_and_its_summary_loads_back(tmp_path, capsys):
    out, saved = tmp_path / "out", tmp_path / "cases" / "light.toml"
    args = [*LIGHT_ARGS, "--pitch-deviation", "1:5=3", "--runout", "2=4@30"]
    assert main(["-q", "solve", *args, "--out", str(out), "--save-case", str(saved)]) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert saved.read_text().startswith("# fegear")
    capsys.readouterr()
    # the summary's case, and an older summary's inputs (written before it had one)
    older = tmp_path / "older.json"
    older.write_text(json.dumps({k: v for k, v in summary.items() if k != "case"}))
    for case in (saved, out / "summary.json"):
        assert main(["-q", "solve", "--case", str(case), "--json"]) == 0
        again = json.loads(capsys.readouterr().out)
        # to 1e-9, not to the bit: a model this process keeps may have formed its unit
        # responses in other batches than a model built afresh (1e-13)
        for key in ("root_stress_gear1_MPa", "root_stress_gear2_MPa", "contact_pressure_MPa"):
            assert again[key] == pytest.approx(summary[key], rel=1e-9)
        assert again["case"] == summary["case"]
    job = prepare_job(read_case(saved))
    assert _pinned(prepare_job(read_case(older)).case) == _pinned(job.case)


def test_options_typed_beside_a_case_win_and_say_so(tmp_path, capsys):
    case = tmp_path / "case.toml"
    case.write_text('z2 = 25\nz1 = 24\ntorque = 150.0\nquality = "coarse"\n'
                    "no-estimate = true\n")
    # typed at the schema's default (200 N·m) is typed all the same
    assert main(["-q", "solve", "--case", str(case), "--torque", "200", "--torque", "20",
                 "--json"]) == 0
    captured = capsys.readouterr()
    assert json.loads(captured.out)["case"]["torque"] == 20.0
    assert "--torque 20.0 typed beside --case wins over" in captured.err
    assert main(["-q", "solve", "--case", str(case), "--torque", "150", "--json"]) == 0
    assert "wins over" not in capsys.readouterr().err   # the same value: nothing to say


@pytest.mark.parametrize("text,fragment", [
    ("torqe = 150.0\n", "unknown key 'torqe' (did you mean 'torque'?)"),
    ("torque = 150.0\ntorque = 1\n", "not valid TOML"),
    ("[base]\ntorque = 150.0\n", "[base] is a table"),
    ("torque = -5.0\n", "case.toml: torque = -5.0 is not admissible"),
    ("h1 = 0.95\n", "case.toml: h1 = 0.95 is not admissible"),
    ("samples = 30\n", "case.toml: samples = 30 is not admissible"),
    ('pitch-deviation = "1:99=5"\n', "pitch-deviation = '1:99' is not admissible"),
])
def test_a_bad_case_is_refused_in_one_line_naming_the_file(tmp_path, capsys, text, fragment):
    case = tmp_path / "case.toml"
    case.write_text(text)
    out = tmp_path / "out"
    assert main(["-q", "solve", "--case", str(case), "--out", str(out),
                 "--save-case", str(tmp_path / "saved.toml")]) == 2
    err = capsys.readouterr().err
    assert fragment in err and len(err.strip().splitlines()) == 1, err
    assert not out.exists() and not (tmp_path / "saved.toml").exists()


@pytest.mark.parametrize("args,fragment", [
    (["--case", "no-such.toml"], "--case 'no-such.toml' cannot be read"),
    (["--save-case", "."], "--save-case '.' is a folder"),
])
def test_case_options_refused_before_any_solve(capsys, args, fragment):
    assert main(["-q", "solve", *args]) == 2
    assert fragment in capsys.readouterr().err


def test_a_json_case_that_is_no_summary_is_refused(tmp_path, capsys):
    case = tmp_path / "x.json"
    case.write_text('{"torque": 5}')
    assert main(["-q", "solve", "--case", str(case)]) == 2
    assert "a JSON case is the summary.json of a solve" in capsys.readouterr().err


def test_help_groups_hold_every_input_once_in_the_order_of_the_help(capsys):
    rows = [row.name for group in HELP_GROUPS.values() for row in group]
    assert sorted(rows) == sorted(JOB_INPUTS) and len(rows) == len(set(rows))
    with pytest.raises(SystemExit):
        main(["solve", "--help"])
    text = capsys.readouterr().out
    titles = ["a design as a file", *HELP_GROUPS, "outputs", "running"]
    where = [text.index(f"\n{title}:\n") for title in titles]
    assert where == sorted(where)
    assert text.startswith("usage: fegear solve [--case FILE] [options]")


def test_a_rating_without_positions_says_it_took_the_default_cycle(tmp_path, capsys):
    spectrum = tmp_path / "duty.csv"
    spectrum.write_text("torque [N·m];cycles\n10;1e6\n20;1e4\n")
    assert main(["-q", "solve", *LIGHT_ARGS, "--spectrum", str(spectrum)]) == 0
    out = capsys.readouterr().out
    assert "24 positions on one mesh" in out
    assert "(not given: 24 positions over one pitch, the default cycle for a rating" in out


def test_a_summary_s_deviations_read_back_in_the_options_grammar_to_every_digit(tmp_path):
    """A summary.json's deviations come back as the options that give them (through the
    grammar's one writer), every digit kept: `:g` kept six."""
    from fegear.toothpair import read_case

    summary = {"inputs": {"torque_Nm": 20.0, "deviations": {
        "gear1": {"11": {"pitch_um": 5.1234567, "slope_um": 0.0}},
        "runout2": {"fr_um": 10.25, "phase_deg": 90.0}}}}
    path = tmp_path / "summary.json"
    path.write_text(json.dumps(summary))
    values = read_case(path)
    assert values["pitch-deviation"] == ["1:11=5.1234567"]
    assert values["runout"] == ["2=10.25@90"]

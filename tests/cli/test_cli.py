"""CLI: outputs, JSON summary, and user errors (exit 2, one line, no traceback, no files)."""

import json
import os
import subprocess
import sys

import numpy as np
import pytest
from in_process import fegear

FEGEAR = [sys.executable, "-m", "fegear"]


def run(*args, **kw):
    return subprocess.run([*FEGEAR, *args], capture_output=True, text=True, timeout=300, **kw)


# The commands below run in this process (tests/in_process.py), their output read at the file
# descriptors, so that what a library prints there breaks the JSON as it would the process's
def test_profile_writes_csv_png_and_json(tmp_path, capfd):
    r = fegear(capfd, "profile", "--m", "2", "--h1", "0.3", "--f1", "0.15", "--shift", "0.016",
               "--rotation", "0.002", "--positions", "6", "--out", str(tmp_path), "--json")
    assert r.code == 0, r.lines
    s = json.loads(r.out)
    assert set(s["backlash_um"]) >= {"plus", "minus"}
    assert 4.0 < s["backlash_um"]["plus"] < 6.0
    assert len(s["clearance_um"]) == 44
    assert {"tooth", "position_deg", "plus_um", "minus_um"} <= set(s["clearance_um"][0])
    assert s["interference"] == []
    for name in ("gear1.csv", "gear2.csv", "pair.png", "summary.json"):
        assert (tmp_path / name).stat().st_size > 0
    g1 = np.loadtxt(tmp_path / "gear1.csv", delimiter=",", skiprows=1)
    g2 = np.loadtxt(tmp_path / "gear2.csv", delimiter=",", skiprows=1)
    # each gear in its own frame: gear 1 within its tip radius, gear 2 within 43.8 … 46.2
    assert np.hypot(*g1.T).max() == pytest.approx(44.784, abs=1e-9)
    assert np.hypot(*g2.T).min() == pytest.approx(43.8, abs=1e-9)
    # no temporary files left behind, and no STEP solid unasked (--step:
    # tests/cli/test_profile_drawings.py)
    assert not [p for p in os.listdir(tmp_path) if p.startswith(".") or p.endswith(".step")]


def test_profile_table_output(capfd):
    # no --out: the table alone (the files --out writes: the test above)
    r = fegear(capfd, "profile", "--positions", "4")
    assert r.code == 0, r.lines
    assert "clearance at β = 0" in r.out and "backlash" in r.out


SCHEDULER_ARGS = ["--grade", "6", "--samples", "2", "--quality", "coarse", "--scheduler",
                  "tcp://127.0.0.1:9"]
SCHEDULER_ERROR = "--scheduler 'tcp://127.0.0.1:9': cannot connect"


@pytest.mark.parametrize("command,args,fragment", [
    ("profile", ["--m", "-1"], "m = -1.0 is not admissible"),
    ("profile", ["--m", "nan"], "m = nan is not admissible"),
    ("profile", ["--h1", "inf"], "h1 = inf is not admissible"),
    ("profile", ["--z2", "44", "--z1", "44"], "z2 = 44"),
    ("profile", ["--f1", "0.7"], "f1 = 0.7 is not admissible"),
    ("profile", ["--h1", "0.9"], "admissible: 0.0500 <= h1 <= 0.83"),
    ("profile", ["--chord-error", "0"], "--chord-error"),
    ("profile", ["--m", "abc"], "--m = 'abc' is not admissible; admissible: 0 < m <= 100 mm"),
    ("hertz", ["--r2", "-5"], "r2 = -5.0 is not admissible"),
    ("hertz", ["--r1", "0"], "r1 = 0.0 is not admissible"),
    ("hertz", ["--load", "nan"], "load = nan is not admissible"),
    ("hertz", ["--E", "-2"], "E = -2.0 is not admissible"),
    ("hertz", ["--nu", "0.5"], "nu = 0.5 is not admissible"),
    ("hertz", ["--thickness", "inf"], "--face-width = inf is not admissible"),
    ("hertz", ["--quality", "best"], "quality = 'best' is not admissible"),
    ("hertz", ["--penalty-factor", "0"], "--penalty-factor = 0.0 is not admissible"),
    ("hertz", ["--load", "1e9"], "load = 1000000000.0 is not admissible"),
    ("solve", ["--torque", "-5"], "torque = -5.0 is not admissible"),
    ("solve", ["--quality", "best"], "quality = 'best' is not admissible"),
    ("solve", ["--tip-round", "5"], "--tip-round = 5.0 is not admissible"),
    ("solve", ["--position", "400"], "position = 400.0 is not admissible"),
    ("solve", ["--extra-pairs", "9"], "--extra-pairs = 9 is not admissible"),
    ("solve", ["--h1", "0.9"], "admissible: 0.0500 <= h1 <= 0.83"),
    ("solve", ["--grade", "0"], "--grade = 0 is not admissible"),
    ("solve", ["--grade", "6", "--samples", "0"], "--samples = 0 is not admissible"),
    ("solve", ["--grade", "6", "--quantile", "1.5"], "--quantile = 1.5 is not admissible"),
    ("solve", ["--samples", "50"], "--samples = 50 is not admissible"),
    ("solve", ["--scheduler", "tcp://127.0.0.1:9"], "--scheduler: with --grade only"),
    # slow: it waits out the connection's 10 s timeout (the test after this one waits 0.5 s)
    pytest.param("solve", SCHEDULER_ARGS, SCHEDULER_ERROR, marks=pytest.mark.slow),
])
def test_user_errors_exit_2_with_one_line(tmp_path, capsys, command, args, fragment):
    """In this process, its warnings counted as lines of stderr (tests/in_process.py); the
    test below starts a process of its own once a command."""
    out = tmp_path / "o"
    ran = fegear(capsys, command, *args, "--out", str(out))
    assert ran.code == 2, ran.lines
    assert ran.out == ""
    assert len(ran.lines) == 1 and ran.lines[0].startswith("fegear: error:"), ran.lines
    assert fragment in ran.lines[0]
    assert not out.exists() or not any(out.iterdir())


@pytest.mark.parametrize("command,args,fragment", [
    ("profile", ["--h1", "0.9"], "admissible: 0.0500 <= h1 <= 0.83"),
    ("hertz", ["--load", "nan"], "load = nan is not admissible"),
    ("solve", ["--torque", "-5"], "torque = -5.0 is not admissible"),
])
def test_a_user_error_is_one_line_from_the_command_itself(tmp_path, command, args, fragment):
    """The test above through ``python -m fegear``, once a command: exit 2, nothing on
    stdout, one line on stderr and no traceback."""
    out = tmp_path / "o"
    r = run(command, *args, "--out", str(out))
    assert r.returncode == 2, r.stderr
    assert r.stdout == ""
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("fegear: error:")
    assert fragment in lines[0]
    assert "Traceback" not in r.stderr
    assert not out.exists() or not any(out.iterdir())


def test_a_scheduler_nobody_listens_at_is_one_line_and_writes_nothing(tmp_path, capsys,
                                                                      monkeypatch):
    """The slow case above in this process, the connection's timeout 0.5 s for its 10 s."""
    distributed = pytest.importorskip("distributed")
    from fegear.cli import main

    client = distributed.Client
    monkeypatch.setattr(distributed, "Client",
                        lambda address, timeout: client(address, timeout="0.5s"))
    out = tmp_path / "o"
    assert main(["solve", *SCHEDULER_ARGS, "--out", str(out)]) == 2
    std = capsys.readouterr()
    lines = std.err.strip().splitlines()
    assert std.out == "" and len(lines) == 1 and lines[0].startswith("fegear: error:")
    assert SCHEDULER_ERROR in lines[0]
    assert not out.exists() or not any(out.iterdir())


def test_unwritable_output_path(tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    r = run("profile", "--positions", "4", "--out", str(blocker / "sub"))
    assert r.returncode == 2
    assert "--out" in r.stderr and "Traceback" not in r.stderr
    assert len(r.stderr.strip().splitlines()) == 1


def test_hertz_prints_fe_beside_hertz_and_writes_vtu(tmp_path, capfd):
    r = fegear(capfd, "hertz", "--r1", "10", "--r2", "10", "--load", "1000", "--thickness",
               "5", "--quality", "coarse", "--out", str(tmp_path), "--json")
    assert r.code == 0, r.lines
    s = json.loads(r.out)
    assert abs(s["error_pct"]["p_max"]) < 0.5 and abs(s["error_pct"]["half_width"]) < 2.0
    assert s["hertz"]["b_over_R"] == pytest.approx(0.0222, abs=1e-4)
    assert s["dofs"] > 0 and s["contact_iterations"] > 0
    assert {"mesh", "assemble_factor", "condense", "contact", "recovery", "output"} <= set(
        s["timings_s"])
    for name in ("disk1.vtu", "disk2.vtu", "summary.json"):
        assert (tmp_path / name).stat().st_size > 0
    table = fegear(capfd, "hertz", "--r2", "-12", "--quality", "coarse")
    assert table.code == 0, table.lines
    assert "disk in bore" in table.out and "b/R*" in table.out


@pytest.mark.slow
def test_solve_writes_vtu_png_and_summary(tmp_path):
    import meshio

    r = run("solve", "--shift", "0.016", "--rotation", "0.002", "--quality", "fast",
            "--no-estimate", "--out", str(tmp_path), "--json")
    assert r.returncode == 0, r.stderr
    s = json.loads(r.stdout)
    for key in ("root_stress_gear1_MPa", "root_stress_gear2_MPa", "contact_pressure_MPa",
                "von_mises_max_MPa", "hertz_p0_MPa", "teeth_in_contact", "load_share",
                "transmission_error_urad", "mesh_stiffness_Nm_per_rad", "error_estimate_pct",
                "wall_s", "inputs"):
        assert key in s
    assert sum(s["load_share"].values()) == pytest.approx(1.0, abs=1e-3)
    assert s["torque_balance_error"] < 1e-6
    for name in ("gear1", "gear2"):
        m = meshio.read(tmp_path / f"{name}.vtu")
        assert "triangle6" in m.cells_dict
        assert {"displacement_mm", "von_mises_MPa", "s1_MPa", "sxx_MPa",
                "contact_pressure_MPa"} <= set(m.point_data)
        assert all(k.endswith(("_mm", "_MPa")) for k in m.point_data)   # ParaView shows units
        assert m.point_data["contact_pressure_MPa"].max() > 0
    assert (tmp_path / "von_mises.png").stat().st_size > 10_000


@pytest.mark.slow
def test_solve_positions_writes_cycle_csv_and_plot(tmp_path):
    r = run("solve", "--shift", "0.016", "--rotation", "0.002", "--quality", "fast",
            "--positions", "3", "--no-estimate", "--out", str(tmp_path), "--json")
    assert r.returncode == 0, r.stderr
    s = json.loads(r.stdout)
    rows = np.genfromtxt(tmp_path / "cycle.csv", delimiter=",", names=True)
    assert len(rows) == 3 == s["cycle"]["positions"]
    assert np.allclose(np.diff(rows["position_deg"]), 360 / 45 / 3)
    shares = np.column_stack([rows[n] for n in rows.dtype.names if n.startswith("share_")])
    assert np.allclose(shares.sum(axis=1), 1.0, atol=1e-6)
    worst = max(rows["root_stress_gear1_MPa"])
    assert s["root_stress_gear1_MPa"] == pytest.approx(worst)  # details at the worst position
    assert s["cycle"]["root_stress_gear1_MPa"]["max"] == pytest.approx(worst)
    assert (tmp_path / "cycle.png").stat().st_size > 10_000
    for name in ("gear1.vtu", "gear2.vtu", "von_mises.png", "summary.json"):
        assert (tmp_path / name).stat().st_size > 0


def test_solve_grade_writes_the_samples_and_sensitivities_tables_pictures_and_summary(
        tmp_path, capfd):
    r = fegear(capfd, "solve", "--shift", "0.03", "--rotation", "0.002", "--quality", "coarse",
               "--grade", "5", "--samples", "4", "--no-estimate", "--sensitivities",
               "--out", str(tmp_path))
    assert r.code == 0, r.lines
    assert "pairs of ISO 1328-1:2013 class 5" in r.out and "verdict: " in r.out
    s = json.loads((tmp_path / "summary.json").read_text())["samples"]
    assert s["samples"] == 4 == len(s["rows"]) and s["grade"]["gear1"]["f_pT_um"] == 6.0
    rows = np.genfromtxt(tmp_path / "samples.csv", delimiter=",", names=True, dtype=None,
                         encoding="utf-8")
    assert list(rows["sample"]) == [0, 1, 2, 3]
    assert (tmp_path / "samples.png").stat().st_size > 10_000
    sens = json.loads((tmp_path / "summary.json").read_text())["sensitivities"]
    first = sens["rows"][0]      # the largest first, at one class-5 tolerance
    assert abs(first["root_stress_gear1_at_tolerance"]) == max(
        abs(r["root_stress_gear1_at_tolerance"]) for r in sens["rows"]
        if r["tolerance_um"] is not None)
    assert "Sensitivities:" in r.out and (tmp_path / "sensitivities.png").exists()


def test_relief_for_a_class_sizes_one_and_names_the_trials_that_stopped_early(capfd):
    """`fegear relief --grade`: a relief and tip clearance for 3 class-4 pairs over a
    2-position cycle; the trials that failed by the pitch point with every pair's round loaded
    say they stopped there, the passing ones give the share they saw over every pair."""
    r = fegear(capfd, "relief", "--grade", "4", "--samples", "3", "--shift", "0.03",
               "--cycle-positions", "2", "--quality", "coarse")
    assert r.code == 0, r.lines
    assert "tip relief 2.50 µm" in r.out and "tip clearance raised from 30.0 to 34.0 µm" in r.out
    trials = [line for line in r.out.splitlines() if " µm, tip clearance " in line]
    stopped = [line for line in trials if "when it stopped" in line]
    assert stopped and all("rounds of teeth" in line for line in stopped)
    assert any("off the rounds (0 % of the pairs that turn load one)" in line
               for line in trials)


@pytest.mark.parametrize("argv,hint", [
    (["solve", "--modul", "2"], "--m"),             # by the first word of its help, "module"
    (["solve", "--module-mm", "2"], "--m"),         # drive reducer's option, not solve's
    (["profile", "--modul", "2"], "--m"),
    (["solve", "--tip-clearence", "6"], "--tip-clearance"),
    (["drive", "reducer", "--modlue-mm", "2"], "--module-mm"),
    (["drive", "reducer", "--torqe", "5"], None),   # solve's --torque is no option here
    (["drive", "bearings", "--rigns", "3"], "--rings"),
    (["optimize", "--trails", "5"], "--trials"),
    (["relief", "--cycle-positons", "6"], "--cycle-positions"),
    (["hertz", "--loda", "5"], "--load"),
])
def test_an_unknown_option_is_told_the_nearest_of_its_own_command(argv, hint, capsys):
    from fegear.cli import main

    with pytest.raises(SystemExit) as exc:
        main(argv)
    lines = capsys.readouterr().err.strip().splitlines()
    assert exc.value.code == 2 and len(lines) == 1, lines
    assert lines[0].startswith(f"fegear: error: unrecognized arguments: {argv[-2]} ")
    if hint is None:
        assert "did you mean" not in lines[0], lines[0]
    else:
        assert lines[0].endswith(f"(did you mean {hint}?)"), lines[0]


def test_a_command_builds_its_own_options_alone_and_help_builds_every_one(monkeypatch, capsys):
    import fegear.cli
    from fegear.cli import main

    def built(sub):
        raise AssertionError("another command's options were built")

    monkeypatch.setattr(fegear.cli.profile, "add_parser", built)
    assert main(["-q", "drive", "ratio", "--train", "internal", "--teeth", "44,45"]) == 0
    assert main(["solve", "--h1", "0.9", "--out", "never-made"]) == 2
    assert "--h1 = 0.9 is not admissible" in capsys.readouterr().err
    with pytest.raises(AssertionError, match="another command"):
        main(["--help"])

"""`fegear drive`: the seed-000 table from the command line, ratios, the lumped model from a
mesh-stiffness file, and one-line errors for bad input."""

import json

import numpy as np
import pytest

from fegear.cli import main
from fegear.drive.bearings import PAPER
from fegear.drive.dynamics import default_inertias
from fegear.toothpair.stiffness import MeshStiffness


def test_bearings_reproduce_the_paper_table_from_the_command_line(tmp_path, capsys):
    assert main(["drive", "bearings", "--json", "--out", str(tmp_path)]) == 0
    s = json.loads(capsys.readouterr().out)
    got = {e["name"]: e for e in s["extremes"]}
    for p in PAPER.extremes:
        e = got[p.name]
        assert (e["min_at_deg"], e["max_at_deg"]) == (p.min_at_deg, p.max_at_deg)
        assert e["min_N"] == pytest.approx(p.min_N, abs=0.006)
        assert e["max_N"] == pytest.approx(p.max_N, abs=0.006)
    assert round(s["support_reactions"]["R_D_max"], -1) == 2800
    assert round(s["support_reactions"]["R_C_max"], -1) == 2110
    assert s["paper"]["R_MFi"] == 1464.1
    csv = (tmp_path / "bearings.csv").read_text().splitlines()
    assert csv[0].startswith("phi_deg,F_A1_N") and len(csv) == 361
    assert (tmp_path / "bearings.png").stat().st_size > 10_000
    # another drive: no paper column
    assert main(["drive", "bearings", "--torque", "500", "--json"]) == 0
    assert "paper" not in json.loads(capsys.readouterr().out)
    # two rings: bearing forces yes, support reactions no (eqs. 6-15 are for three)
    assert main(["drive", "bearings", "--rings", "2"]) == 0
    assert "support reactions need 3 rings" in capsys.readouterr().out


def test_ratio_command(capsys):
    assert main(["drive", "ratio", "--train", "internal", "--teeth", "44,45", "--eta-h",
                 "0.99", "--json"]) == 0
    r = json.loads(capsys.readouterr().out)
    assert r["value"] == pytest.approx(-44.0) and r["efficiency"] == pytest.approx(0.6875)
    assert main(["drive", "ratio", "--train", "2kh", "--i-ab-h", "-3.5"]) == 0
    assert "ratio ω_a/ω_H = 4.5" in capsys.readouterr().out


def test_dynamics_command_on_a_stiffness_file(tmp_path, capsys):
    ph = np.arange(32) / 32
    k = 5e5 * (1 + 0.1 * np.cos(2 * np.pi * ph))
    m = MeshStiffness(ph, k, 1e-6 * np.sin(2 * np.pi * ph), 200.0, 44, 45, 2.0, 5.0, 1.3 * k)
    (tmp_path / "k.json").write_text(json.dumps(m.to_json()))
    assert main(["drive", "dynamics", "--stiffness", str(tmp_path / "k.json"), "--speeds",
                 "100:3000:5", "--json", "--out", str(tmp_path / "dyn")]) == 0
    s = json.loads(capsys.readouterr().out)
    j1, j2 = default_inertias(m)
    assert s["model"]["J1_kgm2"] == pytest.approx(j1)
    # the tangent spring by default, the secant one asked for
    assert s["model"]["spring"] == "tangent"
    assert s["natural_frequencies_rad_s"][1] == pytest.approx(
        np.sqrt(m.mean_tangent * (1 / j1 + (45 / 44) ** 2 / j2)), rel=1e-12)
    assert main(["drive", "dynamics", "--stiffness", str(tmp_path / "k.json"), "--speeds",
                 "100", "--json", "--spring", "secant"]) == 0
    assert json.loads(capsys.readouterr().out)["natural_frequencies_rad_s"][1] == pytest.approx(
        np.sqrt(m.mean * (1 / j1 + (45 / 44) ** 2 / j2)), rel=1e-12)
    assert [r["speed_rpm"] for r in s["speeds"]] == pytest.approx([100, 825, 1550, 2275, 3000])
    assert all(r["dynamic_factor"] > 1 for r in s["speeds"])
    assert (tmp_path / "dyn" / "dynamics.png").exists()


@pytest.mark.parametrize("argv, words", [
    (["ratio", "--train", "ngw", "--teeth", "20"], "teeth = '20'"),
    (["ratio", "--train", "ngw", "--teeth", "20,x"], "teeth"),
    (["ratio", "--train", "ngw", "--teeth", "0,70"], "za = 0"),
    (["ratio", "--train", "internal", "--teeth", "45,44"], "z2 = 44"),
    (["ratio", "--train", "ngw", "--teeth", "20,70", "--eta-h", "1.5"], "--eta-h = 1.5"),
    (["ratio", "--train", "2kh"], "i-ab-h"),
    (["bearings", "--z2", "78"], "z2"),
    (["bearings", "--working-angle", "95"], "--working-angle"),
    (["bearings", "--torque", "-1"], "torque"),
    (["bearings", "--step", "0"], "step = 0.0"),
    (["bearings", "--rings", "0"], "rings = 0"),
    (["bearings", "--half-span", "nan"], "--half-span"),
    (["dynamics", "--stiffness", "/nonexistent.json"], "cannot be read"),
    (["dynamics", "--stiffness", "x", "--speeds", "0:10:3"], "speeds"),
    (["dynamics", "--stiffness", "x", "--speeds", "a,b"], "speeds"),
])
def test_bad_drive_input_is_one_line(argv, words, capsys, tmp_path):
    code = main(["drive", *argv])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1 and err[0].startswith("fegear: error:"), err
    assert words in err[0], err[0]


def test_bad_stiffness_file_and_bad_model_input(tmp_path, capsys):
    (tmp_path / "k.json").write_text('{"phase": [0, 0.5]}')
    assert main(["drive", "dynamics", "--stiffness", str(tmp_path / "k.json")]) == 2
    assert "not a mesh_stiffness.json" in capsys.readouterr().err
    ph = np.arange(4) / 4
    m = MeshStiffness(ph, np.full(4, 1e5), np.zeros(4), 10.0, 24, 25, 2.0, 5.0, np.full(4, 1.2e5))
    (tmp_path / "k.json").write_text(json.dumps(m.to_json()))
    for extra, name in ((["--J1", "0"], "J1"), (["--zeta", "-0.1"], "zeta"),
                        (["--torque", "0"], "torque")):
        assert main(["drive", "dynamics", "--stiffness", str(tmp_path / "k.json"),
                     *extra]) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and name in err[0], err


def _numeric_options():
    from fegear.cli import build_parser

    drive = build_parser()._subparsers._group_actions[0].choices["drive"]
    for name, parser in drive._subparsers._group_actions[0].choices.items():
        for act in parser._actions:
            if act.type in (int, float):
                yield pytest.param(name, act.option_strings[-1], id=f"{name} {act.dest}")


@pytest.mark.parametrize("command, option", list(_numeric_options()))
def test_every_numeric_drive_option_refuses_nan(command, option, tmp_path, capsys):
    ph = np.arange(4) / 4
    m = MeshStiffness(ph, np.full(4, 1e5), np.zeros(4), 10.0, 24, 25, 2.0, 5.0, np.full(4, 1.2e5))
    (tmp_path / "k.json").write_text(json.dumps(m.to_json()))
    need = {"ratio": ["--train", "ngw", "--teeth", "20,70"],
            "dynamics": ["--stiffness", str(tmp_path / "k.json"), "--speeds", "100"]}
    argv = ["drive", command, *need.get(command, []), f"{option}=nan"]
    try:
        code = main(argv)
    except SystemExit as exc:  # argparse: an int option does not parse nan
        code = exc.code
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1 and err[0].startswith("fegear: error:"), err

"""``fegear profile --out``'s drawings to manufacture from: both gears as DXF (and with --step
as STEP solids), the deviated teeth in files of their own, what they are in the summary; a
bad body input refused in one line, exit 2, nothing written."""

import json
import subprocess
import sys

import numpy as np
import pytest

from fegear.cli import main

#: a small pair: the drawings of its 16 and 15 teeth are written in a fraction of a second
SMALL = ["--z2", "16", "--z1", "15", "--positions", "4"]


@pytest.fixture(scope="module")
def profiled(tmp_path_factory):
    """One ``fegear profile --out --json`` for both tests below, a tooth deviated and the
    solids asked for (each run spends 4-5 s on the backlash); its folder and the summary read
    from the process's stdout, so that nothing of the CAD kernel's comes in between. Without
    --step no STEP file is written: tests/cli/test_cli.py's profile test."""
    out = tmp_path_factory.mktemp("drawings") / "out"
    r = subprocess.run([sys.executable, "-m", "fegear", "profile", *SMALL, "--pitch-deviation",
                        "1:3=5", "--step", "--face-width", "8", "--out", str(out), "--json"],
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    return out, json.loads(r.stdout)


def test_profile_out_writes_both_gears_drawings_and_the_deviated_ones(profiled):
    import ezdxf

    out, summary = profiled
    drawn = summary["drawings"]
    assert drawn["chord_error_um"] == pytest.approx(0.1)
    assert drawn["tip_round_mm"] == 0.25 and drawn["deviated"] == ["gear1"]
    assert drawn["gear2_rim_radius_mm"] == pytest.approx(16 + 2 * 0.6 + 6)     # r0 + 2 e1 + 3 m
    assert {"gear1_dxf", "gear2_dxf", "gear1_deviated_dxf"} <= set(summary["files"])
    assert "gear2_deviated_dxf" not in summary["files"]                 # gear 2 is exact
    exact = ezdxf.readfile(out / "gear1.dxf").modelspace().query("LWPOLYLINE")[0]
    moved = ezdxf.readfile(out / "gear1_deviated.dxf").modelspace().query("LWPOLYLINE")[0]
    a, b = np.array(exact.get_points("xy")), np.array(moved.get_points("xy"))
    assert np.allclose(np.hypot(*a.T), np.hypot(*b.T), rtol=0, atol=1e-12)   # teeth turned
    assert 0 < np.abs(a - b).max() < 6e-3                                    # by 5 µm
    csv = np.loadtxt(out / "gear1.csv", delimiter=",", skiprows=1)
    assert np.hypot(*a.T).max() == pytest.approx(np.hypot(*csv.T).max(), abs=1e-12)
    assert not [p for p in out.iterdir() if p.name.startswith(".")]


def test_profile_step_writes_each_gear_as_a_solid_and_keeps_json_clean(profiled):
    out, summary = profiled   # its JSON read whole: nothing of the CAD kernel's
    assert summary["drawings"]["face_width_mm"] == 8
    for gear in (1, 2):
        text = (out / f"gear{gear}.step").read_text()
        assert text.startswith("ISO-10303-21;") and "SI_UNIT(.MILLI.,.METRE.)" in text
        assert summary["files"][f"gear{gear}_step"] == str(out / f"gear{gear}.step")


@pytest.mark.parametrize("args,fragment", [
    (["--tip-round", "1.5"], "--tip-round = 1.5 is not admissible; admissible: 0 <= tip"),
    (["--rim1", "30"], "--rim1 = 30.0 is not admissible"),
    (["--rim2", "0.1"], "--rim2 = 0.1 is not admissible"),
    (["--face-width", "0"], "--face-width = 0.0 is not admissible"),
    (["--step"], "--step: with --out DIR"),
    (["--map", "h1,f1", "--step"], "--step: not with --map"),
    (["--map", "h1,f1", "--rim1", "6"], "--rim1: not with --map"),
])
def test_a_bad_drawing_input_is_one_line_and_writes_nothing(args, fragment, tmp_path, capsys):
    out = tmp_path / "out"
    words = ["profile", *SMALL, *args] + ([] if "--step" in args else ["--out", str(out)])
    assert main(words) == 2
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("fegear: error: " + fragment), lines
    assert not out.exists()

"""What the person at the terminal meets: defaults, errors that blame the input the user
changed, the torque the solve takes, a stop by signal, progress, a clean stderr, --version."""

import fcntl
import io
import os
import pty
import select
import signal
import struct
import subprocess
import sys
import termios
import time

import pytest

from fegear import __version__, progress
from fegear.cli import main
from fegear.cli.terminal import StageBar
from fegear.errors import ParameterError
from fegear.geometry import admissible_pair
from fegear.toothpair import prepare_job, run_job

FEGEAR = [sys.executable, "-m", "fegear"]
COARSE = ["--quality", "coarse", "--no-estimate"]


def run(*args, **kw):
    return subprocess.run([*FEGEAR, *args], capture_output=True, text=True, timeout=300, **kw)


def error_line(capsys) -> str:
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("fegear: error: "), err
    return err[0]


def test_solve_defaults_are_the_seed_papers_pair_as_built():
    job = prepare_job({})
    p, c = job.case.params, job.case
    assert (p.m, p.z2, p.z1, p.h1, p.f1) == (2.0, 45, 44, 0.3, 0.15)
    assert (p.shift, p.rotation) == (0.016, 0.002)      # Δ1, Δ2 [mm]
    assert (c.torque, c.quality, job.estimate) == (200.0, "standard", True)
    assert job.betas == (0.0,)


@pytest.mark.parametrize("values, shift, rotation", [
    ({"m": 1.0}, 0.008, 0.001),                 # 0.008 m and 0.001 m
    ({"m": 4.0, "h1": 0.05}, 0.032, 0.001 * 4),  # 0.008 m, 0.001 m below m h1/4 = 0.05
    ({"shift": 0.004}, 0.004, 0.001),         # too little backlash for 0.001 m = 0.002 mm:
                                               # halved until the pair is free
    ({"shift": 0.02, "rotation": 0.0}, 0.02, 0.0),  # given values win
])
def test_modification_defaults_follow_the_module(values, shift, rotation):
    p = admissible_pair(values)
    assert (p.shift, p.rotation) == pytest.approx((shift, rotation))


def test_version(capsys):
    with pytest.raises(SystemExit) as exc:
        main(["--version"])
    assert exc.value.code == 0
    assert capsys.readouterr().out.strip() == f"fegear {__version__}"


@pytest.mark.parametrize("args, blamed", [
    (["--h1", "0.9"], "--h1 = 0.9 "),        # only h1 changed: h1, though f1 fixes it too
    (["--f1", "0.5"], "--f1 = 0.5 "),
    (["--h1", "0.9", "--f1", "0.5"], "--f1 = 0.5 "),  # both: the curve loops, f1 unlooses it
])
def test_a_refused_design_blames_the_input_the_user_changed(tmp_path, capsys, args, blamed):
    out = tmp_path / "never"
    assert main(["solve", *args, "--out", str(out)]) == 2
    line = error_line(capsys)
    assert line.startswith(f"fegear: error: {blamed}")
    assert "shift = " not in line          # the default shift is never the culprit
    assert not out.exists()


def test_the_stated_h1_range_is_true():
    """The refusal's interval for h1, at the other inputs' values, holds at both its ends."""
    with pytest.raises(ParameterError) as exc:
        admissible_pair({"h1": 0.9}, given={"h1"})
    text = exc.value.admissible
    lo, hi = (float(x) for x in text.split(" at ")[0].split(" <= h1 <= "))
    for h1 in (lo, hi):
        admissible_pair({"h1": h1})                       # admitted
    with pytest.raises(ParameterError):
        admissible_pair({"h1": hi + 1e-3}, given={"h1"})  # just beyond: refused


def test_a_torque_beyond_the_limit_is_refused_before_anything_is_made(tmp_path, capsys):
    out = tmp_path / "o"
    assert main(["solve", "--torque", "1e5", "--out", str(out)]) == 2
    line = error_line(capsys)
    assert "torque = 100000.0 is not admissible" in line
    assert "torque <= 4532 N·m" in line          # 0.05 E m b r1 of the seed paper's pair
    assert not out.exists()


def test_the_solve_settles_at_its_torque_limit():
    """The stated range is the one the model takes: a small pair at its largest torque."""
    values = {"m": 1.0, "h1": 0.15, "f1": 0.1, "quality": "coarse", "no-estimate": True}
    limit = prepare_job(values).case.torque_limit
    assert limit == pytest.approx(0.05 * 206000 * 1.0 * 5.0 * 22.0 * 1e-3)
    result = run_job(prepare_job({**values, "torque": limit}), None)
    assert result.summary["torque_balance_error"] < 1e-9
    assert result.summary["teeth_in_contact"] > 2


def test_solve_without_out_prints_the_table_and_writes_nothing(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(["solve", *COARSE]) == 0
    text = capsys.readouterr().out
    assert "root σ1, gear 1" in text and "no files written" in text
    assert "for the whole command" in text.splitlines()[-1]
    assert list(tmp_path.iterdir()) == []


def test_stderr_stays_clean_off_a_terminal(tmp_path):
    """No progress bar into a pipe, no library noise (VTK's X-server line, colour codes)."""
    r = run("solve", *COARSE, "--out", str(tmp_path / "o"))
    assert r.returncode == 0
    assert r.stderr == ""
    assert (tmp_path / "o" / "von_mises.png").stat().st_size > 0


@pytest.mark.parametrize("signum", [signal.SIGTERM, pytest.param(signal.SIGINT,
                                                                  marks=pytest.mark.slow)])
def test_a_stopped_solve_leaves_no_out_behind(tmp_path, signum):
    """On a terminal the stages show; a stop during the solve is one line, and the --out
    directory (made only after the solve) does not appear."""
    out = tmp_path / "o"
    screen, tty = pty.openpty()
    fcntl.ioctl(tty, termios.TIOCSWINSZ, struct.pack("HHHH", 24, 100, 0, 0))  # 100 columns
    proc = subprocess.Popen([*FEGEAR, "solve", "--quality", "fast", "--out", str(out)],
                            stdout=subprocess.PIPE, stderr=tty, text=True)
    os.close(tty)
    seen = _read_until(screen, "contact at β")   # the progress bar: the solve is under way
    proc.send_signal(signum)
    proc.communicate(timeout=60)
    seen += _read_until(screen, None)
    os.close(screen)
    assert proc.returncode == 128 + signum, seen
    assert "stage 1/" in seen and "gear 1's profile" in seen
    lines = [x.split("\r")[-1] for x in seen.strip().splitlines()]
    assert lines[-1] == (f"fegear: stopped by {signal.Signals(signum).name}; nothing "
                         "half-written was left behind")
    assert not out.exists()


def _read_until(fd: int, text: str | None, timeout: float = 120.0) -> str:
    """What the terminal ``fd`` shows until ``text`` appears (None: until it closes)."""
    got, end = b"", time.monotonic() + timeout
    while time.monotonic() < end and (text is None or text.encode() not in got):
        ready, _, _ = select.select([fd], [], [], 0.5)
        if ready:
            try:
                chunk = os.read(fd, 4096)
            except OSError:   # the other end closed
                break
            if not chunk:
                break
            got += chunk
    return got.decode(errors="replace")


def test_the_stage_bar_shows_each_stage_and_the_estimate(monkeypatch):
    screen = io.StringIO()
    monkeypatch.setattr(sys, "stderr", screen)
    bar = StageBar(enabled=True)
    with progress.reporting(bar):
        run_job(prepare_job({"quality": "coarse", "positions": 2}), None)
    bar.close()
    text = screen.getvalue()
    for stage in ("gear 1's profile", "model: both gears meshed and condensed at quality "
                  "coarse", "contact at β 0° (1 of 2)", "(2 of 2)",
                  "error estimate: the same case again at quality fast"):
        assert stage in text
    assert "stage 5/5]" in text        # profile, model, two positions, estimate: as planned


def test_a_silent_bar_writes_nothing(monkeypatch):
    screen = io.StringIO()
    monkeypatch.setattr(sys, "stderr", screen)
    bar = StageBar(enabled=False)
    with progress.reporting(bar):
        progress.plan(2)
        progress.stage("a")
        progress.stage("b")
    bar.close()
    assert screen.getvalue() == ""


@pytest.mark.parametrize("argv", [["-q", "-v", "drive", "bearings"],
                                  ["drive", "bearings", "-q", "-v"],
                                  ["drive", "-v", "bearings", "-q"]])
def test_common_options_are_taken_before_or_after_the_command(argv):
    from fegear.cli import build_parser

    a = build_parser().parse_args(argv)
    assert (a.quiet, a.verbose) == (True, True)
    assert build_parser().parse_args(["drive", "bearings"]).quiet is False


def test_a_reader_that_goes_away_ends_the_command_quietly():
    read, write = os.pipe()
    os.close(read)               # the reader is gone before the first line, as `| head -0`
    proc = subprocess.run([*FEGEAR, "drive", "bearings"], stdout=write, stderr=subprocess.PIPE,
                          timeout=120)
    os.close(write)
    assert proc.stderr.decode() == ""
    assert proc.returncode == 128 + signal.SIGPIPE


def test_the_wall_time_is_the_whole_process():
    """Counted from the process's start: the sleep before fegear is imported included, and no
    more than the parent saw pass (psutil's start time was up to a second off)."""
    code = ("import time; time.sleep(1.0); from fegear.cli.terminal import command_wall_s; "
            "print(command_wall_s())")
    t0 = time.perf_counter()
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         timeout=120, check=True).stdout
    elapsed = time.perf_counter() - t0
    assert 1.0 <= float(out) <= elapsed + 0.02

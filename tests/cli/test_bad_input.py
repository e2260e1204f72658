"""Bad input at every CLI option: NaN, ±infinity, zero, negative and absurd values each give
exit code 2 and one line naming the parameter, before any work starts and before the output
directory is made.

The commands run in-process with their work replaced by a function that fails the test, so an
accepted value shows up as that failure instead of as a long solve."""

import os
from pathlib import Path

import pytest

import fegear.geometry
import fegear.optimize.job
import fegear.optimize.relief_rule
import fegear.running
import fegear.study
import fegear.toothpair.pair
import fegear.verify
from fegear.cli import main

NOT_FINITE = ["nan", "inf", "-inf"]

# option → values that must be rejected (each also gets NaN and ±inf)
PAIR = {
    "--m": ["0", "-2", "1e300"],
    "--z2": ["0", "-45", "44", "100000"],  # z2 <= z1 = 44 and absurd
    "--z1": ["0", "-44", "45", "2"],
    "--h1": ["0", "-0.3", "5"],
    "--f1": ["-0.15", "1.5"],
    "--shift": ["-0.016", "5"],
    "--rotation": ["-5", "5"],
    "--tip-clearance": ["-5", "5"],
    "--relief": ["-1", "1000"],
    "--relief-extent": ["0", "-0.5"],   # too long for the flank: tests/geometry/test_relief.py
    "--relief-start": ["0", "-44"],
}
MATERIAL = {"--face-width": ["0", "-5", "1e300"], "--E": ["0", "-206000", "1e300"],
            "--nu": ["-0.1", "0.5", "3"]}
ALLOWABLE = {"--allowable-bending": ["0", "-558", "1e300"],
             "--allowable-contact": ["0", "-745", "1e300"]}
OPTIONS = {
    "profile": {**PAIR, "--chord-error": ["0", "-1e-4", "1"], "--positions": ["0", "-16",
                                                                              "100000"],
                "--map-size": ["0", "-5", "1000"]},
    "hertz": {"--r1": ["0", "-10", "1e300"], "--r2": ["0", "-5", "1e300"],
              "--load": ["0", "-1000", "1e300"], **MATERIAL,
              "--quality": ["0", "-8", "1e9", "best"],
              "--penalty-factor": ["0", "-300", "1e300"]},
    "solve": {**PAIR, "--torque": ["0", "-200", "1e300"], "--position": ["400", "-400"],
              "--positions": ["1", "0", "-24", "100000"], **MATERIAL, **ALLOWABLE,
              "--quality": ["best"], "--tip-round": ["-0.25", "100"],
              "--rim1": ["0", "-6", "1e300"], "--rim2": ["0", "-6", "1e300"],
              "--extra-pairs": ["-1", "1000"],
              "--pitch-deviation": ["1:99=5", "3:1=5", "1:11=abc", "1:11=1e9", "11=5"],
              "--slope-deviation": ["1:11=1e9", "2:45=1"], "--form-deviation": ["1:11=x"],
              "--runout": ["1=-5@0", "3=5@0", "1=5@x", "1=1e9@0"],
              "--centre-distance-deviation": ["1e9", "-1e9"],
              "--deviations": ["missing.csv"]},
    "bench": {**PAIR, "--repeat": ["0", "-3", "100000"], "--cycle": ["1", "-24",
                                                                     "100000"],
              "--pair-quality": ["best"], "--torque": ["0", "-200", "1e300"],
              "--disk-levels": ["8", "0,4", "4,1e9", "4,x"],
              "--pair-levels": ["fast", "fast,best", ""],
              "--sector-levels": ["best", "fast,best", "coarse"],
              "--scaling": ["7", "45,x", "45.5"],
              "--study-cases": ["1", "-6", "100000"]},
    "relief": {**{k: v for k, v in PAIR.items() if k != "--relief"},
               "--torque": ["0", "-200", "1e300"], **MATERIAL, "--quality": ["best"],
               "--tip-round": ["-0.25", "100"],
               "--rim1": ["0", "-6", "1e300"], "--rim2": ["0", "-6", "1e300"],
               "--extra-pairs": ["-1", "1000"],
               "--cycle-positions": ["1", "0", "100000"], "--margin": ["-0.1", "3"],
               "--workers": ["0", "-2", "100000"]},
    "study": {"--workers": ["0", "-2", "100000"]},
    "optimize": {**PAIR, "--torque": ["0", "-200", "1e300"], **MATERIAL, **ALLOWABLE,
                 "--tip-round": ["-0.25", "100"], "--rim1": ["0", "-6", "1e300"],
                 "--rim2": ["0", "-6", "1e300"], "--extra-pairs": ["-1", "1000"],
                 "--trials": ["0", "-5", "1000000"], "--positions": ["1", "0", "100000"],
                 "--workers": ["0", "-2", "100000"], "--best": ["-1", "100"],
                 "--seed": ["-1", "99999999999"], "--quality": ["best"],
                 "--max-outer-diameter": ["0", "-100", "10"],
                 "--max-centre-distance": ["0", "-1", "0.2"],
                 "--min-backlash": ["-1"], "--max-backlash": ["-1"]},
    "drive": {},  # its options sit on its subcommands: tests/test_drive_cli.py
    "cache": {},  # no numeric option; its cap is FEGEAR_CACHE_GB: tests/cli/test_cache_cli.py
}
CHOICE = {"--sector-levels"}
INTEGER = {"--z1", "--z2", "--positions", "--extra-pairs", "--repeat",
           "--cycle", "--study-cases", "--workers", "--cycle-positions", "--trials", "--best",
           "--seed"}
ARGS = {"profile": ["--positions", "4"], "hertz": [], "solve": [], "bench": [], "drive": [],
        "relief": ["--relief-extent", "0.5"], "optimize": [],
        "study": [str(Path(__file__).resolve().parents[2] / "studies" / "paper_trends.toml")]}


def _cases():
    for command, options in OPTIONS.items():
        for option, values in options.items():
            extra = [] if option in INTEGER | CHOICE or option.endswith("quality") else NOT_FINITE
            for value in values + extra:
                # the relief command refuses a pair input as solve does, by a search over
                # relieved profiles (seconds): checked at solve, there only in the slow run
                slow = command == "relief" and option in PAIR and value not in NOT_FINITE
                yield pytest.param(command, option, value, id=f"{command} {option} {value}",
                                   marks=[pytest.mark.slow] if slow else [])


@pytest.fixture
def no_work(monkeypatch):
    def accepted(*args, **kwargs):
        raise AssertionError("the bad value was accepted: the work started")

    for module, name in ((fegear.geometry, "build_geometry"), (fegear.verify, "solve_disks"),
                         (fegear.toothpair.pair, "solve_positions"),
                         (fegear.verify, "geometry_bench"), (fegear.verify, "disk_ladder"),
                         (fegear.verify, "pair_ladder"), (fegear.verify, "ring_ladder"),
                         (fegear.verify, "run_fresh"), (fegear.study, "run_study"),
                         (fegear.verify, "study_overhead"), (fegear.optimize.job, "run_search"),
                         (fegear.optimize.relief_rule, "cycle_result")):
        monkeypatch.setattr(module, name, accepted)
    # `fegear solve` forks its spare core's picture processes as it starts (0.1-0.5 s a test,
    # 25 of the file's 70 CPU seconds): here its executor is this process; the checks are
    # the same
    monkeypatch.setattr(fegear.running, "spare_core", lambda *args, **kwargs: fegear.running.SERIAL)


@pytest.mark.parametrize("command,option,value", list(_cases()))
def test_bad_value_exits_2_with_one_line_naming_the_parameter(command, option, value,
                                                               tmp_path, capsys, no_work):
    out = tmp_path / "out"
    argv = [command, *ARGS[command], f"{option}={value}"]
    if command not in ("bench", "relief"):
        argv += ["--out", str(out)]
    try:
        code = main(argv)
    except SystemExit as exc:  # argparse: not a number
        code = exc.code
    err = capsys.readouterr().err
    lines = err.strip().splitlines()
    assert code == 2, err
    assert len(lines) == 1 and lines[0].startswith("fegear: error:"), err
    name = option[2:].replace("-", "_")
    assert name in lines[0] or option in lines[0], lines[0]
    assert "admissible" in lines[0] or "invalid" in lines[0], lines[0]
    assert not out.exists()


def _commands():
    """(argv of the command, its parser) of every command and subcommand."""
    import argparse

    from fegear.cli import build_parser

    def walk(parser, argv):
        subs = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
        if not subs:
            yield argv, parser
        for action in subs:
            for name, sub in action.choices.items():
                yield from walk(sub, [*argv, name])

    return list(walk(build_parser(), []))


def _numeric(parser):
    """The parser's options that take a number (argparse's type named int or float)."""
    return [a for a in parser._actions if a.option_strings
            and getattr(a.type, "__name__", None) in ("int", "float")]


def test_every_numeric_option_comes_from_a_schema_and_its_help_gives_range_and_default():
    # a new numeric option must be a schema row (fegear.checks.Input), so that its help, its
    # refusals and its checks come from one place
    rows = 0
    for argv, parser in _commands():
        schema = {row.dest: row for row in parser.inputs}
        for action in _numeric(parser):
            row = schema.get(action.dest)
            assert row is not None, (argv, action.option_strings, "not from add_inputs")
            assert row.range_text and f"; admissible: {row.range_text}" in action.help, (
                argv, action.help)
            assert row.default_text and f"; default: {row.default_text}" in action.help, (
                argv, action.help)
            rows += 1
    assert rows > 100


#: the words a command needs beside the option tried (a missing stiffness file is read only
#: once every option has passed)
BESIDE = {("study",): [str(Path(__file__).resolve().parents[2] / "studies"
                           / "paper_trends.toml")],
          ("drive", "ratio"): ["--train", "2kh"],
          ("drive", "dynamics"): ["--stiffness", "missing.json"]}


def _walk_cases():
    for argv, parser in _commands():
        schema = {row.dest: row for row in parser.inputs}
        for action in _numeric(parser):
            row = schema[action.dest]
            # relief refuses a pair input after a search over relieved profiles: slow
            slow = argv == ["relief"] and f"--{row.name}" in PAIR
            out = any("--out" in a.option_strings for a in parser._actions)
            yield pytest.param(argv, row, out, id=f"{' '.join(argv)} --{row.name}",
                               marks=[pytest.mark.slow] if slow else [])


def _outside(row) -> list[str]:
    """Values just outside the row's static range."""
    step = 1 if row.kind is int else 1e-3 * max(1.0, abs(row.low or 0), abs(row.high or 0))
    out = []
    if row.low is not None:
        out.append(repr(row.low if row.low_open else row.low - step))
    if row.high is not None:
        out.append(repr(row.high if row.high_open else row.high + step))
    return out


@pytest.mark.parametrize("argv,row,has_out", list(_walk_cases()))
def test_a_numeric_option_refuses_text_nan_and_outside_with_one_line_naming_its_range(
        argv, row, has_out, tmp_path, capsys, no_work):
    out = tmp_path / "out"
    told = {}
    for value in ["abc", "True", "nan", *_outside(row)]:
        words = [*argv, *BESIDE.get(tuple(argv), []), f"--{row.name}", value]
        if has_out:
            words += ["--out", str(out)]
        try:
            code = main(words)
        except SystemExit as exc:
            code = exc.code
        lines = capsys.readouterr().err.strip().splitlines()
        assert code == 2 and len(lines) == 1, (words, lines)
        head = f"fegear: error: --{row.name} = "
        assert lines[0].startswith(head) and " is not admissible" in lines[0], (words, lines)
        told[value] = lines[0].split("; admissible: ", 1)[-1]
        assert row.name in told[value], (words, lines)      # the range names the input
        assert not out.exists()
    # the same range whatever is wrong with the value; the schema's own where it is static
    assert len(set(told.values())) == 1, told
    if not row.limits:
        assert set(told.values()) == {row.range_text}, told


def test_the_torque_is_refused_with_its_upper_limit_at_the_given_inputs(capsys):
    # issue 54: `--torque abc`, `nan` and `-5` left out the 0.05 E m b r1 that 1e9 stated
    for value in ("abc", "nan", "-5", "0", "1e9"):
        assert main(["solve", "--torque", value, "--m", "1", "--face-width", "10"]) == 2
        line = capsys.readouterr().err.strip()
        assert line.endswith("admissible: 0 < torque <= 2266 N·m (0.05 E m b r1 at "
                             "E=206000 MPa, m=1, b=10, r1=22 mm)"), line


def test_outputs_are_written_atomically_with_ordinary_permissions(tmp_path):
    import os

    from fegear.files import write_atomic, write_json

    old = os.umask(0o027)
    try:
        path = write_json(tmp_path / "summary.json", {"a": 1})
    finally:
        os.umask(old)
    assert path.stat().st_mode & 0o777 == 0o640  # 0666 under the umask, not mkstemp's 0600

    def fails(tmp):
        tmp.write_text("half")
        raise OSError("no space left")

    with pytest.raises(OSError):
        write_atomic(tmp_path / "result.csv", fails)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["summary.json"]  # nothing left


@pytest.mark.parametrize("field,value", [
    (f, v) for f, values in {
        "torque": [0.0, -1.0, 1e300], "beta": [10.0, -7.0], "thickness": [0.0, -5.0, 1e300],
        "E": [0.0, -1.0, 1e300], "nu": [-0.1, 0.5], "quality": ["best", 3],
        "rim1": [0.0, -1.0, 1e300], "rim2": [0.0, 1e300],
        "extra_pairs": [-1, 1000, True], "tip_round": [-0.1, 100.0, True]}.items()
    for v in values + ([float("nan"), float("inf")] if f not in ("quality",) else [])])
def test_solve_case_rejects_bad_fields(field, value):
    from fegear.errors import ParameterError
    from fegear.geometry.parameters import PairParameters
    from fegear.toothpair.case import SolveCase

    with pytest.raises(ParameterError) as err:
        SolveCase(PairParameters(), **{field: value})
    renamed = {"beta": "position", "thickness": "face-width"}
    assert err.value.name == renamed.get(field, field.replace("_", "-"))


@pytest.mark.parametrize("field,value", [
    (f, v) for f, values in {
        "r1": [0.0, -1.0, 1e300, True], "r2": [0.0, 1e300, -5.0],
        "load": [0.0, -1.0, 1e300, False],
        "thickness": [0.0, 1e300], "E": [0.0, 1e300], "nu": [0.5, -1.0],
        "quality": ["best", 0, 1e9, True], "penalty_factor": [0.0, 1e300, True]}.items()
    for v in values + ([float("nan"), float("-inf")] if f != "quality" else [])])
def test_disk_case_rejects_bad_fields(field, value):
    from fegear.errors import ParameterError
    from fegear.verify import DiskCase

    with pytest.raises(ParameterError) as err:
        DiskCase(**{field: value})
    assert err.value.name == {"thickness": "face-width"}.get(field, field.replace("_", "-"))


def test_contact_peer_without_calculix_is_one_line_and_writes_nothing(tmp_path, capsys,
                                                                      monkeypatch):
    import fegear.verify.calculix

    monkeypatch.setattr(fegear.verify.calculix, "ccx_available", lambda: False)
    out = tmp_path / "out"
    code = main(["bench", "--contact-peer", "--out", str(out)])
    lines = capsys.readouterr().err.strip().splitlines()
    assert code != 0
    assert len(lines) == 1 and "ccx" in lines[0] and "calculix-ccx" in lines[0], lines
    assert not out.exists()


def test_the_hertz_penalty_default_is_the_contact_models():
    from fegear.verify.disk_inputs import PENALTY_FACTOR
    from fegear.verify.penalty import ContactSettings

    assert PENALTY_FACTOR == ContactSettings.penalty_factor


#: every command that writes into --out, with the words it needs beside it
WRITERS = [["solve"], ["solve", "--positions", "24"], ["profile"], ["profile", "--map", "h1,f1"],
           ["hertz"], ["bench"], ["optimize"], ["study", *BESIDE[("study",)]],
           ["drive", "bearings"], ["drive", "dynamics", *BESIDE[("drive", "dynamics")]],
           ["drive", "reducer"]]


def _unwritable(tmp_path) -> list[Path]:
    """--out paths that cannot be made: under a regular file, and as root (whom os.access
    lets write anywhere) in /proc."""
    blocker = tmp_path / "file"
    blocker.write_text("x")
    paths = [blocker / "a" / "b"]
    if os.geteuid() == 0:
        paths.append(Path("/proc/fegear-out-test"))
    return paths


@pytest.mark.parametrize("argv", WRITERS, ids=" ".join)
def test_an_out_that_cannot_be_made_is_refused_before_any_work(argv, tmp_path, capsys,
                                                               no_work, monkeypatch):
    import fegear.drive
    import fegear.drive.reducer_report

    def accepted(*args, **kwargs):
        raise AssertionError("the work started before --out was checked")

    monkeypatch.setattr(fegear.drive, "bearings_summary", accepted)
    monkeypatch.setattr(fegear.drive.reducer_report, "reducer_summary", accepted)
    for out in _unwritable(tmp_path):
        assert main([*argv, "--out", str(out)]) == 2
        lines = capsys.readouterr().err.strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith(f"fegear: error: --out '{out}'"), lines
    assert not Path("/proc/fegear-out-test").exists()


def test_checking_an_out_leaves_nothing_behind(tmp_path):
    from fegear.files import OutputError, check_dir, prepare_dir

    assert check_dir(tmp_path / "new" / "deeper") == tmp_path / "new" / "deeper"
    assert check_dir(tmp_path) == tmp_path
    assert list(tmp_path.iterdir()) == []        # neither the probe nor the new folders
    made = prepare_dir(tmp_path / "made")
    assert made.is_dir() and list(made.iterdir()) == []
    (tmp_path / "made" / "file").write_text("x")
    with pytest.raises(OutputError, match="is a file, not a directory"):
        check_dir(tmp_path / "made" / "file")
    with pytest.raises(OutputError, match="'.*file' is a file, not a directory"):
        check_dir(tmp_path / "made" / "file" / "sub")

"""Parameter studies: the study file's checks, the runner (kill and restart, a dying worker,
a failing case) and the same table from a local Dask cluster as from the local pool."""

from __future__ import annotations

import csv
import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from fegear.cli import main
from fegear.study.file import Outputs, StudyError, build_study, case_key, load_study

ROOT = Path(__file__).resolve().parents[2]

# four cheap real solves (a 25/24 pair, coarse, no second level) and one that fails in the
# solve (made to by failing/sitecustomize.py: no admissible design fails), which must not stop
# the study
SMALL = """
[study]
name = "small"
[base]
quality = "coarse"
z2 = 25
z1 = 24
shift = 0.016
rotation = 0.002
no-estimate = true
[[sweep]]
torque = [5, 10, 15, 20]
[[sweep]]
torque = 10
position = 1.5
"""
#: the folder whose sitecustomize makes the 10 N·m case at β = 1.5° fail in its solve
FAILING = Path(__file__).parent / "failing"
N_SMALL = 5
# columns that say when, where and how fast, not what
VOLATILE = ("wall_s", "case_wall_s", "solve_s", "host", "pid", "finished_utc", "timings_s.",
            "cycle.solve_s")


def _study(tmp_path: Path, text: str, name: str = "s.toml"):
    path = tmp_path / name
    path.write_text(text)
    return load_study(path)


def _records(out: Path) -> dict[str, tuple[bytes, int]]:
    return {p.name: (p.read_bytes(), p.stat().st_mtime_ns)
            for p in (out / "cases").glob("*.json") if not p.name.startswith(".")}


def _table(out: Path) -> list[dict]:
    with open(out / "results.csv", newline="") as f:
        return list(csv.DictReader(f))


def _same(a: dict, b: dict) -> None:
    """Two CSV rows agree in every column but the volatile ones; numbers (also in lists and
    in the per-tooth records) to 1e-9 relative, since residuals of 1e-13 and least-squares
    fits differ in the last digit between processes."""
    assert list(a) == list(b)
    for k in a:
        if k.startswith(VOLATILE) or a[k] == b[k]:
            continue
        _close(json.loads(a[k]), json.loads(b[k]), k)  # not equal as text: must be numbers


def _close(x, y, where: str) -> None:
    if isinstance(x, dict):
        assert isinstance(y, dict) and list(x) == list(y), where
        for k in x:
            _close(x[k], y[k], f"{where}.{k}")
    elif isinstance(x, list):
        assert isinstance(y, list) and len(x) == len(y), where
        for i, (u, v) in enumerate(zip(x, y)):
            _close(u, v, f"{where}[{i}]")
    elif isinstance(x, (int, float)) and not isinstance(x, bool):
        assert x == pytest.approx(y, rel=1e-9, abs=1e-12), where
    else:
        assert x == y, where


def _wait_for(cond, proc, what: str, timeout: float = 300.0) -> None:
    t = time.monotonic()
    while not cond():
        if proc.poll() is not None:
            raise AssertionError(f"the study ended (exit {proc.returncode}) before {what}: "
                                 + proc.stderr.read())
        if time.monotonic() - t > timeout:
            proc.kill()
            raise AssertionError(f"timed out waiting for {what}")
        time.sleep(0.1)


def _failing_env() -> dict:
    """The environment of a study process whose 10 N·m case at β = 1.5° fails in its solve:
    this process's as it is now (the session's model cache, tests/conftest.py), not as it was
    when this module was imported."""
    return {**os.environ, "PYTHONPATH": os.pathsep.join(
        [str(FAILING), *filter(None, [os.environ.get("PYTHONPATH")])])}


def _start(toml: Path, out: Path) -> subprocess.Popen:
    """The study of ``toml`` started into ``out``, to be stopped or killed: its temporary
    folders (a worker killed mid-case cannot remove its case's) in pytest's own temporary
    folder, beside the test's (which some tests check holds nothing else), not in /tmp."""
    tmp = toml.parent.parent / f"{toml.parent.name}-tmp"
    tmp.mkdir(exist_ok=True)
    return subprocess.Popen([sys.executable, "-m", "fegear", "study", str(toml), "--workers",
                             "1", "--out", str(out), "--no-progress"], cwd=ROOT,
                            env={**_failing_env(), "TMPDIR": str(tmp)},
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


# --- the study file ---------------------------------------------------------------------------

def test_sweeps_expand_ranges_products_and_zips(tmp_path):
    s = _study(tmp_path, """
[base]
torque = 50
[[sweep]]
h1 = {start = 0.2, stop = 0.4, step = 0.05}
[[sweep]]
m = [1.5, 2.5]
f1 = {start = 0.1, stop = 0.2, num = 3}
[[sweep]]
combine = "zip"
m = [1.0, 3.0]
torque = [20, 30]
""")
    got = [c.swept for c in s.cases]
    assert got[:5] == [{"h1": v} for v in (0.2, 0.25, 0.3, 0.35, 0.4)]  # stop included, no
    assert got[5:11] == [{"m": m, "f1": f} for m in (1.5, 2.5) for f in (0.1, 0.15, 0.2)]
    assert got[11:] == [{"m": 1.0, "torque": 20.0}, {"m": 3.0, "torque": 30.0}]
    assert all(c.values["torque"] == c.swept.get("torque", 50.0) for c in s.cases)
    assert s.varied == ("m", "h1", "f1", "torque")
    assert [c.index for c in s.cases] == list(range(13))


def test_a_case_two_sweeps_produce_runs_once(tmp_path):
    s = _study(tmp_path, """
[[sweep]]
m = [1.5, 2.0]
[[sweep]]
h1 = [0.3, 0.35]
""")  # m 2.0 and h1 0.3 are both the default case
    assert len(s.cases) == 3
    assert len({c.key for c in s.cases}) == 3


def test_key_follows_inputs_outputs_and_code_not_spelling():
    k = case_key({"m": 2.0}, Outputs(), "v1")
    assert case_key({}, Outputs(), "v1") == k  # 2.0 is the default module
    assert case_key({"m": 2.5}, Outputs(), "v1") != k
    assert case_key({"m": 2.0}, Outputs(vtu=True), "v1") != k
    assert case_key({"m": 2.0}, Outputs(), "v2") != k
    # the allowable stresses only read the results: they leave the key (and the cached
    # solve) alone
    assert case_key({"m": 2.0, "allowable-bending": 400.0, "allowable-contact": 1000.0},
                    Outputs(), "v1") == k


def test_cases_apart_in_allowables_alone_share_a_key_not_a_row(tmp_path):
    s = _study(tmp_path, "[[sweep]]\nallowable-contact = [700, 800]\nm = [1.5, 2.0]\n")
    assert len(s.cases) == 4 and len({c.key for c in s.cases}) == 2
    assert s.varied == ("m", "allowable-contact")


@pytest.mark.parametrize("text, words", [
    ("[base]\ntip_clearance = 0.01", ["[base]", "'tip_clearance'", "did you mean 'tip-clearance'"]),
    ("[base]\ntip-relief = 0.01", ["[base]", "'tip-relief'", "renamed: now tip-clearance"]),
    ("[base]\nh1 = 'big'", ["[base] h1", "must be a number"]),
    ("[base]\nz1 = 44.0", ["[base] z1", "must be an integer"]),
    ("[base]\nno-estimate = 1", ["[base] no-estimate", "true or false"]),
    ("[outputs]\nvtk = true", ["[outputs]", "'vtk'", "did you mean 'vtu'"]),
    ("[sweeps]\nm = [1]", ["unknown section 'sweeps'", "did you mean 'sweep'"]),
    ("[[sweep]]\nh1 = [0.85, 0.9]", ["all 2 cases are refused; the first, [[sweep]] 1 "
                                     "(h1 = 0.85): h1 = 0.85 is not admissible", "admissible: "]),
    ("[[sweep]]\nm = []", ["[[sweep]] 1 m", "at least one value"]),
    ("[[sweep]]\nm = {start = 1, stop = 2}", ["[[sweep]] 1 m", "{start, stop, step}"]),
    ("[[sweep]]\nm = {start = 1, stop = 2, step = -1}", ["[[sweep]] 1 m.step", "non-zero"]),
    ("[[sweep]]\ncombine = 'zip'\nm = [1, 2]\nh1 = [0.2, 0.3, 0.4]", ["zip", "m 2, h1 3"]),
    ("[[sweep]]\ncombine = 'all'\nm = [1, 2]", ["combine = 'all'", "\"product\" or \"zip\""]),
    ("[[sweep]]\ncombine = 'zip'", ["[[sweep]] 1", "sweeps nothing"]),
    ("[base]\nquality = 'best'", ["[base]", "quality = 'best' is not admissible",
                                  "coarse / fast / standard / fine"]),
    ("[base]\ntorque = -5", ["[base]", "torque = -5.0 is not admissible"]),
    ("[study]\nname = 'a b'", ["[study] name", "letters, digits"]),
    ("m = [1", ["not valid TOML"]),
])
def test_bad_study_file_names_file_key_and_reason(tmp_path, text, words):
    with pytest.raises(StudyError) as exc:
        _study(tmp_path, text, "bad.toml")
    msg = str(exc.value)
    assert msg.startswith(str(tmp_path / "bad.toml"))
    assert "\n" not in msg
    for w in words:
        assert w in msg


def test_an_inadmissible_case_is_set_aside_with_its_reason_and_the_others_kept(tmp_path):
    s = _study(tmp_path, "[[sweep]]\nh1 = [0.3, 0.9, 0.35]\n", "x.toml")
    assert [(c.index, c.swept) for c in s.cases] == [(0, {"h1": 0.3}), (2, {"h1": 0.35})]
    (refused,) = s.refused
    assert (refused.index, refused.swept, refused.block) == (1, {"h1": 0.9}, "[[sweep]] 1")
    assert refused.values["h1"] == 0.9 and s.varied == ("h1",)
    # the line a study refused whole for it gave before: the input, its value, the range
    line = refused.describe(s.path)
    assert line.startswith(f"{tmp_path / 'x.toml'}: [[sweep]] 1 (h1 = 0.9): h1 = 0.9 is not "
                           "admissible (the gear-2 curve folds back")
    assert "; admissible: 0.0500 <= h1 <= 0.83" in line and "\n" not in line


def test_cli_bad_study_is_one_line_and_creates_nothing(tmp_path, capsys):
    (tmp_path / "bad.toml").write_text("[[sweep]]\nf1 = [0.5]\n")
    out = tmp_path / "out"
    assert main(["study", str(tmp_path / "bad.toml"), "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("fegear: error: ") and "f1 = 0.5 is not admissible" in err
    assert "\n" not in err and not out.exists()
    assert main(["study", str(tmp_path / "none.toml")]) == 2
    assert "cannot be read" in capsys.readouterr().err
    assert main(["study", str(tmp_path / "bad.toml"), "--workers", "0"]) == 2
    assert "workers = 0 is not admissible" in capsys.readouterr().err
    # the cases of test_bad_study_file_names_file_key_and_reason: at m 1.5 as well, their
    # refusals took 4 s more
    (tmp_path / "all.toml").write_text("[[sweep]]\nh1 = [0.85, 0.9]\n")
    assert main(["study", str(tmp_path / "all.toml"), "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith(f"fegear: error: {tmp_path / 'all.toml'}: all 2 cases are refused")
    assert "\n" not in err and not out.exists()


def test_shipped_studies_load():
    for path in sorted((ROOT / "studies").glob("*.toml")):
        s = load_study(path)
        assert s.cases and s.varied, path


def test_an_input_zipped_with_the_plotted_one_goes_with_it_a_product_splits_the_lines():
    """paper_trends_relieved zips a relief per case with h1: the h1 plot is one line through
    its cases and the m = 2 case (h1 0.30); a product of torque and shift is one line per
    shift."""
    from fegear.study.results import tied_inputs

    s = load_study(ROOT / "studies" / "paper_trends_relieved.toml")
    rows = [{"case": c.index, "status": "ok"} for c in s.cases]
    assert tied_inputs(s, rows, "h1") == ["relief"] and tied_inputs(s, rows, "m") == ["relief"]
    assert tied_inputs(s, rows, "relief") == []
    p = build_study({"base": {}, "sweep": [{"torque": [10.0, 20.0], "shift": [0.008, 0.01]}]},
                    Path("x"))
    rows = [{"case": c.index, "status": "ok"} for c in p.cases]
    assert tied_inputs(p, rows, "torque") == [] and tied_inputs(p, rows, "shift") == []


def test_a_swept_deviation_is_an_input_of_its_own_plotted_in_the_file_s_order():
    from fegear.study.results import study_plot

    s = load_study(ROOT / "studies" / "pitch_deviation.toml")
    assert s.varied == ("pitch-deviation",) and len({c.key for c in s.cases}) == 4
    rows = [{"case": c.index, "key": c.key, "status": "ok", "torque": 200.0,
             "allowable-bending": 558.0, "allowable-contact": 745.0,
             **{k: 1.0 for k in ("root_stress_gear1_MPa", "root_stress_gear2_MPa",
                                 "contact_pressure_MPa", "flank_contact_pressure_MPa",
                                 "von_mises_max_MPa")}, **c.values} for c in s.cases]
    plot = study_plot(s, rows[::-1], "pitch-deviation")
    assert plot.lines[0].x == ("1:11=0", "1:11=2", "1:11=5", "1:11=10")


#: what a life rating wants beside its spectrum: a deviated pair's over a revolution
RATED = {"positions": 2, "revolution": True}


@pytest.mark.parametrize("name, file, text, other", [
    ("deviations", "measured.csv", "gear, tooth, fp [µm]\n1, 11, 4.0\n",
     "gear, tooth, fp [µm]\n1, 11, 5.0\n"),
    ("spectrum", "duty.csv", "torque,cycles\n100,1e6\n", "torque,cycles\n100,2e6\n"),
    ("material", "steel.toml", 'treatment = "nitrided"\nsigma_Hlim = 1000\nsigma_FE = 740\n',
     'treatment = "nitrided"\nsigma_Hlim = 1000\nsigma_FE = 700\n'),
])
def test_a_file_input_is_found_beside_the_study_and_keyed_by_what_it_holds(tmp_path, name,
                                                                          file, text, other):
    (tmp_path / "duty.csv").write_text("torque,cycles\n100,1e6\n")
    doc = {"base": {**RATED, "spectrum": "duty.csv", name: file},
           "sweep": [{"torque": [100.0, 200.0]}]}
    (tmp_path / file).write_text(text)
    first = build_study(doc, tmp_path / "a.toml")
    assert first.cases[0].values[name] == str(tmp_path / file)
    elsewhere = tmp_path / "copy"
    elsewhere.mkdir()
    (elsewhere / "duty.csv").write_text("torque,cycles\n100,1e6\n")
    (elsewhere / file).write_text(text)
    assert [c.key for c in build_study(doc, elsewhere / "a.toml").cases] == [
        c.key for c in first.cases]                      # the same file: its results
    (tmp_path / file).write_text(other)
    assert not {c.key for c in build_study(doc, tmp_path / "a.toml").cases} & {
        c.key for c in first.cases}                      # another one: solved again


def test_a_spectrum_without_positions_is_rated_over_the_default_cycle(tmp_path):
    # as `fegear solve --spectrum` alone: a case is rated over 24 positions, not refused
    (tmp_path / "duty.csv").write_text("torque,cycles\n100,1e6\n")
    s = build_study({"base": {"spectrum": "duty.csv"}, "sweep": [{"torque": [100.0, 200.0]}]},
                    tmp_path / "a.toml")
    assert not s.refused and len(s.cases) == 2


def test_a_material_of_the_table_is_a_name_not_a_file(tmp_path):
    (tmp_path / "duty.csv").write_text("torque,cycles\n100,1e6\n")
    doc = {"base": {**RATED, "spectrum": "duty.csv", "material": "20CrMnTi"},
           "sweep": [{"torque": [100.0, 200.0]}]}
    assert build_study(doc, tmp_path / "a.toml").cases[0].values["material"] == "20CrMnTi"


def test_build_study_accepts_a_parsed_document(tmp_path):
    s = build_study({"base": {"torque": 50}, "sweep": [{"m": [1.5, 2.0]}]}, tmp_path / "x")
    assert s.name == "x" and [c.values["m"] for c in s.cases] == [1.5, 2.0]


# --- the runner, on real solves ---------------------------------------------------------------

@pytest.fixture(scope="module")
def pool_run(tmp_path_factory):
    """The small study killed twice mid-run by a real signal (SIGTERM, then SIGKILL), then run
    to the end: the records in the folder after each stage, the outputs of the last run."""
    tmp = tmp_path_factory.mktemp("pool")
    toml, out = tmp / "small.toml", tmp / "out"
    toml.write_text(SMALL)
    stages = []
    for sig in (signal.SIGTERM, signal.SIGKILL):
        before = len(_records(out)) if out.exists() else 0
        proc = _start(toml, out)
        _wait_for(lambda b=before: out.exists() and len(_records(out)) > b, proc,
                  "a case finished")
        proc.send_signal(sig)
        proc.wait(timeout=60)
        stages.append({"signal": sig, "returncode": proc.returncode,
                       "stderr": proc.stderr.read(), "records": _records(out),
                       "table": _table(out) if (out / "results.csv").exists() else [],
                       "lock": (out / ".lock").exists()})
    final = subprocess.run([sys.executable, "-m", "fegear", "study", str(toml), "--workers",
                            "1", "--out", str(out), "--no-progress"], cwd=ROOT,
                           env=_failing_env(), capture_output=True, text=True, timeout=600)
    assert final.returncode == 0, final.stderr
    return {"out": out, "stages": stages, "final": final, "records": _records(out)}


def test_killed_study_restarts_without_losing_duplicating_or_recomputing(pool_run):
    term, kill = pool_run["stages"]
    assert term["returncode"] == 128 + signal.SIGTERM
    assert "stopped by SIGTERM" in term["stderr"] and "Traceback" not in term["stderr"]
    assert not term["lock"] and kill["lock"]   # SIGKILL leaves its lock, for the next run
    # SIGTERM leaves a table of exactly the finished cases
    assert {r["key"] + ".json" for r in term["table"]} == set(term["records"])
    assert kill["returncode"] == -signal.SIGKILL
    # its workers removed the pool's semaphores: no resource tracker warning
    assert "leaked" not in kill["stderr"] and "Traceback" not in kill["stderr"]
    assert len(term["records"]) < len(kill["records"]) < N_SMALL
    final = pool_run["records"]
    assert len(final) == N_SMALL
    # every record written before a kill is still the same file: nothing was recomputed
    for stage in (term, kill):
        for name, (data, mtime) in stage["records"].items():
            assert final[name] == (data, mtime)
    found = len(kill["records"])
    assert (f"{N_SMALL} cases: {found} found finished, {N_SMALL - found} computed (1 failed)"
            in pool_run["final"].stdout)
    table = _table(pool_run["out"])
    assert len(table) == N_SMALL and len({r["key"] for r in table}) == N_SMALL
    assert [int(r["case"]) for r in table] == list(range(N_SMALL))
    assert not (pool_run["out"] / "cases" / ".running").exists()   # the markers go with
    assert not (pool_run["out"] / ".lock").exists()                # the run, as the lock


def _tree(root: Path) -> dict[str, tuple[bytes, int] | None]:
    """Every folder (None) and file (bytes, mtime) below ``root``, by relative path."""
    return {str(p.relative_to(root)): (p.read_bytes(), p.stat().st_mtime_ns) if p.is_file()
            else None for p in root.rglob("*")}


def _stop_in_first_case(toml: Path, out: Path, sig: int) -> subprocess.CompletedProcess:
    """Start the study, stop it with ``sig`` while its 7 N·m case solves (it never finishes:
    failing/sitecustomize.py), and wait for it."""
    proc = _start(toml, out)
    running = out / "cases" / ".running"
    _wait_for(lambda: running.is_dir() and any(running.iterdir()), proc, "a case started")
    proc.send_signal(sig)
    stdout, stderr = proc.communicate(timeout=60)
    return subprocess.CompletedProcess(proc.args, proc.returncode, stdout, stderr)


# SIGINT's case in the slow run: the supervisor notes both signals by one handler, for both
# tested in tests/running/test_supervisor.py (test_a_signal_is_noted_and_ends_the_waiting)
@pytest.mark.parametrize("sig", [signal.SIGTERM,
                                 pytest.param(signal.SIGINT, marks=pytest.mark.slow)])
def test_a_study_stopped_before_its_first_case_finished_leaves_no_folder(tmp_path, sig):
    toml = tmp_path / "hang.toml"
    toml.write_text(SMALL.split("[[sweep]]")[0] + "[[sweep]]\ntorque = [7, 20]\n")
    done = _stop_in_first_case(toml, tmp_path / "new" / "out", sig)
    assert done.returncode == 128 + sig, done.stderr
    assert (f"stopped by {signal.Signals(sig).name} before any case finished; nothing was "
            "kept") in done.stderr
    assert "Traceback" not in done.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["hang.toml"]   # nor its parent


def test_a_resumed_study_stopped_before_a_case_finished_is_left_as_it_was(pool_run,
                                                                          tmp_path):
    import shutil

    out = tmp_path / "out"
    shutil.copytree(pool_run["out"], out)
    toml = tmp_path / "small.toml"
    toml.write_text(SMALL + "[[sweep]]\ntorque = 7\n")
    before = _tree(out)
    done = _stop_in_first_case(toml, out, signal.SIGTERM)
    assert done.returncode == 128 + signal.SIGTERM, done.stderr
    assert "the finished cases are kept" in done.stderr and "Traceback" not in done.stderr
    assert _tree(out) == before   # no marker, no study.json, no table rewritten


def test_failed_case_is_recorded_with_its_reason(pool_run):
    rows = {r["case"]: r for r in _table(pool_run["out"])}
    bad = rows["4"]
    assert bad["status"] == "failed" and bad["position"] == "1.5"
    assert bad["error"].startswith("GeometryError: injected by the study tests")
    assert bad["root_stress_gear1_MPa"] == ""
    assert all(rows[str(i)]["status"] == "ok" for i in range(4))


def test_study_table_holds_solve_outputs_and_versions(pool_run):
    import pyarrow.parquet as pq

    rows = _table(pool_run["out"])
    par = pq.read_table(pool_run["out"] / "results.parquet").to_pylist()
    assert [r["key"] for r in par] == [r["key"] for r in rows]
    rec = json.loads((pool_run["out"] / "cases" / f"{rows[1]['key']}.json").read_text())
    for k, v in rec["summary"].items():  # every value of `fegear solve --json`
        if not isinstance(v, (dict, list)):
            assert par[1][k] == v, k
    tooth, share = next(iter(rec["summary"]["load_share"].items()))
    assert par[1][f"load_share.{tooth}"] == share
    assert json.loads(par[1]["teeth"]) == rec["summary"]["teeth"]
    assert par[1]["versions.scikit-fem"] == "12.0.2" and par[1]["fegear"]
    assert par[1]["torque"] == 10.0 and par[1]["z1"] == 24 and par[1]["no-estimate"] is True
    # the trend a coarse run must show: root stresses and contact pressure grow with torque
    ok = [r for r in par if r["status"] == "ok"]
    for k in ("root_stress_gear1_MPa", "root_stress_gear2_MPa", "contact_pressure_MPa"):
        assert all(a[k] < b[k] for a, b in zip(ok, ok[1:])), k
    # 10 N·m: the whole ring (the sector model with one tooth beyond the paired ones gave
    # 32.4 MPa, with four 40.0: its free cut faces)
    assert ok[1]["root_stress_gear1_MPa"] == pytest.approx(40.0, abs=0.5)
    assert (pool_run["out"] / "plots" / "torque.png").stat().st_size > 10_000


@pytest.mark.slow  # 10-20 s: the default suite stays under 5 min
def test_dask_cluster_gives_the_local_pool_table(pool_run, tmp_path, monkeypatch):
    distributed = pytest.importorskip("distributed")
    from fegear.study.runner import run_study

    study = load_study(pool_run["out"] / ".." / "small.toml")
    monkeypatch.setenv("PYTHONPATH", _failing_env()["PYTHONPATH"])   # the workers' failing case
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster:
        report = run_study(study, tmp_path / "dask", scheduler=cluster.scheduler_address,
                           progress=False)
    assert (report.computed, report.failed) == (N_SMALL, 1)
    dask, pool = _table(tmp_path / "dask"), _table(pool_run["out"])
    assert len(dask) == len(pool) == N_SMALL
    for a, b in zip(dask, pool):
        _same(a, b)


# slow (5 s of processes): in the default run the supervisor sends a dead worker's task to a
# fresh pool (tests/running/test_supervisor.py's test_a_task_that_kills_its_worker_is_given_up_
# after_its_retries_the_others_finish) and the design search loses no trial to a worker killed
# mid-run (tests/optimize/test_optimize.py, the search stopped, killed and short of a worker)
@pytest.mark.slow
def test_worker_that_dies_costs_its_case_a_rerun_not_the_study(tmp_path):
    import psutil

    toml, out = tmp_path / "small.toml", tmp_path / "out"
    toml.write_text(SMALL.replace("[5, 10, 15, 20]", "[5, 10]"))
    proc = _start(toml, out)
    running = out / "cases" / ".running"
    _wait_for(lambda: running.exists() and any(running.iterdir()), proc, "a case started")
    victim = int(next(running.iterdir()).name.split(".")[1])
    assert victim in {p.pid for p in psutil.Process(proc.pid).children()}
    os.kill(victim, signal.SIGKILL)
    stdout, stderr = proc.communicate(timeout=600)
    assert proc.returncode == 0, stderr
    assert "a worker process died" in stderr
    assert "3 cases: 0 found finished, 3 computed (1 failed)" in stdout
    assert [r["status"] for r in _table(out)] == ["ok", "ok", "failed"]


@pytest.mark.slow  # 10-20 s: the default suite stays under 5 min
def test_unreachable_scheduler_is_one_line_and_creates_nothing(tmp_path, capsys):
    (tmp_path / "s.toml").write_text("[[sweep]]\nm = [1.5, 2.0]\n")
    out = tmp_path / "out"
    code = main(["study", str(tmp_path / "s.toml"), "--scheduler", "tcp://127.0.0.1:9",
                 "--out", str(out)])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1
    assert err[0].startswith("fegear: error: --scheduler 'tcp://127.0.0.1:9': cannot connect")
    assert not out.exists()


def test_a_study_runs_its_admissible_cases_and_lists_the_refused_ones(tmp_path, capsys):
    """h1 0.95 folds gear 2's curve back: that case is said at the start, listed under the
    table and in it (status refused, the reason in `error`) and in study.json; the other
    runs."""
    from fegear.study import load_results

    toml, out = tmp_path / "s.toml", tmp_path / "out"
    toml.write_text(SMALL.split("[[sweep]]")[0] + "[[sweep]]\ntorque = 20\nh1 = [0.3, 0.95]\n")
    assert main(["study", str(toml), "--workers", "1", "--out", str(out)]) == 0
    std = capsys.readouterr()
    reason = "h1 = 0.95 is not admissible (the gear-2 curve folds back"
    head = std.err.splitlines()
    assert "2 cases, varying h1 (0 finished before, 1 to compute, 1 refused)" in head[0]
    assert head[1].startswith(f"refused: {toml}: [[sweep]] 1 (torque = 20.0, h1 = 0.95): "
                              + reason)
    assert "admissible: 0.0500 <= h1 <= 0.8260 at f1=0.15, m=2, z2=25, z1=24" in head[1]
    assert "| 0.95 | – |" in std.out and "refused (below)" in std.out
    assert f"* case 1 (h1 = 0.95): {reason}" in std.out
    assert "2 cases: 0 found finished, 1 computed (0 failed), 1 refused" in std.out
    df = load_results(out)
    assert list(df["status"]) == ["ok", "refused"] and list(df["h1"]) == [0.3, 0.95]
    assert df["error"][1].startswith(reason) and df["key"].isna().tolist() == [False, True]
    assert df["root_stress_gear1_MPa"].isna().tolist() == [False, True]
    (refused,) = json.loads((out / "study.json").read_text())["refused"]
    assert refused["swept"] == {"torque": 20.0, "h1": 0.95} and refused["reason"] == \
        df["error"][1]
    assert (out / "results.md").read_text() in std.out


def test_second_run_into_the_same_directory_is_refused(tmp_path):
    import fcntl

    from fegear.study.runner import run_study

    study = _study(tmp_path, "[[sweep]]\nm = [1.5, 2.0]\n")
    out = tmp_path / "out"
    out.mkdir()
    with open(out / ".lock", "w") as held:
        fcntl.flock(held, fcntl.LOCK_EX | fcntl.LOCK_NB)
        held.write("4242")
        held.flush()
        with pytest.raises(StudyError, match=r"another study is running there \(pid 4242\)"):
            run_study(study, out, workers=1, progress=False)
    assert sorted(p.name for p in out.iterdir()) == [".lock"]  # nothing else touched


def test_kept_vtu_files_arrive_beside_the_record(tmp_path):
    import meshio

    from fegear.study.runner import run_study

    text = SMALL.split("[[sweep]]")[0].replace("[study]", "[outputs]\nvtu = true\n[study]")
    study = _study(tmp_path, text + "[[sweep]]\ntorque = 10\n")
    report = run_study(study, tmp_path / "out", workers=1, progress=False)
    assert (report.computed, report.failed) == (1, 0)
    key = study.cases[0].key
    rec = json.loads((tmp_path / "out" / "cases" / f"{key}.json").read_text())
    # both rings and the contact submodels; no picture: png = false
    assert sorted(rec["files"]) == ["gear1.vtu", "gear1_contact.vtu", "gear2.vtu",
                                    "gear2_contact.vtu"]
    mesh = meshio.read(rec["files"]["gear1.vtu"])
    assert mesh.points.shape[0] > 1000 and "von_mises_MPa" in mesh.point_data
    again = run_study(study, tmp_path / "out", workers=1, progress=False)
    assert (again.found, again.computed) == (1, 0)


# --- the results: safety factors from stored stresses, the pandas loader ----------------------

def test_new_allowables_recompute_the_factors_not_the_cases(pool_run, tmp_path):
    """The finished study with other allowables in its base and a sweep over the bending one:
    every case is found in the folder, none is solved again, the stresses stay, the factors follow
    the file."""
    import shutil

    from fegear.study.runner import run_study

    out = tmp_path / "out"
    shutil.copytree(pool_run["out"], out)
    text = SMALL.replace("[base]", "[base]\nallowable-contact = 1000\nallowable-bending = 400")
    text += "[[sweep]]\ntorque = 10\nallowable-bending = [300, 600]\n"
    study = _study(tmp_path, text, "small.toml")
    assert len(study.cases) == N_SMALL + 2 and len({c.key for c in study.cases}) == N_SMALL
    report = run_study(study, out, workers=1, progress=False)
    assert (report.found, report.computed) == (N_SMALL, 0)
    before = {r["case"]: r for r in _table(pool_run["out"])}
    after = _table(out)
    assert len(after) == N_SMALL + 2
    for r in after:
        if r["status"] != "ok":
            assert r["safety_bending_gear1"] == ""
            continue
        old = before[r["case"] if int(r["case"]) < N_SMALL else "1"]   # torque 10: case 1
        for k in ("root_stress_gear1_MPa", "root_stress_gear2_MPa", "contact_pressure_MPa"):
            assert r[k] == old[k]
        bending = float(r["allowable-bending"])
        assert bending == (400.0 if int(r["case"]) < N_SMALL else 300.0 + 300.0 * (
            int(r["case"]) - N_SMALL))
        assert float(r["safety_bending_gear1"]) == pytest.approx(
            bending / float(r["root_stress_gear1_MPa"]), rel=1e-12)
        assert float(r["safety_contact"]) == pytest.approx(
            1000.0 / float(r["contact_pressure_MPa"]), rel=1e-12)
        assert float(old["safety_contact"]) == pytest.approx(
            745.0 / float(old["contact_pressure_MPa"]), rel=1e-12)
        teeth = json.loads(r["teeth"])
        assert all(t["safety_bending_gear1"] == pytest.approx(
            bending / t["root_stress_gear1_MPa"]) for t in teeth if t["load_N"] > 0)
    assert "S_F1" in (out / "results.md").read_text()
    assert not (out / "plots" / "allowable-bending.png").exists()


def test_load_results_is_one_row_per_case_with_inputs_results_and_failures(pool_run):
    import pandas as pd

    from fegear.study import load_results

    df = load_results(pool_run["out"])
    assert isinstance(df, pd.DataFrame) and len(df) == N_SMALL
    assert list(df["case"]) == list(range(N_SMALL))
    for column in ("key", "status", "error", "torque", "tip-clearance", "allowable-bending",
                   "root_stress_gear1_MPa", "contact_pressure_MPa", "safety_bending_gear1",
                   "safety_contact", "transmission_error_urad", "teeth_in_contact"):
        assert column in df.columns, column
    assert list(df["status"]) == ["ok"] * 4 + ["failed"]
    failed = df[df["status"] == "failed"].iloc[0]
    assert failed["error"].startswith("GeometryError") and pd.isna(failed["safety_contact"])
    ok = df[df["status"] == "ok"]
    assert list(ok["torque"]) == [5.0, 10.0, 15.0, 20.0]
    assert (ok["safety_bending_gear1"] * ok["root_stress_gear1_MPa"]).to_numpy() == \
        pytest.approx(558.0)
    assert ok["root_stress_gear1_MPa"].is_monotonic_increasing
    assert ok["safety_contact"].is_monotonic_decreasing
    # the Parquet file itself gives the same frame
    assert load_results(pool_run["out"] / "results.parquet").equals(df)


def test_load_results_of_a_directory_without_results_names_it(tmp_path):
    from fegear.study import load_results

    with pytest.raises(StudyError, match="no study results there"):
        load_results(tmp_path)


def test_a_spectrum_rates_each_case_and_the_table_shows_its_limit(tmp_path):
    # the spectrum beside the study file; the table's life columns are the limiting mode's
    toml = tmp_path / "life.toml"
    (tmp_path / "duty.csv").write_text("torque,cycles\n10,1e8\n20,1e6\n")
    base = SMALL.split("[[sweep]]")[0]
    toml.write_text(base + 'positions = 2\nspectrum = "duty.csv"\nspeed = 1500.0\n'
                    'material = "42CrMo"\n[[sweep]]\nh1 = [0.3, 0.4]\n')
    out = tmp_path / "out"
    assert main(["study", str(toml), "--workers", "1", "--out", str(out), "--no-progress"]) == 0
    text = (out / "results.md").read_text()
    assert "S at life" in text and "Rated for a life" in text
    for r in _table(out):
        assert r["status"] == "ok"
        modes = json.loads((out / "cases" / f"{r['key']}.json").read_text())[
            "summary"]["rating"]["modes"]
        name, worst = min(modes.items(), key=lambda kv: float(kv[1]["safety"]))
        row = next(line for line in text.splitlines() if line.startswith(f"| {r['h1']} |"))
        assert f"| {name} | {float(worst['safety']):.2f} |" in row


def test_a_class_is_an_input_its_samples_a_few_columns(tmp_path, capsys):
    # grade, samples, seed and quantile are study inputs; each case's samples become the
    # jammed share, each headline's quantiles with their errors, the factors at the quantile
    # and the verdict (the per-sample rows stay in the case's record)
    toml = tmp_path / "classes.toml"
    base = SMALL.split("[[sweep]]")[0].replace("shift = 0.016", "shift = 0.03")
    toml.write_text(base + "samples = 3\n[[sweep]]\ngrade = [4, 6]\n")
    out = tmp_path / "out"
    assert main(["study", str(toml), "--workers", "1", "--out", str(out), "--no-progress"]) == 0
    table = _table(out)
    assert [r["grade"] for r in table] == ["4", "6"]
    for r in table:
        assert r["status"] == "ok" and r["samples.n"] == "3"
        assert float(r["samples.jammed_share"]) <= 1.0
        assert "samples.root_stress_gear1_MPa.P95" in r and "samples.verdict" in r
        assert "samples.rows" not in r
        record = json.loads((out / "cases" / f"{r['key']}.json").read_text())
        assert len(record["summary"]["samples"]["rows"]) == 3
    assert "jammed %" in (out / "results.md").read_text()

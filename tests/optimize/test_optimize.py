"""The design search (fegear.optimize): its space checked before anything runs, a design's
record against a cycle solved directly, the sampler's seed, a search resumed after SIGTERM
and after a worker's SIGKILL with no trial lost or solved twice, and the printed ``fegear
solve`` line giving the printed numbers. Tiny budgets at `coarse`, two or three positions."""

import math
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from fegear.cli import main
from fegear.errors import FegearError, ParameterError
from fegear.optimize import (
    Space,
    Variable,
    check_space,
    evaluate,
    load_trials,
    open_study,
    outer_diameter,
    parse_variables,
    run_search,
)

BASE = {"shift": 0.016, "rotation": 0.002, "torque": 200.0}
SPACE = Space((Variable("h1", 0.25, 0.35), Variable("relief", 0.0, 6.0)),
              {**BASE, "tip-clearance": 0.02}, positions=2, quality="coarse")
FEGEAR = [sys.executable, "-m", "fegear"]


# --- the space ------------------------------------------------------------------------------
def test_variables_are_parsed_and_bad_ones_refused_by_name():
    assert parse_variables(["m=1:2.5", "relief=0:10"]) == (Variable("m", 1.0, 2.5),
                                                          Variable("relief", 0.0, 10.0))
    for text, name in (("z2=40:50", "vary"), ("m=2:1", "vary"), ("m=1", "vary"),
                       ("m=nan:2", "vary"), ("m=-1:2", "m"), ("h1=0.2:0.4,f1", "vary")):
        with pytest.raises(ParameterError) as err:
            parse_variables([text])
        assert err.value.name == name, text
    with pytest.raises(ParameterError, match="once"):
        parse_variables(["m=1:2", "m=1.5:2.5"])
    # a space built in Python has its bounds checked too: a bool is no number
    for bounds in ((True, 2.0), (1.0, "2"), (math.nan, 2.0), (2.0, 1.0)):
        with pytest.raises(ParameterError) as err:
            check_space(Space((Variable("m", *bounds),), BASE))
        assert err.value.name == "vary", bounds


def test_a_constraint_no_design_inside_the_bounds_meets_is_refused():
    space = Space((Variable("m", 1.0, 2.5), Variable("h1", 0.2, 0.4)), BASE,
                  constraints={"max_outer_diameter": 50.0})
    with pytest.raises(ParameterError) as err:
        check_space(space)
    # the smallest gear 2 inside the bounds: m 1, h1 0.2, rim 3 m: 2 (22.5 + 0.4 + 3) mm
    assert err.value.name == "max-outer-diameter" and "51.8" in str(err.value)
    with pytest.raises(ParameterError, match="min-backlash"):
        check_space(Space(SPACE.variables, BASE,
                          constraints={"min_backlash": 30.0, "max_backlash": 20.0}))
    with pytest.raises(FegearError, match="given and also varied"):
        check_space(Space(SPACE.variables, {**BASE, "h1": 0.3}))


def test_bad_bounds_an_unknown_variable_and_an_infeasible_constraint_write_nothing(tmp_path,
                                                                                  capsys):
    out = tmp_path / "search"
    for argv in (["--vary", "m=2.5:1"], ["--vary", "teeth=40:50"],
                 ["--max-outer-diameter", "40"]):
        assert main(["optimize", *argv, "--out", str(out)]) == 2
        lines = capsys.readouterr().err.strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith("fegear: error:"), lines
        assert not out.exists()


# --- a design -------------------------------------------------------------------------------
def test_a_designs_record_is_its_cycle_read_as_a_designer_would():
    """The worst of each stress over the cycle and the factors from them, against the same
    cycle solved directly; the objective is the smallest of S_F1, S_F2, S_H flank."""
    from fegear.toothpair.job import prepare_job
    from fegear.toothpair.pair import solve_positions

    values = {**BASE, "quality": "coarse", "relief": 3.0, "tip-clearance": 0.02}
    rec = evaluate(values, 3, {"max_outer_diameter": 100.0})
    job = prepare_job({**values, "positions": 3, "no-estimate": True})
    sols = solve_positions(job.case, job.betas, submodels="none")
    root1 = max(s.root_stress[0] for s in sols)
    flank = max(s.flank_contact_pressure for s in sols)
    assert rec["status"] == "ok" and rec["root_stress_gear1_MPa"] == root1
    assert rec["S_F1"] == pytest.approx(558.0 / root1)
    assert rec["S_H_flank"] == pytest.approx(745.0 / flank)
    assert rec["objective_safety"] == min(rec["S_F1"], rec["S_F2"], rec["S_H_flank"])
    assert rec["violation_edge_load"] == 0.0 and rec["violation_buildable"] == 0.0
    # m 2, z2 45, h1 0.3, rim 6 mm: 2 (45 + 1.2 + 6) = 104.4 mm, 4.4 mm too large for 100
    assert rec["outer_diameter_mm"] == pytest.approx(104.4)
    assert rec["violation_outer_diameter"] == pytest.approx(4.4)
    assert outer_diameter({"m": 1.0, "h1": 0.2, "rim2": 2.0}) == pytest.approx(2 * 24.9)


def test_a_class_s_design_is_measured_at_the_quantile_of_its_pairs():
    """With a class, the objective is the smallest factor the quantile of the class's pairs
    meets (those of the samples' own solve), the tip rounds' constraint the pairs' share."""
    from fegear.toothpair import prepare_job, solve_job

    values = {**BASE, "quality": "coarse", "shift": 0.03, "relief": 3.0, "tip-clearance": 0.04,
              "grade": 4, "samples": 4, "quantile": 0.5}
    rec = evaluate(values, 2, {})
    s = solve_job(prepare_job({**values, "positions": 2, "no-estimate": True})).summary
    at = {k: v["at_quantile"] for k, v in s["samples"]["safety"].items()}
    assert rec["S_F1_P50"] == pytest.approx(at["safety_bending_gear1"], rel=1e-6)
    assert rec["S_H_flank_P50"] == pytest.approx(at["safety_contact_flank"], rel=1e-6)
    assert rec["objective_safety"] == min(rec["S_F1_P50"], rec["S_F2_P50"],
                                          rec["S_H_flank_P50"])
    assert rec["jammed_share"] == s["samples"]["jammed_share"]
    assert rec["violation_jam"] == pytest.approx(rec["jammed_share"] - 0.5)
    assert (rec["violation_edge_load"] > 0) == (rec["edge_share"] > 0.5)


def test_a_class_s_design_whose_pairs_jam_beyond_the_quantile_breaks_the_jam_constraint():
    """The baseline's backlash at class 6 leaves most pairs jammed: more than the quantile
    leaves (one of four at the 95th percentile) is a design that cannot be built to turn at
    that class, infeasible by how far beyond (not a feasible design of objective 0, which a
    sampler would seek out), and none of its pairs is solved."""
    values = {**BASE, "quality": "coarse", "relief": 3.0, "tip-clearance": 0.04, "grade": 6,
              "samples": 4, "quantile": 0.95}
    rec = evaluate(values, 2, {})
    assert rec["status"] == "ok" and rec["jammed_share"] >= 0.25
    assert rec["violation_jam"] == pytest.approx(rec["jammed_share"] - 0.05)
    assert f"{round(4 * rec['jammed_share'])} of its 4 pairs jam" in rec["reason"]
    assert rec["objective_safety"] == 0.0 and rec["S_F1_P95"] is None
    # none solved: no pair's rounds were read
    assert rec["edge_share"] == 0.0 and rec["violation_edge_load"] == 0.0


def test_a_class_s_design_whose_pairs_load_their_rounds_is_solved_no_further():
    """Without a relief every pair loads a tip round: once more than the quantile leaves
    have (one of four at the 95th percentile), the design breaks the rounds' constraint
    whatever the rest give, and its pairs are solved no further: its factors at the quantile
    unknown (blank), its objective 0, the share and load those it saw."""
    values = {**BASE, "quality": "coarse", "shift": 0.03, "grade": 4, "samples": 4,
              "quantile": 0.95}
    rec = evaluate(values, 2, {})
    assert rec["status"] == "ok" and "solved no further" in rec["reason"]
    assert rec["objective_safety"] == 0.0 and rec["S_F1_P95"] is None
    assert rec["violation_edge_load"] > 0 and 0.05 < rec["edge_share"] <= 1.0


def test_a_design_the_solve_refuses_comes_back_as_a_violation_not_an_error():
    rec = evaluate({**BASE, "quality": "coarse", "tip-clearance": 5.0}, 2, {})
    assert rec["status"] == "refused" and "tip-clearance" in rec["reason"]
    assert rec["violation_buildable"] == 1.0


def test_the_sampler_ranks_violations_as_shares_of_what_each_is_measured_against():
    """A sampler ranks infeasible designs by the sum of their violations: a load on the rounds
    in N beside a jammed share would outweigh it a thousand times. Each reaches it as a share:
    the load of the force on gear 1's pitch circle, a size of its bound; the record keeps the
    units."""
    from fegear.optimize.search import sampler_violation

    rec = evaluate({**BASE, "quality": "coarse"}, 2, {"max_outer_diameter": 100.0})
    force = rec["pitch_force_N"]
    assert force == pytest.approx(1000.0 * 200.0 / 44.0)   # 200 N·m at r1 = m z1 / 2 = 44 mm
    assert rec["violation_edge_load"] > 100.0       # no relief: the rounds carry load (N)
    cons = {"max_outer_diameter": 100.0}
    assert sampler_violation(rec, "edge_load", cons) == rec["violation_edge_load"] / force
    assert sampler_violation(rec, "outer_diameter", cons) == pytest.approx(4.4 / 100.0)
    assert sampler_violation(rec, "buildable", cons) == 0.0
    assert sampler_violation({"violation_jam": 0.15}, "jam", cons) == 0.15
    low = {"backlash_um": 8.0, "violation_backlash": 2.0}
    high = {"backlash_um": 14.0, "violation_backlash": 2.0}
    both = {"min_backlash": 10.0, "max_backlash": 12.0}
    assert sampler_violation(low, "backlash", both) == 0.2
    assert sampler_violation(high, "backlash", both) == pytest.approx(2.0 / 12.0)


# --- the search ----------------------------------------------------------------------------
def _params(out: Path, state: str = "COMPLETE") -> list[tuple]:
    table = load_trials(out)
    done = table[table["state"] == state]
    return [tuple(round(v, 12) for v in row) for row in done[["h1", "relief"]].values]


# slow (11 s: three searches); the default run resumes a search in the stopped and killed
# one's test below
@pytest.mark.slow
def test_a_seeded_search_repeats_and_a_resumed_one_solves_only_what_is_missing(tmp_path):
    a, b = tmp_path / "a", tmp_path / "b"
    for out in (a, b):
        out.mkdir()
        run_search(SPACE, out, trials=2, workers=1, seed=7)
    assert _params(a) == _params(b) and len(_params(a)) == 2
    report = run_search(SPACE, a, trials=3, workers=1, seed=7)
    assert (report.found, report.solved) == (2, 1)
    done = _params(a)
    assert len(done) == 3 and len(set(done)) == 3 and done[:2] == _params(b)
    with pytest.raises(FegearError, match="other settings"):
        run_search(SPACE, a, trials=3, workers=1, seed=8)


def test_a_trial_killed_while_its_design_was_drawn_is_drawn_whole_and_solved_again(tmp_path):
    # a kill between a trial's draws of its variables leaves it running with part of a
    # design: the next start draws the rest, marks it cut and solves that whole design
    study = open_study(SPACE, tmp_path)
    study.ask().suggest_float("h1", 0.25, 0.35)          # killed before relief was drawn
    run_search(SPACE, tmp_path, trials=1, workers=1)
    cut = _params(tmp_path, "FAIL")
    assert len(cut) == 1 and all(math.isfinite(v) for v in cut[0])
    assert _params(tmp_path) == cut


def _complete(out: Path) -> int:
    """How many trials the search in ``out`` has finished, as its journal says (its table is
    written only at its end or a stop)."""
    from optuna.trial import TrialState

    if not (out / "search.journal").exists():
        return 0
    study = open_study(SPACE_CLI, out)
    return sum(t.state == TrialState.COMPLETE for t in study.get_trials())


def _wait_for(out: Path, complete: int, proc, timeout: float = 120.0) -> None:
    """Until the search in ``out`` has ``complete`` finished trials."""
    t0 = time.time()
    while time.time() - t0 < timeout:
        assert proc.poll() is None, proc.communicate()
        if _complete(out) >= complete:
            return
        time.sleep(0.3)
    raise AssertionError("the search did not get going")


SPACE_CLI = Space((Variable("h1", 0.25, 0.35), Variable("relief", 0.0, 6.0)),
                  {**BASE, "tip-clearance": 0.02}, positions=2, quality="coarse")
ARGV = ["optimize", "--vary", "h1=0.25:0.35", "--vary", "relief=0:6", "--shift", "0.016",
        "--rotation", "0.002", "--tip-clearance", "0.02", "--positions", "2", "--best", "0",
        "--no-baselines", "--trials", "6", "--workers", "2"]


def _check_resumed(out: Path, trials: int = 6) -> None:
    """``trials`` finished trials, each design once; every trial a stop or a kill cut short
    was queued again and finished with the same design."""
    done = _params(out)
    assert len(done) == trials and len(set(done)) == trials
    cut = _params(out, "FAIL")
    assert cut and set(cut) <= set(done)


def _cut(out: Path, *whys: str) -> None:
    """Every trial cut short says one of ``whys`` (each of them said by one at least) and
    which trial redoes its design; that one says which it redoes, or is cut short itself."""
    table = load_trials(out).set_index("trial")
    cut = table[table["state"] == "FAIL"]
    assert len(cut) and set(cut["status"]) == {"cut"}
    said = set()
    for number, row in cut.iterrows():
        head, copy = row["reason"].split("; its design queued again as trial ")
        assert head in whys, row["reason"]
        said.add(head)
        redo = table.loc[int(copy)]
        if redo["status"] == "cut":     # cut short in its turn: it says so, checked in its turn
            continue
        assert redo["state"] == "COMPLETE" or redo["reason"].startswith(
            f"the design of trial {number} ({head})")
    assert said == set(whys), said


def _clean_exit(err: str) -> None:
    """Nothing on stderr but fegear's own lines: no traceback, and no resource tracker
    warning of semaphores the search's pool left behind."""
    assert "Traceback" not in err and "leaked" not in err and "Warning" not in err, err


# The four tests below start the search seven times in all (a start takes 3-5 s before its
# first trial: the imports, the pool's processes; the four 45-60 s): the default run has them
# in one search of three starts, the test after them (17-21 s).
@pytest.mark.slow
@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGINT])
def test_a_search_stopped_by_a_signal_resumes_with_no_trial_lost_or_repeated(tmp_path, sig):
    out = tmp_path / "search"
    proc = subprocess.Popen([*FEGEAR, *ARGV, "--out", str(out)], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    _wait_for(out, 2, proc)
    proc.send_signal(sig)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == 128 + sig, err
    assert "queued again" in err
    _clean_exit(err)
    name = signal.Signals(sig).name
    _cut(out, f"stopped by {name}")
    queued = load_trials(out).query("state == 'WAITING'")
    assert len(queued) and set(queued["status"]) == {"queued"}
    assert all(f"(stopped by {name}), solved first" in r for r in queued["reason"])
    again = subprocess.run([*FEGEAR, *ARGV, "--out", str(out)], capture_output=True, text=True,
                           timeout=300)
    assert again.returncode == 0, again.stderr
    _clean_exit(again.stderr)
    _check_resumed(out)
    _cut(out, f"stopped by {name}")


@pytest.mark.slow
def test_a_search_killed_outright_leaves_no_semaphore_and_says_what_it_cut(tmp_path):
    """SIGKILL leaves no time to clean up: the pool's workers remove its queues' semaphores
    (else multiprocessing's resource tracker does, with a warning on the terminal), and the
    next start marks the trials it finds running as cut by the kill."""
    out = tmp_path / "search"
    proc = subprocess.Popen([*FEGEAR, *ARGV, "--out", str(out)], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    _wait_for(out, 1, proc)
    proc.kill()
    _, err = proc.communicate(timeout=60)   # until the workers and the tracker have ended
    assert proc.returncode == -signal.SIGKILL
    _clean_exit(err)
    again = subprocess.run([*FEGEAR, *ARGV, "--out", str(out)], capture_output=True, text=True,
                           timeout=300)
    assert again.returncode == 0, again.stderr
    _clean_exit(again.stderr)
    _check_resumed(out)
    _cut(out, "the search ended while it ran (killed outright)")


@pytest.mark.slow
def test_a_killed_worker_costs_its_trial_a_second_start_and_nothing_else(tmp_path):
    out = tmp_path / "search"
    proc = subprocess.Popen([*FEGEAR, *ARGV, "--out", str(out)], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    _wait_for(out, 1, proc)
    _kill_a_worker(proc)
    _, err = proc.communicate(timeout=300)
    assert proc.returncode == 0, err
    _check_resumed(out)


def _kill_a_worker(proc) -> None:
    """SIGKILL one of the worker processes of the search ``proc``."""
    psutil = pytest.importorskip("psutil")
    workers = [p for p in psutil.Process(proc.pid).children()
               if any("spawn_main" in part for part in p.cmdline())]
    assert workers
    os.kill(workers[0].pid, signal.SIGKILL)


def test_a_search_stopped_killed_and_short_of_a_worker_loses_no_trial_and_solves_none_twice(
        tmp_path):
    """The four tests above in one search of eight trials and three starts: stopped by SIGTERM
    (its trials under way queued again, solved first by the next start), killed outright (the
    next start finds its trials running and queues them again), a worker killed (the pool
    started anew, its trials under way queued again); it ends with eight designs, each once,
    and every trial cut short saying why."""
    out = tmp_path / "search"
    argv = [*FEGEAR, *ARGV[:ARGV.index("--trials")], "--trials", "8", "--workers", "2",
            "--out", str(out)]

    def start():
        return subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                text=True)

    proc = start()
    _wait_for(out, 1, proc)
    proc.send_signal(signal.SIGTERM)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == 128 + signal.SIGTERM, err
    assert "queued again" in err
    _clean_exit(err)
    queued = load_trials(out).query("state == 'WAITING'")
    assert len(queued) and set(queued["status"]) == {"queued"}
    assert all("(stopped by SIGTERM), solved first" in r for r in queued["reason"])

    done, proc = _complete(out), start()
    _wait_for(out, done + 1, proc)
    proc.kill()
    _, err = proc.communicate(timeout=60)   # until the workers and the tracker have ended
    assert proc.returncode == -signal.SIGKILL
    _clean_exit(err)

    done, proc = _complete(out), start()
    _wait_for(out, done + 1, proc)
    _kill_a_worker(proc)
    _, err = proc.communicate(timeout=300)
    assert proc.returncode == 0, err
    _clean_exit(err)
    _check_resumed(out, trials=8)
    _cut(out, "stopped by SIGTERM", "the search ended while it ran (killed outright)",
         "a worker process of the pool died")


def test_the_printed_solve_line_gives_the_printed_numbers(tmp_path, capsys):
    """The final table's design, solved again by the ``fegear solve`` line printed for it (and
    in its one-page report), gives its safety factors to the last digit printed (the same
    solve), well inside its error estimate."""
    import json
    import shlex

    from fegear.optimize import resolve

    row = resolve({**BASE, "relief": 3.0, "tip-clearance": 0.02, "h1": 0.3}, 2,
                  tmp_path / "best")
    page = (tmp_path / "best" / "report.html").read_text(encoding="utf-8")
    assert row["command"].replace("'", "&#x27;") in page   # its page, with the same line
    argv = shlex.split(row["command"])[1:]
    assert main([*argv, "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    cycle = summary["cycle"]
    assert cycle["safety_bending_gear1"]["min"] == pytest.approx(row["S_F1"], rel=1e-9)
    assert cycle["safety_contact_flank"]["min"] == pytest.approx(row["S_H_flank"], rel=1e-9)
    assert row["safety"] == min(row["S_F1"], row["S_F2"], row["S_H_flank"], row["S_H"])
    assert all(math.isfinite(v) for v in row["estimate_pct"].values())


def test_a_search_with_no_feasible_design_says_which_constraint_binds(tmp_path, capsys):
    """Without relief every design of these bounds loads its tip rounds at 200 N·m."""
    out = tmp_path / "search"
    assert main(["optimize", "--vary", "h1=0.28:0.32", "--shift", "0.016", "--rotation",
                 "0.002", "--positions", "2", "--trials", "2", "--workers", "1",
                 "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert "no feasible design: the constraint that binds is edge_load (violated by 2 of 2" \
        in text
    assert len(load_trials(out)) == 2


@pytest.mark.slow  # 15-25 s: a local Dask cluster's start and three trials
def test_a_search_runs_on_a_dask_cluster_as_on_the_local_pool(tmp_path):
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster:
        report = run_search(SPACE, tmp_path, trials=3, seed=7,
                            scheduler=cluster.scheduler_address)
    assert report.solved == 3 and len(_params(tmp_path)) == 3


# --- the pictures ---------------------------------------------------------------------------
def test_the_legends_of_the_search_pictures_lie_outside_the_points(tmp_path, monkeypatch):
    """variables.png: one legend under every panel (inside one it covered that panel's
    points); history.png: beside the trials."""
    import pandas as pd

    import fegear.optimize.plot as plot

    boxes = {}

    def measure(fig, path, dpi):      # the boxes as drawn, in place of the file
        fig.canvas.draw()
        r = fig.canvas.get_renderer()
        boxes[path.name] = ([ax.get_window_extent(r) for ax in fig.axes],
                            [ax.get_legend().get_window_extent(r) for ax in fig.axes
                             if ax.get_legend()],
                            [leg.get_window_extent(r) for leg in fig.legends])
        return path

    monkeypatch.setattr(plot, "save_png", measure)
    rows = [{"trial": k, "state": "COMPLETE", "feasible": str(k % 3 != 0), "h1": 0.25 + k / 200,
             "relief": k / 3, "objective_safety": 0.5 + (k % 7) / 10} for k in range(20)]
    plot.search_pngs(pd.DataFrame(rows), ["h1", "relief"], ["safety"], tmp_path, "search",
                     0.39, 0.97)
    panels, inside, (below,) = boxes["variables.png"]
    assert inside == [] and below.y1 < min(b.y0 for b in panels)
    (panel,), (beside,), _ = boxes["history.png"]
    assert beside.x0 > panel.x1

"""A design search's design on a class's pairs ends once its pairs bound its objective below
the bar (fegear.optimize.bar): the bound of every pair read is the objective itself, of some
read it is never below it, and a design pruned by it would have scored below the bar."""

import numpy as np
import pytest

from fegear.optimize import evaluate
from fegear.optimize.bar import Beaten, bound_of, objective_bound
from fegear.optimize.design import LIMITS
from fegear.toothpair import allowables_of, class_samples, prepare_job

VALUES = {"shift": 0.03, "rotation": 0.002, "torque": 200.0, "quality": "coarse",
          "relief": 3.0, "tip-clearance": 0.04, "grade": 4, "samples": 4, "quantile": 0.5}


def reading(sol):
    """A search's reading of a position: the load on the rounds and the limiting stresses."""
    head = sol.headline()
    return (sum(t.edge_load_N for t in sol.teeth),
            np.array([head[f.stress.key] for f in LIMITS.values()]))


@pytest.fixture(scope="module")
def whole():
    return evaluate(VALUES, 2, {})


def test_the_bound_of_every_pair_read_is_the_objective_and_of_fewer_above_it(whole):
    job = prepare_job({**VALUES, "positions": 2, "no-estimate": True})
    allow = allowables_of(VALUES)
    allowable = np.array([getattr(allow, f.stress.allowable) for f in LIMITS.values()])
    sampled = class_samples(job, allow, read=reading, enough=Beaten(0.5, allowable, None))
    assert not sampled.stopped and whole["status"] == "ok" and whole["objective_safety"] > 0
    jammed = round(sampled.jammed_share * 4)
    turning = sampled.turning
    assert bound_of(sampled.readings, turning, jammed, 0.5, allowable) == pytest.approx(
        whole["objective_safety"], rel=1e-12)
    # the first position alone, or a pair not read at all: never below the objective
    first = {k: v[:1] for k, v in sampled.readings.items()}
    assert bound_of(first, turning, jammed, 0.5, allowable) >= whole["objective_safety"]
    fewer = {k: v for k, v in sampled.readings.items() if k != turning[0]}
    assert bound_of(fewer, turning, jammed, 0.5, allowable) >= whole["objective_safety"]


def test_a_jammed_pair_is_beyond_every_other_and_a_stress_of_none_bounds_nothing():
    allow = np.array([500.0, 500.0, 1000.0])   # S_F1, S_F2, S_H flank's allowables
    top = np.array([250.0, 100.0, 500.0])      # S_F1 2, S_F2 5, S_H flank 2
    assert objective_bound([top], 0, 0, 0.5, allow) == 2.0
    # half the pairs unread (at zero): the median between them, the bound twice as high
    assert objective_bound([top], 1, 0, 0.5, allow) == pytest.approx(4.0)
    # a pair that jams: beyond every other, the upper quantile's factor about 0
    assert objective_bound([top], 0, 1, 0.95, allow) < 1e-20
    assert objective_bound([], 3, 0, 0.5, allow) == np.inf


def test_a_design_below_the_bar_is_pruned_and_one_above_it_scored_as_without(whole):
    score = whole["objective_safety"]
    pruned = evaluate(VALUES, 2, {}, bar=1.2 * score)
    assert pruned["status"] == "pruned" and "below" in pruned["reason"]
    assert score <= pruned["objective_bound"] < 1.2 * score
    assert pruned["S_F1_P50"] is None and pruned["objective_safety"] is None
    assert pruned["violation_jam"] <= 0
    kept = evaluate(VALUES, 2, {}, bar=0.9 * score)
    assert kept["status"] == "ok" and kept["objective_safety"] == score


def test_a_search_prunes_what_cannot_join_its_best_and_counts_it_finished(tmp_path):
    from fegear.optimize import Space, Variable, load_trials, run_search

    fixed = {k: v for k, v in VALUES.items() if k not in ("quality", "relief")}
    space = Space((Variable("relief", 2.0, 6.0),), fixed, positions=2, quality="coarse")
    report = run_search(space, tmp_path, trials=5, workers=1, seed=3, keep=1)
    table = load_trials(tmp_path)
    pruned = table[table["state"] == "PRUNED"]
    done = table[table["state"] == "COMPLETE"]
    assert len(pruned) and (pruned["status"] == "pruned").all()
    assert report.solved == 5 and len(pruned) + len(done) == 5
    best = report.study.best_value
    for t in report.study.get_trials(deepcopy=False):
        if t.state.name == "PRUNED":   # its bound, below the best when it was asked
            assert t.value == t.user_attrs["objective_bound"] < best
    again = run_search(space, tmp_path, trials=5, workers=1, seed=3, keep=1)
    assert (again.found, again.solved) == (5, 0)


def test_a_pair_that_fails_is_left_out_of_the_bound_as_the_quantiles_leave_it_out():
    allow = np.array([500.0, 500.0, 1000.0])
    top = np.array([250.0, 100.0, 500.0])      # alone: S 2
    run = Beaten(0.5, allow, bar=3.0)
    run.among(2, 2)
    run.saw(0, (0.0, top))                     # the other pair unread, at zero: S 4 at most
    assert not run.reached
    run.failed(1)                              # left out: this pair alone, S 2 at most
    run.saw(0, (0.0, top))
    assert run.reached
    # a round loaded by one pair of two, more than the median's half leaves: reached too
    edge = Beaten(0.5, allow, bar=None)
    edge.among(2, 2)
    edge.saw(0, (10.0, top))
    assert not edge.reached
    edge.saw(1, (5.0, top))
    assert edge.reached

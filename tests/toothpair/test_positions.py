"""The one driver over positions (fegear/toothpair/positions.py), with a stand-in model: the
first guess, the attempts, the timings, the error when a position does not settle and a long
cycle's two chains, on an executor that solves the second here or in a forked copy."""

import math
import os

import pytest

from fegear.errors import FegearError
from fegear.geometry import PairParameters, gear1_profile
from fegear.running import SERIAL, Forks, WorkerFailed
from fegear.timing import timed
from fegear.toothpair import (
    ATTEMPTS,
    CHAINED,
    SHARE_GUESS,
    TOOTH_STIFFNESS,
    Attempt,
    ContactChecks,
    PairSolution,
    SolveCase,
    Trial,
    drive,
)

CASE = SolveCase(PairParameters(shift=0.016, rotation=0.002), torque=200.0)


@pytest.fixture(scope="module")
def profile():
    return gear1_profile(CASE.params)


class StandIn:
    """Settles a position after ``again`` attempts; its rotation puts the elastic part at
    ``elastic_um`` past the first touch. Its stages take no time but are counted."""

    def __init__(self, again: int, elastic_um: float = 5.0):
        self.again, self.elastic_um = again, elastic_um
        self.trials: list[tuple[float, Trial]] = []

    def build(self, case, profile, states):
        self.built_with = states()
        with timed("model"):
            pass

    def attempt(self, case, state, trial, near):
        self.trials.append((case.beta, trial))
        settled = sum(1 for b, _ in self.trials if b == case.beta) > self.again
        again = None if settled else Trial(trial.teeth, trial.elastic_um * 2)
        with timed("contact"):
            pass
        return Attempt(state, again, "stand-in")

    def finish(self, case, state, attempt):
        p = case.params
        first = p.turn_of(state.closest(+1).plus_um)
        with timed("stresses"):
            pass
        # the process that solved it (dofs) and the trial it started from (detail)
        return PairSolution(case, (), (0.0, 0.0), 0.0, first + p.turn_of(self.elastic_um),
                            first, os.getpid(), ContactChecks(0.0, 0.0, 0, (), 0), {},
                            self.trials[-1][1])


def test_the_first_guess_shares_the_torque_and_later_positions_start_from_the_last(profile):
    model = StandIn(again=0)
    betas = (0.0, 2 * math.pi / 45 / 4)
    sols = drive(CASE, betas, model, profile)
    (b0, first), (b1, second) = model.trials
    p = CASE.params
    assert first.elastic_um == pytest.approx(
        CASE.torque * 1e3 / p.r0 / (CASE.thickness * TOOTH_STIFFNESS) / SHARE_GUESS)
    assert second.elastic_um == pytest.approx(5.0)          # the first position's, solved
    assert first.teeth                                       # chosen from the clearance state
    assert [s.case.beta for s in sols] == list(betas)
    assert [b for b, _ in model.built_with] == list(betas)  # its build saw every state
    # the one-off stages are the first position's; every position has its own
    assert {"model", "clearance", "contact", "stresses"} <= set(sols[0].timings_s)
    assert set(sols[1].timings_s) == {"contact", "stresses"}


def test_a_position_after_one_without_its_first_touch_starts_from_the_first_guess(profile):
    # a solution read in brief (a sample's, a spectrum level's) has no first touch (NaN): the
    # next position's rotation is guessed afresh, not a NaN that no attempt settles on
    from dataclasses import replace

    from fegear.toothpair import expected_elastic_um

    model = StandIn(again=0)
    sol = drive(CASE, (0.0,), model, profile)[0]
    brief = replace(sol, first_touch=math.nan)
    p = CASE.params
    guess = CASE.torque * 1e3 / p.r0 / (CASE.thickness * TOOTH_STIFFNESS) / SHARE_GUESS
    assert expected_elastic_um(CASE, brief) == pytest.approx(guess)
    assert expected_elastic_um(CASE, sol) == pytest.approx(5.0)


def test_attempts_are_summed_and_bounded(profile):
    model = StandIn(again=2)
    sol = drive(CASE, (0.0,), model, profile)[0]
    assert len(model.trials) == 3
    assert set(sol.timings_s) >= {"contact", "stresses"}     # three attempts' contact stages
    assert model.trials[2][1].elastic_um == pytest.approx(4 * model.trials[0][1].elastic_um)
    with pytest.raises(FegearError, match=f"did not settle in {ATTEMPTS} attempts"):
        drive(CASE, (0.0,), StandIn(again=ATTEMPTS), profile)


def test_blas_runs_on_one_thread_during_a_solve_and_as_before_after(profile):
    # OpenBLAS's threads slowed every solve on two cores (docs/benchmark.md, "BLAS threads")
    import numpy as np  # noqa: F401  (its BLAS loaded, so that there is a pool to limit)
    from threadpoolctl import threadpool_info, threadpool_limits

    def blas():
        return {i["filepath"]: i["num_threads"] for i in threadpool_info()
                if i["user_api"] == "blas"}

    seen = []

    class Recording(StandIn):
        def attempt(self, case, state, trial, near):
            seen.append(blas())
            return super().attempt(case, state, trial, near)

    # two threads before, whatever the environment gave (the tests' is one: conftest.py)
    with threadpool_limits(limits=2, user_api="blas"):
        before = blas()
        assert set(before.values()) == {2}
        drive(CASE, (0.0,), Recording(again=0), profile)
        assert seen and all(n == 1 for n in seen[0].values())
        assert blas() == before


class FailingBeside(StandIn):
    """Fails wherever it runs outside the process that made it."""

    def __init__(self, *args):
        super().__init__(*args)
        self.home = os.getpid()

    def attempt(self, case, state, trial, near):
        if os.getpid() != self.home:
            raise RuntimeError("a worker's failure")
        return super().attempt(case, state, trial, near)


BETAS = tuple(2 * math.pi / 45 * k / CHAINED for k in range(CHAINED))


@pytest.mark.parametrize("forked", [False, True])
def test_a_long_cycle_is_two_chains_each_from_the_first_guess(profile, forked):
    with Forks(2) if forked else SERIAL as executor:
        sols = drive(CASE, BETAS, StandIn(again=0), profile, executor)
    assert [s.case.beta for s in sols] == list(BETAS)
    guess = sols[0].detail.elastic_um
    cut = CHAINED // 2
    starts = [k for k, s in enumerate(sols) if s.detail.elastic_um == pytest.approx(guess)]
    assert starts == [0, cut]                     # the others start from the one before
    assert all(s.detail.elastic_um == pytest.approx(5.0) for k, s in enumerate(sols)
               if k not in (0, cut))
    solvers = [s.dofs for s in sols]
    assert set(solvers[:cut]) == {os.getpid()}
    # forked, the second chain in one other process, which has ended
    assert set(solvers[cut:]) == ({os.getpid()} if not forked else {solvers[cut]})
    if forked:
        assert solvers[cut] != os.getpid()
        with pytest.raises(ChildProcessError):
            os.waitpid(solvers[cut], os.WNOHANG)
    assert "model" in sols[0].timings_s and "model" not in sols[cut].timings_s


def test_a_chain_that_fails_in_a_worker_raises_where_workers_are_strict(profile):
    with Forks(2) as executor, pytest.raises(WorkerFailed, match="a worker's failure"):
        drive(CASE, BETAS, FailingBeside(0), profile, executor)


def test_a_chain_that_fails_in_a_worker_is_solved_here_with_a_warning(profile, monkeypatch,
                                                                     caplog):
    monkeypatch.delenv("FEGEAR_STRICT_WORKERS", raising=False)
    with Forks(2) as executor:
        sols = drive(CASE, BETAS, FailingBeside(0), profile, executor)
    assert {s.dofs for s in sols} == {os.getpid()}
    assert len(sols) == CHAINED
    assert "a task failed in a worker process (RuntimeError: a worker's failure)" in caplog.text


def test_a_short_cycle_is_one_chain(profile):
    with Forks(2) as executor:
        sols = drive(CASE, BETAS[:-1], StandIn(again=0), profile, executor)
    assert {s.dofs for s in sols} == {os.getpid()}
    assert sum(s.detail.elastic_um != pytest.approx(5.0) for s in sols) == 1


def test_an_interference_is_refused_before_the_model_is_built():
    from fegear.errors import GeometryError

    case = SolveCase(PairParameters(shift=0.016, rotation=0.002, tip_clearance=-1e-5),
                     torque=200.0)
    model = StandIn(again=0)
    with pytest.raises(GeometryError, match="interferes"):
        drive(case, BETAS, model, gear1_profile(case.params))
    assert not hasattr(model, "built_with")

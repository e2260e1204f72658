"""The one driver over positions (fegear/toothpair/positions.py), with a stand-in model: the
first guess, the attempts, the timings, the error when a position does not settle and a long
cycle's two chains, the second solved beside or not."""

import math
import os

import pytest

from fegear.errors import FegearError
from fegear.geometry import PairParameters, gear1_profile
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
    ``elastic_um`` past the first touch."""

    reads_states = True

    def __init__(self, again: int, elastic_um: float = 5.0):
        self.again, self.elastic_um = again, elastic_um
        self.trials: list[tuple[float, Trial]] = []
        self.timings_s = {}

    def build(self, case, profile, states, beside=False):
        self.timings_s = {"model": 1.0}

    def settle(self):
        return {}

    def attempt(self, case, state, trial, near):
        self.trials.append((case.beta, trial))
        settled = sum(1 for b, _ in self.trials if b == case.beta) > self.again
        again = None if settled else Trial(trial.teeth, trial.elastic_um * 2)
        return Attempt(state, again, "stand-in", {"contact": 0.5})

    def complete(self, sols, beside=False):
        self.completed, self.completed_beside = sols, beside
        return sols

    def prepare(self, sols, busy):
        self.prepared = (len(sols), busy)

    def finish(self, case, state, attempt):
        p = case.params
        first = p.turn_of(state.closest(+1).plus_um)
        # the process that solved it (dofs) and the trial it started from (detail)
        return PairSolution(case, (), (0.0, 0.0), 0.0, first + p.turn_of(self.elastic_um),
                            first, os.getpid(), ContactChecks(0.0, 0.0, 0, (), 0),
                            {"stresses": 0.25}, self.trials[-1][1])

    def detach(self, sol):
        return sol

    def attach(self, sol):
        return sol


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
    assert model.completed == sols                           # the model saw the whole cycle
    # the one-off stages are the first position's; every position has its own
    assert {"model", "clearance", "contact", "stresses"} <= set(sols[0].timings_s)
    assert set(sols[1].timings_s) == {"contact", "stresses"}


def test_attempts_are_summed_and_bounded(profile):
    model = StandIn(again=2)
    sol = drive(CASE, (0.0,), model, profile)[0]
    assert len(model.trials) == 3
    assert sol.timings_s["contact"] == pytest.approx(1.5)    # three attempts' contact stages
    assert model.trials[2][1].elastic_um == pytest.approx(4 * model.trials[0][1].elastic_um)
    with pytest.raises(FegearError, match=f"did not settle in {ATTEMPTS} attempts"):
        drive(CASE, (0.0,), StandIn(again=ATTEMPTS), profile)


def test_blas_runs_on_one_thread_during_a_solve_and_as_before_after(profile):
    # OpenBLAS's threads slowed every solve on two cores (docs/benchmark.md, "BLAS threads")
    import numpy as np  # noqa: F401  (its BLAS loaded, so that there is a pool to limit)
    from threadpoolctl import threadpool_info

    def blas():
        return {i["filepath"]: i["num_threads"] for i in threadpool_info()
                if i["user_api"] == "blas"}

    seen = []

    class Recording(StandIn):
        def attempt(self, case, state, trial, near):
            seen.append(blas())
            return super().attempt(case, state, trial, near)

    before = blas()
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


@pytest.mark.parametrize("beside", [False, True])
def test_a_long_cycle_is_two_chains_each_from_the_first_guess(profile, beside):
    betas = tuple(2 * math.pi / 45 * k / CHAINED for k in range(CHAINED))
    sols = drive(CASE, betas, StandIn(again=0), profile, beside=beside)
    assert [s.case.beta for s in sols] == list(betas)
    guess = sols[0].detail.elastic_um
    cut = CHAINED // 2
    starts = [k for k, s in enumerate(sols) if s.detail.elastic_um == pytest.approx(guess)]
    assert starts == [0, cut]                     # the others start from the one before
    assert all(s.detail.elastic_um == pytest.approx(5.0) for k, s in enumerate(sols)
               if k not in (0, cut))
    solvers = [s.dofs for s in sols]
    assert set(solvers[:cut]) == {os.getpid()}
    # beside, the second chain in one other process (a fork), which has ended
    assert set(solvers[cut:]) == ({os.getpid()} if not beside else {solvers[cut]})
    if beside:
        assert solvers[cut] != os.getpid()
        with pytest.raises(ChildProcessError):
            os.waitpid(solvers[cut], os.WNOHANG)
    assert "model" in sols[0].timings_s and "model" not in sols[cut].timings_s


def test_the_wait_for_the_second_chain_is_the_models_to_prepare_in(profile):
    # beside, once the first chain is solved, the model may prepare what completing will
    # need while the other chain runs; solved here, there is no wait
    betas = tuple(2 * math.pi / 45 * k / CHAINED for k in range(CHAINED))
    model = StandIn(again=0)
    drive(CASE, betas, model, profile, beside=True)
    count, busy = model.prepared
    assert count == CHAINED // 2 and callable(busy) and not busy()   # that chain has answered
    model = StandIn(again=0)
    drive(CASE, betas, model, profile)
    assert not hasattr(model, "prepared")


def test_a_chain_that_fails_beside_is_solved_here(profile):
    betas = tuple(2 * math.pi / 45 * k / CHAINED for k in range(CHAINED))
    sols = drive(CASE, betas, FailingBeside(0), profile, beside=True)
    assert {s.dofs for s in sols} == {os.getpid()}
    assert len(sols) == CHAINED


def test_a_short_cycle_is_one_chain(profile):
    betas = tuple(2 * math.pi / 45 * k / CHAINED for k in range(CHAINED - 1))
    sols = drive(CASE, betas, StandIn(again=0), profile, beside=True)
    assert {s.dofs for s in sols} == {os.getpid()}
    assert sum(s.detail.elastic_um != pytest.approx(5.0) for s in sols) == 1


def test_ahead_sees_every_position_before_the_model_completes_them(profile):
    betas = tuple(2 * math.pi / 45 * k / CHAINED for k in range(CHAINED))
    seen = []
    model = StandIn(again=0)
    model.completed = None
    sols = drive(CASE, betas, model, profile, beside=True,
                 ahead=lambda s: seen.append((list(s), model.completed)))
    ((given, completed),) = seen
    assert completed is None and tuple(given) == sols
    # what ahead started holds the second core: the model completes here alone …
    assert model.completed_beside is False
    # … where without it the second core is the model's to share
    drive(CASE, betas, model, profile, beside=True)
    assert model.completed_beside is True
    drive(CASE, betas, model, profile)
    assert model.completed_beside is False


class Templates(StandIn):
    """A model whose build reads no clearance states (the ring model's kind)."""

    reads_states = False

    def build(self, case, profile, states, beside=False):
        self.built_with = states
        super().build(case, profile, states, beside)

    def attempt(self, case, state, trial, near):
        self.states = getattr(self, "states", []) + [state]
        return super().attempt(case, state, trial, near)


def test_a_long_cycle_s_clearances_found_beside_the_build_are_the_ones_found_here(profile):
    from fegear.geometry import ToothContact

    betas = tuple(2 * math.pi / 45 * k / CHAINED for k in range(CHAINED))
    here = drive(CASE, betas, StandIn(again=0), profile)
    model = Templates(again=0)
    beside = drive(CASE, betas, model, profile, beside=True)
    assert model.built_with is None           # found in the fork, while the model was built
    assert [s.rotation for s in beside] == [s.rotation for s in here]
    direct = ToothContact(CASE.params, profile).states(betas[:CHAINED // 2], directions=(+1,))
    assert model.states == list(direct)       # the first chain's, as found here


def test_an_interference_found_beside_is_refused_all_the_same():
    from fegear.errors import GeometryError

    case = SolveCase(PairParameters(shift=0.016, rotation=0.002, tip_clearance=-1e-5),
                     torque=200.0)
    betas = tuple(2 * math.pi / 45 * k / CHAINED for k in range(CHAINED))
    with pytest.raises(GeometryError, match="interferes"):
        drive(case, betas, Templates(again=0), gear1_profile(case.params), beside=True)

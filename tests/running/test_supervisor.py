"""The supervisor (fegear/running/supervisor.py): every task's outcome given back once; a
worker's death sends the tasks it took to a fresh pool and gives up on the one that was
running after its retries; a task's own error is raised; SIGTERM and SIGINT stop the waiting,
not the caller."""

import os
import signal
import time

import pytest

from fegear.running import Supervisor, WorkerFailed


def _square(x):
    return x * x


def _die(_):
    os.kill(os.getpid(), signal.SIGKILL)


def _fails(_):
    raise ValueError("no")


def _slow(x):
    time.sleep(x)
    return x


def _all(tasks: Supervisor) -> dict:
    out = {}
    while tasks.under_way:
        for o in tasks.ended():
            assert o.name not in out
            out[o.name] = o
    return out


def test_each_task_comes_back_once_with_its_value():
    with Supervisor(2) as tasks:
        for k in range(5):
            tasks.submit(f"t{k}", _square, k)
        got = _all(tasks)
    assert {n: (o.value, o.lost) for n, o in got.items()} == {f"t{k}": (k * k, None)
                                                                for k in range(5)}


def test_a_task_that_kills_its_worker_is_given_up_after_its_retries_the_others_finish(
        tmp_path):
    with Supervisor(2, marks=tmp_path, retries=1) as tasks:
        tasks.submit("dies", _die, 0)
        for k in range(3):
            tasks.submit(f"t{k}", _square, k)
        got = _all(tasks)
    lost = got.pop("dies").lost
    assert isinstance(lost, WorkerFailed) and "died 2 times" in str(lost)
    assert {n: o.value for n, o in got.items()} == {"t0": 0, "t1": 1, "t2": 4}
    assert not list(tmp_path.iterdir())     # a task's mark goes with it


def test_without_marks_every_task_the_broken_pool_held_is_lost():
    with Supervisor(2) as tasks:
        tasks.submit("dies", _die, 0)
        tasks.submit("beside it", _slow, 30)
        got = _all(tasks)
    assert all(isinstance(o.lost, WorkerFailed) for o in got.values()) and len(got) == 2


def test_a_task_that_raises_raises_where_it_ended():
    with Supervisor(1) as tasks, pytest.raises(ValueError, match="no"):
        tasks.submit("fails", _fails, 0)
        _all(tasks)


@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGINT])
def test_a_signal_is_noted_and_ends_the_waiting(sig):
    before = signal.getsignal(sig)
    with Supervisor(1, poll_s=30) as tasks:
        tasks.submit("slow", _slow, 60)
        os.kill(os.getpid(), sig)
        start = time.monotonic()
        assert tasks.ended() == [] and tasks.stopped == sig
        assert time.monotonic() - start < 5
    assert signal.getsignal(sig) is before

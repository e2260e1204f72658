"""The executors (fegear/running/executors.py): the same results wherever a task runs; a
serial task runs when its result is read; a forked one sees what was built before and runs
in parallel; a task that fails in a worker raises where workers are strict and runs here, with a
warning, where they are not."""

import os
import signal

import numpy as np
import pytest

from fegear.running import SERIAL, Forks, Pool, WorkerFailed, pool_or_serial, spare_core


def _square(x):
    return x * x


def _pid_of(_):
    return os.getpid()


def _die(_):
    os.kill(os.getpid(), signal.SIGKILL)


def test_a_serial_task_runs_when_its_result_is_read():
    ran = []
    task = SERIAL.submit(lambda: ran.append(1) or 7)
    assert not ran and not task.done()
    assert task.result() == 7 and task.result() == 7 and ran == [1] and task.done()
    assert SERIAL.map(_square, [1, 2, 3]) == [1, 4, 9]


def test_forks_map_runs_the_first_here_and_the_rest_in_parallel():
    with Forks(2) as forks:
        pids = forks.map(_pid_of, range(2))
    assert pids[0] == os.getpid() and pids[1] != os.getpid()


def test_a_forked_task_sees_what_was_built_before_and_answers_in_place():
    built = np.arange(1e6)
    with Forks(2) as forks:
        task = forks.submit(lambda: built[::2].sum())
        assert task.result() == built[::2].sum()


def test_forks_run_one_task_in_parallel_at_once_the_next_here():
    with Forks(2) as forks:
        forked = forks.submit(os.getpid)
        here = forks.submit(os.getpid)            # the worker is busy: here, when read
        assert here.result() == os.getpid()
        assert forked.result() != os.getpid()
        again = forks.submit(os.getpid)           # the worker answered: forked again
        assert again.result() != os.getpid()


def test_a_forked_task_that_fails_raises_where_workers_are_strict():
    with Forks(2) as forks, pytest.raises(WorkerFailed, match="ValueError: no"):
        forks.submit(_fails).result()


def _fails():
    raise ValueError("no")


def test_a_forked_task_that_fails_runs_here_with_a_warning_in_use(monkeypatch, caplog):
    monkeypatch.delenv("FEGEAR_STRICT_WORKERS")
    parent = os.getpid()

    def fails_there():
        if os.getpid() != parent:
            raise ValueError("no")
        return "here"

    with Forks(2) as forks:
        assert forks.submit(fails_there).result() == "here"
    assert "a task failed in a worker process (ValueError: no); it runs here instead" in \
        caplog.text


def test_a_pool_runs_tasks_in_other_processes():
    with Pool(2) as pool:
        assert pool.map(_square, [1, 2, 3]) == [1, 4, 9]
        assert pool.submit(_pid_of, 0).result() != os.getpid()


def test_a_pool_whose_worker_dies_raises_where_strict_and_runs_here_in_use(monkeypatch,
                                                                          caplog):
    with Pool(1) as pool, pytest.raises(WorkerFailed, match="a worker process died"):
        pool.submit(_die, 0).result()
    monkeypatch.delenv("FEGEAR_STRICT_WORKERS")
    with Pool(1) as pool:
        assert pool.submit(_pid_of, 0).result() != os.getpid()
        task = pool.submit(_die_there, os.getpid())
        assert task.result() == "here"
        assert pool.broken and pool.submit(_pid_of, 0).result() == os.getpid()
    assert "a worker process died" in caplog.text


def _die_there(parent):
    if os.getpid() != parent:
        os.kill(os.getpid(), signal.SIGKILL)
    return "here"


def test_the_command_executors():
    assert pool_or_serial(1) is SERIAL
    with pool_or_serial(2) as pool:
        assert isinstance(pool, Pool) and pool.workers == 2
    spare = spare_core()
    assert spare is SERIAL or (isinstance(spare, Forks) and spare.workers == 2)

"""Processes made ready at a command's start (fegear.running.Primed): prepared before their
task, the task's data pickled to them, a failure told where the result is read, and nothing
left running."""

import os

import pytest

from fegear.running import Forks, Primed, WorkerFailed, spare_core

#: set by _prepare in the copy that runs it, never in this process
PREPARED = []


def _prepare():
    PREPARED.append(os.getpid())


def _what_was_prepared(extra):
    return list(PREPARED), extra


def test_the_copy_is_prepared_before_its_task_and_gets_the_task_s_data():
    with Primed(_prepare) as ready:
        prepared, extra = ready.submit(_what_was_prepared, {"big": list(range(100_000))}).result()
    assert len(prepared) == 1 and prepared[0] != os.getpid()
    assert extra == {"big": list(range(100_000))}
    assert PREPARED == []


def test_a_failed_task_is_told_where_its_result_is_read(monkeypatch):
    monkeypatch.setenv("FEGEAR_STRICT_WORKERS", "1")
    with Primed(_prepare) as ready:
        task = ready.submit(int, "not a number")
        with pytest.raises(WorkerFailed, match="not a number"):
            task.result()


def test_one_task_each_and_closed_whether_used_or_not():
    ready = Primed(_prepare)
    pid = ready._forked.pid
    ready.close()
    with pytest.raises(ChildProcessError):
        os.waitpid(pid, 0)           # ended and reaped
    with pytest.raises(RuntimeError, match="one task"):
        ready.submit(abs, -1)
    with Primed(_prepare) as used:
        assert used.submit(abs, -1).result() == 1
        with pytest.raises(RuntimeError, match="one task"):
            used.submit(abs, -2)


def test_the_spare_core_holds_as_many_as_asked_and_ends_those_not_taken():
    with Forks(2, _prepare, ready=2) as forks:
        first = forks.ready()
        second = forks.ready()
        assert forks.ready() is None
        pid = second._forked.pid
        assert first.submit(_what_was_prepared, 1).result()[1] == 1
    with pytest.raises(ChildProcessError):
        os.waitpid(pid, 0)
    assert spare_core().ready() is None    # none asked for

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


def _where(extra):
    return list(PREPARED), os.getpid(), extra


def test_its_tasks_and_no_more_and_closed_whether_used_or_not():
    ready = Primed(_prepare)
    pid = ready._forked.pid
    ready.close()
    with pytest.raises(ChildProcessError):
        os.waitpid(pid, 0)           # ended and reaped
    with pytest.raises(RuntimeError, match="takes 1 task"):
        ready.submit(abs, -1)
    with Primed(_prepare) as used:
        assert used.submit(abs, -1).result() == 1
        with pytest.raises(RuntimeError, match="takes 1 task"):
            used.submit(abs, -2)
    with Primed(_prepare, tasks=2) as two:
        first = two.submit(abs, -1)
        assert first.result() == 1   # read before the second was sent: none will come
        with pytest.raises(RuntimeError, match="takes 2 tasks, sent before any is read"):
            two.submit(abs, -2)


def test_its_tasks_share_one_preparation_and_run_side_by_side():
    """The first task runs in a copy of the prepared copy, the last in the copy itself: one
    preparation for both, two processes."""
    with Primed(_prepare, tasks=2) as ready:
        first = ready.submit(_where, "a")
        second = ready.submit(_where, {"big": list(range(100_000))})
        (prep_a, pid_a, a), (prep_b, pid_b, b) = first.result(), second.result()
    assert prep_a == prep_b and len(prep_a) == 1 and prep_a[0] == pid_b
    assert pid_a not in (pid_b, os.getpid()) and pid_b != os.getpid()
    assert (a, b) == ("a", {"big": list(range(100_000))})
    assert PREPARED == []


def test_a_task_that_fails_among_several_is_told_alone(monkeypatch):
    monkeypatch.setenv("FEGEAR_STRICT_WORKERS", "1")
    with Primed(_prepare, tasks=2) as ready:
        bad = ready.submit(int, "not a number")
        good = ready.submit(abs, -3)
        assert good.result() == 3
        with pytest.raises(WorkerFailed, match="not a number"):
            bad.result()


def test_the_spare_core_holds_one_copy_for_as_many_tasks_as_asked_and_ends_it():
    with Forks(2, _prepare, ready=2) as forks:
        first = forks.ready()
        second = forks.ready()
        assert forks.ready() is None
        assert first is second and first.tasks == 2
        pid = second._forked.pid
        assert first.submit(_what_was_prepared, 1).result()[1] == 1   # the other never sent
    with pytest.raises(ChildProcessError):
        os.waitpid(pid, 0)
    assert spare_core().ready() is None    # none asked for

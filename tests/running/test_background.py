"""Work beside the main thread (fegear.running.meanwhile): its value, its failure kept for
the reader, and a fork that waits for it."""

import threading

import pytest

from fegear.running import Forks, meanwhile


def test_the_value_and_the_failure_come_back_where_the_result_is_read():
    assert meanwhile(divmod, 7, 2).result() == (3, 1)
    task = meanwhile(int, "not a number")
    with pytest.raises(ValueError, match="not a number"):
        task.result()
    assert task.done()


def test_a_fork_waits_for_the_work_under_way():
    """The forked copy sees what the thread made: the fork was made after it ended (a copy
    forked while a thread imports would keep that module locked for good)."""
    release = threading.Event()
    made = []

    def slow():
        release.wait(5.0)
        made.append("ready")
        return len(made)

    task = meanwhile(slow)
    threading.Timer(0.2, release.set).start()
    with Forks(2) as forks:
        seen = forks.submit(lambda: list(made)).result()
    assert seen == ["ready"]
    assert task.result() == 1


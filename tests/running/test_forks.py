"""One function in a forked copy of the process (fegear/running/forks.py, Forked): its value
back in place, a failure or a death as WorkerFailed with what happened, its output discarded,
and ended when the caller stops it."""

import os
import signal
import sys
import time

import numpy as np
import pytest

from fegear.running.forks import Forked, WorkerFailed


def test_the_value_comes_back_from_another_process():
    data = np.arange(1_000_000.0)       # built here, read there without a copy
    f = Forked(lambda: (os.getpid(), data.sum(), {"a": data[:3]}))
    pid, total, rest = f.result()
    assert pid != os.getpid()
    assert total == data.sum()
    assert np.array_equal(rest["a"], data[:3])
    with pytest.raises(WorkerFailed, match="stopped before it answered"):
        f.result()                      # read once; the child reaped
    f.stop()


def test_a_failure_there_is_told_here_with_its_traceback():
    def fails():
        raise ValueError("nothing to see")

    with pytest.raises(WorkerFailed, match="ValueError: nothing to see"):
        Forked(fails).result()


def test_a_value_that_does_not_pickle_is_a_failure():
    with pytest.raises(WorkerFailed, match="pickle"):
        Forked(lambda: (lambda: 1)).result()


def test_a_child_killed_is_a_failure():
    with pytest.raises(WorkerFailed, match="died before it answered"):
        Forked(lambda: os.kill(os.getpid(), signal.SIGKILL)).result()


def test_its_output_goes_nowhere(capfd):
    def noisy():
        print("out")
        print("err", file=sys.stderr)
        return 1

    assert Forked(noisy).result() == 1
    assert capfd.readouterr() == ("", "")


def test_stop_ends_a_child_still_running():
    f = Forked(lambda: time.sleep(60))
    pid = f.pid
    f.stop()            # killed and reaped (else this waits the minute out)
    try:
        os.kill(pid, 0)
        alive = True
    except ProcessLookupError:
        alive = False
    assert not alive
    with pytest.raises(WorkerFailed):
        f.result()


def test_a_large_answer_waits_for_nobody():
    # 16 MB, far more than a pipe holds: the child leaves it in memory and ends without
    # waiting for the parent to read (through the pipe it would wait at its write)
    data = np.arange(2_000_000.0)
    f = Forked(lambda: data * 2.0)
    pid = f.pid
    deadline = time.monotonic() + 10.0
    ended = 0
    while not ended and time.monotonic() < deadline:
        ended, _ = os.waitpid(pid, os.WNOHANG)
        time.sleep(0.01)
    assert ended == pid                 # it ended with its answer unread
    f.pid = None                        # reaped here
    assert np.array_equal(f.result(), data * 2.0)


def test_arrays_come_back_read_in_place_and_writable():
    import mmap

    big = np.arange(300_000.0).reshape(1000, 300)
    parts = {"big": big, "fortran": np.asfortranarray(big[:, :7]), "strided": big[::3, ::2],
             "empty": np.zeros((0, 4)), "ints": np.arange(5, dtype=np.int64), "text": "x" * 9}
    got = Forked(lambda: parts).result()
    for k, v in parts.items():
        assert np.array_equal(got[k], v) if k != "text" else got[k] == v
    # the large contiguous ones are the in-memory file's pages, not a copy of them
    base = got["big"]
    while not isinstance(base, mmap.mmap) and getattr(base, "base", None) is not None:
        base = base.base
    owner = base.obj if isinstance(base, memoryview) else base
    assert isinstance(owner, mmap.mmap)
    assert got["big"].ctypes.data % 64 == 0          # aligned
    got["big"][0, 0] = -1.0                          # private pages: writable here alone
    assert got["big"][0, 0] == -1.0 and big[0, 0] == 0.0

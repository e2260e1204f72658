"""Local process pools (fegear/running/pools.py): their workers leave Ctrl-C to the parent,
also while they start; a worker's death breaks the pool at once, whichever submission spawned
it."""

import os
import signal
import time
from concurrent.futures.process import BrokenProcessPool

from fegear.running import LocalPool


def _pid() -> int:
    return os.getpid()


def _sleep(s: float) -> float:
    time.sleep(s)
    return s


def _die() -> None:
    os.kill(os.getpid(), signal.SIGKILL)


def test_a_worker_spawned_for_a_later_task_that_dies_breaks_the_pool_at_once(monkeypatch):
    """The pool's manager thread watches the workers it knew when it began to wait, and a
    submission wakes it before it spawns the worker for its task: unless the pool wakes it
    again, a worker spawned so that dies can break the pool only after the task beside it
    has finished. The spawn is slowed here so that the thread surely waits again before the
    worker is there (as on a loaded machine)."""
    from multiprocessing.context import SpawnProcess

    start = SpawnProcess.start

    def slow_start(process):
        time.sleep(0.2)
        start(process)

    monkeypatch.setattr(SpawnProcess, "start", slow_start)
    pool = LocalPool(2)
    try:
        pool.submit(_pid).result()        # the first worker, idle: it takes the next task
        beside = pool.submit(_sleep, 30)
        dies = pool.submit(_die)          # on a second worker, spawned for it
        assert isinstance(beside.exception(timeout=60), BrokenProcessPool)
        assert isinstance(dies.exception(timeout=5), BrokenProcessPool)
    finally:
        pool.stop()


def test_a_pool_worker_hit_by_ctrl_c_while_it_starts_lives_and_says_nothing(capfd):
    """Ctrl-C on a terminal signals the whole process group: the pool's workers too, which
    leave it to the parent, also while they still import (a KeyboardInterrupt's traceback
    there and a broken pool, before)."""
    import psutil

    pool = LocalPool(1)
    try:
        before = {p.pid for p in psutil.Process().children()}
        future = pool.submit(_pid)
        deadline = time.monotonic() + 60
        hit = set()
        while not future.done() and time.monotonic() < deadline:
            for p in psutil.Process().children():
                try:
                    if p.pid not in before and any("spawn_main" in c for c in p.cmdline()):
                        os.kill(p.pid, signal.SIGINT)
                        hit.add(p.pid)
                except (psutil.Error, ProcessLookupError):   # it died of it
                    continue
            time.sleep(0.005)
        assert future.result(timeout=1) in hit
    finally:
        pool.stop()
    assert "Traceback" not in capfd.readouterr().err

"""Local process pools (fegear/running/pools.py): their workers leave Ctrl-C to the parent,
also while they start."""

import os
import signal
import time

from fegear.running import local_pool


def _pid() -> int:
    return os.getpid()


def test_a_pool_worker_hit_by_ctrl_c_while_it_starts_lives_and_says_nothing(capfd):
    """Ctrl-C on a terminal signals the whole process group: the pool's workers too, which
    leave it to the parent, also while they still import (a KeyboardInterrupt's traceback
    there and a broken pool, before)."""
    import psutil

    pool = local_pool(1)
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

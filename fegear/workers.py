"""Worker pools: the local process pools of the study runner, the relief search and the design
search (:class:`LocalPool`: all three end their workers the same way), and the Dask client of
the first and the last.

Workers are spawned, not forked (the parent may hold threads: the progress bar's), leave
Ctrl-C to the parent and end when it does: a parent killed outright (SIGKILL) leaves no time
to stop them, and one would finish its task for nobody and then wait forever for the next.
"""

from __future__ import annotations

import os
import signal
import threading
import time
from concurrent.futures import ProcessPoolExecutor

from .errors import FegearError


class LocalPool(ProcessPoolExecutor):
    """A pool of spawned processes set up by :func:`init_worker` that can be stopped at once
    (:meth:`stop`), broken or not."""

    def __init__(self, workers: int) -> None:
        import multiprocessing

        self._before = _children()
        super().__init__(workers, mp_context=multiprocessing.get_context("spawn"),
                         initializer=init_worker)

    def stop(self) -> None:
        """Shut down without waiting for the tasks under way: terminate the workers, the
        children of this process that multiprocessing's spawn started since the pool was
        made (found by psutil: a broken pool has forgotten its own)."""
        import psutil

        procs = []
        for p in psutil.Process().children():
            try:
                if p.pid not in self._before and any("spawn_main" in part
                                                     for part in p.cmdline()):
                    procs.append(p)
            except psutil.Error:
                continue
        self.shutdown(wait=False, cancel_futures=True)
        for p in procs:
            try:
                p.terminate()
            except psutil.NoSuchProcess:
                continue
        # no psutil.wait_procs: reaping them here would hide their exit from
        # multiprocessing, whose shutdown then waits forever


def local_pool(workers: int) -> LocalPool:
    """A pool of ``workers`` spawned processes set up by :func:`init_worker`."""
    return LocalPool(workers)


def _children() -> set[int]:
    import psutil

    return {p.pid for p in psutil.Process().children()}


def init_worker() -> None:
    """A local pool's worker: Ctrl-C is left to the parent, and it ends with the parent."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    threading.Thread(target=_exit_with_parent, args=(os.getppid(),), daemon=True).start()


def _exit_with_parent(parent: int) -> None:
    while os.getppid() == parent:
        time.sleep(0.5)
    os._exit(1)


def connect(address: str, error: type[FegearError] = FegearError):
    """A Dask distributed client of the scheduler at ``address`` (``--scheduler``); what is
    wrong is raised as ``error``, naming the option."""
    try:
        from distributed import Client
    except ImportError as exc:
        raise error(f"--scheduler needs Dask distributed: {exc}") from None
    try:
        return Client(address, timeout="10s")
    except (OSError, TimeoutError, ValueError, TypeError) as exc:
        raise error(f"--scheduler {address!r}: cannot connect: {exc}") from None

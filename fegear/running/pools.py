"""Worker pools: the local process pools of the study runner, the relief search and the design
search (:class:`LocalPool`: all three end their workers the same way), and the Dask client of
the first and the last.

Pool workers are spawned, not forked (the parent may hold threads: the progress bar's). All
leave Ctrl-C to the parent and end when it does: a parent killed outright (SIGKILL) leaves no
time to stop them, and one would finish its task for nobody and then wait forever for the next.
Such a parent also leaves the named semaphores of its pool's queues behind, which
multiprocessing's resource tracker would remove with a warning on the terminal ("There appear
to be 5 leaked semaphore objects"); its workers remove them before they end.
"""

from __future__ import annotations

import os
import signal
import threading
import time
from concurrent.futures import ProcessPoolExecutor

from ..errors import FegearError


class LocalPool(ProcessPoolExecutor):
    """A pool of spawned processes set up by :func:`init_worker` that can be stopped at once
    (:meth:`stop`), broken or not, and that breaks as soon as a worker dies, whichever
    submission spawned it (:meth:`_spawn_process`)."""

    def __init__(self, workers: int) -> None:
        import multiprocessing

        self._before = _children()
        super().__init__(workers, mp_context=multiprocessing.get_context("spawn"),
                         initializer=init_worker)
        # read when the workers are spawned, at the first submission
        self._initargs = (_semaphores(self),)

    def submit(self, fn, /, *args, **kwargs):
        """As the pool's, with SIGINT held back from the workers it spawns: they are born
        with it blocked and ignore it once set up (:func:`init_worker`), so that a Ctrl-C
        to the whole process group while they still import is not a traceback of theirs
        and a broken pool. Here it waits the few milliseconds of the spawn."""
        if not hasattr(signal, "pthread_sigmask"):   # pragma: no cover - Windows
            return super().submit(fn, *args, **kwargs)
        held = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
        try:
            return super().submit(fn, *args, **kwargs)
        finally:
            signal.pthread_sigmask(signal.SIG_SETMASK, held)

    def _spawn_process(self) -> None:
        """As the pool's, then a wake-up for its manager thread, which watches for a worker's
        death only among the workers it knew when it last began to wait. ``submit`` wakes it
        before it spawns the worker that takes the task (CPython 3.11 to 3.13), so the thread
        often waits again without that worker, and its death would go unseen until another
        task ended: a broken pool's tasks then wait for the longest of those still running."""
        super()._spawn_process()
        wakeup = getattr(self, "_executor_manager_thread_wakeup", None)
        if wakeup is not None:   # None once shut down
            wakeup.wakeup()

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
        manager = getattr(self, "_executor_manager_thread", None)
        self.shutdown(wait=False, cancel_futures=True)
        for p in procs:
            try:
                p.terminate()
            except psutil.NoSuchProcess:
                continue
        # the pool's manager thread sees its workers end and closes its wake-up pipe; at the
        # interpreter's exit multiprocessing writes to that pipe unlocked (CPython 3.11), so
        # a close under way then is an EBADF traceback: let the thread finish here
        if manager is not None:
            manager.join(timeout=10)
        # no psutil.wait_procs: reaping them here would hide their exit from
        # multiprocessing, whose shutdown then waits forever


def _children() -> set[int]:
    import psutil

    return {p.pid for p in psutil.Process().children()}


def _semaphores(pool: ProcessPoolExecutor) -> tuple[str, ...]:
    """The names of the semaphores that the pool's call and result queues hold (five in
    CPython 3.11), registered with the resource tracker by this process."""
    from multiprocessing.synchronize import SemLock

    queues = (getattr(pool, "_call_queue", None), getattr(pool, "_result_queue", None))
    locks = [v for q in queues if q is not None for v in vars(q).values()
             if isinstance(v, SemLock)]
    return tuple(n for n in (getattr(lock._semlock, "name", None) for lock in locks) if n)


def init_worker(semaphores: tuple[str, ...] = ()) -> None:
    """A local pool's worker: Ctrl-C is left to the parent, and it ends with the parent,
    removing the ``semaphores`` of the pool's queues if the parent could not."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    if hasattr(signal, "pthread_sigmask"):   # blocked since its spawn
        signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT})
    threading.Thread(target=exit_with_parent, args=(os.getppid(), semaphores),
                     daemon=True).start()


def exit_with_parent(parent: int, semaphores: tuple[str, ...] = ()) -> None:
    """Wait for the process ``parent`` to end, then end this one (a worker's thread), first
    removing ``semaphores`` (:func:`_remove`)."""
    while os.getppid() == parent:
        time.sleep(0.5)
    _remove(semaphores)
    os._exit(1)


def _remove(semaphores: tuple[str, ...]) -> None:
    """Unlink the named semaphores a dead parent registered and tell its resource tracker,
    as the parent's own exit would have: the worker that unlinks a name unregisters it (a
    name already gone was removed by another worker, or by the parent before it ended)."""
    if not semaphores:
        return
    try:
        from _multiprocessing import sem_unlink
        from multiprocessing import resource_tracker
    except ImportError:   # pragma: no cover - no named semaphores here
        return
    for name in semaphores:
        try:
            sem_unlink(name)
        except OSError:
            continue
        try:
            resource_tracker.unregister(name, "semaphore")
        except Exception:   # noqa: BLE001  no tracker to tell: it left nothing to warn of
            pass


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

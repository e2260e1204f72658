"""Worker pools: the local process pools of the study runner, the relief search and the design
search (:class:`LocalPool`: all three end their workers the same way), and the Dask client of
the first and the last; and one function run in a forked copy of this process
(:class:`Forked`: the error estimate's second solve, a mesh cycle's clearance states, its
second chain of positions on the model built here and a share of its peaks' submodels).

Pool workers are spawned, not forked (the parent may hold threads: the progress bar's). All
leave Ctrl-C to the parent and end when it does: a parent killed outright (SIGKILL) leaves no
time to stop them, and one would finish its task for nobody and then wait forever for the next.
Such a parent also leaves the named semaphores of its pool's queues behind, which
multiprocessing's resource tracker would remove with a warning on the terminal ("There appear
to be 5 leaked semaphore objects"); its workers remove them before they end.
"""

from __future__ import annotations

import os
import pickle
import select
import signal
import sys
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


def second_core() -> bool:
    """Whether the machine has a second core for a one-off command's work beside its own
    (counted as the relief search and the design search count cores)."""
    return (os.cpu_count() or 1) >= 2


def local_pool(workers: int) -> LocalPool:
    """A pool of ``workers`` spawned processes set up by :func:`init_worker`."""
    return LocalPool(workers)


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
    threading.Thread(target=_exit_with_parent, args=(os.getppid(), semaphores),
                     daemon=True).start()


def _exit_with_parent(parent: int, semaphores: tuple[str, ...] = ()) -> None:
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


class Forked:
    """``fn()`` run in a forked copy of this process, which shares everything built so far
    (a ring model's meshes and factors) without copying it; :meth:`result` is its return
    value, pickled back into an anonymous in-memory file made before the fork (a pipe only says
    when it is there: a mesh cycle's second chain, 15 MB, crossed a pipe, which holds 64 kB,
    only as the parent read it, in 40 ms after its own chain; read from memory, 10 ms), or
    through the pipe where no such file can be made. In that file its arrays' data lie beside
    the pickle (out of band) and are read in place, not copied (:func:`_loaded`): gear 1's
    responses formed beside a solve's build, 64 MB, took 26 ms to pickle, as long to write
    and as long to read back. The child touches none of the parent's
    streams or locks (another thread of the parent, the progress bar's, may hold one at the
    fork): its output goes nowhere and the progress is not reported. Anywhere but Linux (no
    ``os.fork`` on Windows; on macOS a fork after Apple's BLAS has run may crash, and
    multiprocessing spawns there for that reason), or the child failing in any way, the result
    is None: the caller then does the work itself, and raises whatever error it meets there."""

    def __init__(self, fn) -> None:
        self.pid = None
        self._pipe = None
        self._memory = None
        if not sys.platform.startswith("linux"):   # pragma: no cover - not Linux
            return
        try:
            self._memory = os.memfd_create("fegear-forked", os.MFD_CLOEXEC)
        except (AttributeError, OSError):   # pragma: no cover - a kernel before 3.17
            self._memory = None
        r, w = os.pipe()
        try:
            pid = os.fork()
        except OSError:
            os.close(r)
            os.close(w)
            self._close_memory()
            return
        if pid == 0:
            os.close(r)
            _forked_child(fn, w, self._memory)      # never returns
        os.close(w)
        self.pid, self._pipe = pid, os.fdopen(r, "rb")

    def result(self):
        """The child's return value, once it has ended; None if it failed or never ran."""
        if self._pipe is None:
            return None
        try:
            data = self._pipe.read()
            if self._memory is not None and data == _IN_MEMORY:
                return _loaded(self._memory)
            return _loaded(data)
        finally:
            self._pipe.close()
            self._pipe = None
            self._close_memory()
            self._reap()

    def _close_memory(self) -> None:
        if self._memory is not None:
            os.close(self._memory)
            self._memory = None

    def running(self) -> bool:
        """Whether the child is still at its work: nothing of its answer in the pipe yet (a
        child that failed or never ran is not)."""
        if self._pipe is None:
            return False
        ready, _, _ = select.select([self._pipe], [], [], 0.0)
        return not ready

    def stop(self) -> None:
        """End the child if it still runs (the caller stopped or failed meanwhile)."""
        if self.pid is None:
            return
        try:
            os.kill(self.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        if self._pipe is not None:
            self._pipe.close()
            self._pipe = None
        self._close_memory()
        self._reap()

    def _reap(self) -> None:
        if self.pid is not None:
            try:
                os.waitpid(self.pid, 0)
            except ChildProcessError:
                pass
            self.pid = None


#: what the pipe says when the answer is in the in-memory file
_IN_MEMORY = b"m"


def _loaded(answer: bytes | int):
    """The value of a child's ``answer``: its pickled (ok, value), or the in-memory file that
    holds them (:func:`_written`), read in place; None if the child failed or was cut short."""
    import mmap

    try:
        if isinstance(answer, bytes):
            ok, value = pickle.loads(answer)
        else:
            # a private mapping: the arrays read from it may be written to (their pages are
            # then copied); it lasts as long as they do
            m = mmap.mmap(answer, os.fstat(answer).st_size, access=mmap.ACCESS_COPY)
            view = memoryview(m)
            head = int.from_bytes(view[:8], "little")
            at, buffers = 8 + head, []
            while at < len(view):
                size = int.from_bytes(view[at:at + 8], "little")
                at = _aligned(at + 8)
                buffers.append(view[at:at + size])
                at += size
            ok, value = pickle.loads(view[8:8 + head], buffers=buffers)
    except Exception:   # cut short: the child died before writing all of it
        return None
    return value if ok else None


def _written(f, value) -> None:
    """``value`` pickled into the file ``f``: the pickle's length and the pickle, then each of
    its out-of-band buffers (an array's data) as its length and its bytes, aligned to
    :data:`ALIGN` bytes (:func:`_loaded` reads them in place)."""
    buffers: list = []
    data = pickle.dumps(value, protocol=5, buffer_callback=buffers.append)
    f.write(len(data).to_bytes(8, "little"))
    f.write(data)
    at = 8 + len(data)
    for buffer in buffers:
        raw = buffer.raw()
        f.write(raw.nbytes.to_bytes(8, "little"))
        start = _aligned(at + 8)
        f.write(bytes(start - at - 8))
        f.write(raw)
        at = start + raw.nbytes


ALIGN = 64   # bytes: an array read in place starts on a cache line


def _aligned(at: int) -> int:
    return -(-at // ALIGN) * ALIGN


def _forked_child(fn, fd: int, memory: int | None) -> None:
    """The forked child: Ctrl-C left to the parent, SIGTERM ending it, its output discarded;
    it ends with the parent, and writes (ok, value) into the in-memory file ``memory`` and
    then :data:`_IN_MEMORY` to ``fd`` (without that file, the value itself to ``fd``)."""
    import logging

    from . import progress

    code = 1
    try:
        signal.signal(signal.SIGINT, signal.SIG_IGN)
        signal.signal(signal.SIGTERM, signal.SIG_DFL)
        # the log's handlers hold the parent's stderr, whose lock another thread may have
        # held at the fork
        logging.disable(logging.CRITICAL)
        sys.stdout = sys.stderr = open(os.devnull, "w")
        threading.Thread(target=_exit_with_parent, args=(os.getppid(),), daemon=True).start()
        with progress.reporting(None):
            value = (True, fn())
        if memory is None:
            data = pickle.dumps(value, protocol=pickle.HIGHEST_PROTOCOL)
        else:
            with os.fdopen(memory, "wb", closefd=False) as f:
                _written(f, value)
            data = _IN_MEMORY
        code = 0
    except BaseException:   # any failure: the parent does the work itself
        data = pickle.dumps((False, None))
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
    finally:
        os._exit(code)

"""Independent tasks on a pool of worker processes, watched (:class:`Supervisor`): what the
study runner runs its cases on and the design search its trials.

A worker process that dies (killed, out of memory, a crash in a native library) breaks a
local pool: every task under way in it is lost. The supervisor starts a fresh pool and sends
those tasks again, except a task that was running when a worker died more than ``retries``
times: that one comes back *lost* (:class:`Outcome`), for the caller to record, so that a task
that kills its worker every time cannot stop the others. Which tasks were running is told by
marks: in a ``marks`` folder a task is the file ``<name>.<pid>`` while it runs in a worker
(without one, every task the broken pool held counts as running). On a Dask cluster, whose
scheduler already runs a task again when its worker dies, a task the cluster gives up on
comes back lost at once.

SIGTERM and SIGINT stop nothing half-way: within the supervisor's block they are noted
(:attr:`Supervisor.stopped`), :meth:`Supervisor.ended` then answers at once, and the caller
ends what it does (keeps what finished, says what did not) before it stops. The block's end
ends the workers, a task still running included.
"""

from __future__ import annotations

import logging
import os
import signal
import threading
import uuid
from collections.abc import Callable
from concurrent.futures import FIRST_COMPLETED, Future, wait
from concurrent.futures.process import BrokenProcessPool
from dataclasses import dataclass
from pathlib import Path

from .forks import WorkerFailed
from .pools import LocalPool

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class Outcome:
    """How a task ended: ``name`` as it was submitted, and its return ``value``, or ``lost``:
    why it gave none (:class:`~.forks.WorkerFailed`: its worker process died too often;
    anything else: what the Dask cluster raised for it)."""

    name: str
    value: object = None
    lost: BaseException | None = None


@dataclass(frozen=True)
class _Task:
    name: str
    fn: Callable
    args: tuple


class Supervisor:
    """Tasks on a local pool of ``workers`` spawned processes (:class:`~.pools.LocalPool`),
    or on the cluster of the Dask ``client`` (its workers need fegear installed; the client
    stays the caller's to close), each given back as an :class:`Outcome` when it ends. A task
    that raises in a local worker raises the same from :meth:`ended`. ``marks``: the folder
    that tells which tasks a dead worker was running (what a dead pool or a killed run left
    there is removed); ``retries``: how often such a task is sent again before it comes back
    lost; ``poll_s``: how long :meth:`ended` waits for a task before it answers."""

    def __init__(self, workers: int, client=None, marks: Path | None = None,
                 retries: int = 0, poll_s: float = 0.5) -> None:
        self.workers, self.marks, self.retries, self.poll_s = workers, marks, retries, poll_s
        #: the first SIGTERM or SIGINT received within the block, else None
        self.stopped: int | None = None
        self._cluster = None if client is None else client.get_executor(pure=False)
        self._token = uuid.uuid4().hex[:8]   # a Dask key of this supervisor's alone
        self._pool: LocalPool | None = None
        self._running: dict[Future, _Task] = {}
        self._ready: list[Outcome] = []
        self._deaths: dict[str, int] = {}
        self._held: dict = {}

    def submit(self, name: str, fn: Callable, /, *args) -> None:
        """Start ``fn(*args)`` as the task ``name`` (unique among those under way)."""
        self._send(_Task(name, fn, args))

    @property
    def under_way(self) -> int:
        """The tasks submitted whose outcome :meth:`ended` has not given yet."""
        return len(self._running) + len(self._ready)

    def ended(self) -> list[Outcome]:
        """The tasks that ended since it was last asked, after waiting up to ``poll_s`` for
        one (once a signal stopped the block, it waits no more)."""
        if not self._ready and self._running and self.stopped is None:
            done, _ = wait(self._running, timeout=self.poll_s, return_when=FIRST_COMPLETED)
            for future in done:
                if future in self._running:   # a broken pool has taken its tasks back
                    self._end(future)
        out, self._ready = self._ready, []
        return out

    def _end(self, future: Future) -> None:
        try:
            value = future.result()
        except BrokenProcessPool:             # a worker died: every task under way is lost
            self._broken()
            return
        except Exception as exc:  # noqa: BLE001  a task the cluster lost (KilledWorker …)
            task = self._running.pop(future)
            if self._cluster is None:
                raise
            self._ready.append(Outcome(task.name, lost=exc))
            return
        self._ready.append(Outcome(self._running.pop(future).name, value))

    def _send(self, task: _Task) -> None:
        if self._cluster is not None:
            future = self._cluster.submit(task.fn, *task.args,
                                          key=f"fegear-{task.name}-{self._token}")
        else:
            if self._pool is None:
                self._start()
            call = ((_marked, str(self.marks), task.name, task.fn, task.args) if self.marks
                    else (task.fn, *task.args))
            try:
                future = self._pool.submit(*call)
            except BrokenProcessPool:   # a worker died before a result said so: the task
                future = Future()       # is one the broken pool held (ran, without marks)
                future.set_exception(BrokenProcessPool("a worker process died"))
                self._running[future] = task
                self._broken()
                return
        self._running[future] = task

    def _start(self) -> None:
        if self.marks:
            for stale in self.marks.glob("*"):   # a dead worker's, or a killed run's
                stale.unlink(missing_ok=True)
        self._pool = LocalPool(self.workers)

    def _broken(self) -> None:
        """The pool broke: the tasks it held go to a fresh pool, those that were running when
        a worker died once more than ``retries`` times come back lost."""
        held = {f: t for f, t in self._running.items()
                if not f.done() or isinstance(f.exception(), BrokenProcessPool)}
        if self.marks:
            marks = list(self.marks.glob("*"))
            running = {p.name.rsplit(".", 1)[0] for p in marks}
            for mark in marks:                   # the dead pool's: read, done with
                mark.unlink(missing_ok=True)
        else:
            running = {t.name for t in held.values()}
        self._pool.stop()
        self._pool = None
        again = []
        for future, task in held.items():
            del self._running[future]
            if task.name in running:
                self._deaths[task.name] = self._deaths.get(task.name, 0) + 1
                if self._deaths[task.name] > self.retries:
                    self._ready.append(Outcome(task.name, lost=WorkerFailed(
                        f"its worker process died {self._deaths[task.name]} times")))
                    continue
            again.append(task)
        log.warning("a worker process died running %s%s", ", ".join(sorted(running)) or "?",
                    f"; {len(again)} unfinished tasks go to a new pool" if again else "")
        for task in again:
            self._send(task)

    def close(self) -> None:
        """End what still runs: the local workers at once, the cluster's tasks cancelled."""
        if self._pool is not None:
            self._pool.stop()
            self._pool = None
        for future in self._running:
            future.cancel()
        self._running.clear()

    def __enter__(self) -> Supervisor:
        if threading.current_thread() is threading.main_thread():
            for sig in (signal.SIGTERM, signal.SIGINT):
                self._held[sig] = signal.signal(sig, self._stop)
        return self

    def __exit__(self, *exc) -> None:
        try:
            self.close()
        finally:
            for sig, handler in self._held.items():
                signal.signal(sig, handler)
            self._held.clear()

    def _stop(self, signum, frame) -> None:
        if self.stopped is None:
            self.stopped = signum


def _marked(marks: str, name: str, fn: Callable, args: tuple):
    """``fn(*args)`` in a worker, marked in ``marks`` as ``<name>.<pid>`` while it runs."""
    mark = Path(marks) / f"{name}.{os.getpid()}"
    mark.touch()
    try:
        return fn(*args)
    finally:
        mark.unlink(missing_ok=True)

"""Where work runs: the one layer of fegear that knows about processes.

A command or a job makes an executor where it starts and hands it to the code that has work
to share. That code submits tasks (:meth:`Executor.submit`, :meth:`Executor.map`) and reads
their results; it never learns where they ran, and the numbers are the same wherever they did.

* :class:`Serial`: everything in this process, a submitted task when its result is read.
* :class:`Forks`: a task in a forked copy of this process, which shares what is built so far
  (a ring model's meshes and factors), one at a time in parallel with this process: a
  one-off command's second core (:func:`spare_core`).
* :class:`Pool`: tasks on spawned worker processes that share nothing (a relief search's
  trials, each a mesh cycle of its own).
* :class:`Cluster`: tasks on a Dask cluster's workers (``--scheduler``), which share nothing
  either.

Whether a task sees what this process built is the executor's ``shares_memory``: where it
does not, a task builds what it needs (a ring model) in the process it runs in, and what it
gives back must be plain data.

A task that fails where it was sent (it raised there, or its process died) raises
:class:`~.forks.WorkerFailed` where its result is read if workers are strict (the tests set
``FEGEAR_STRICT_WORKERS=1``: a change that stops something pickling must not pass as lost
speed); otherwise a warning is logged and the task runs again here.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterable
from typing import Protocol

from .forks import Forked, WorkerFailed, again_here, available
from .pools import LocalPool
from .primed import Primed


class Task(Protocol):
    """What :meth:`Executor.submit` gives back."""

    def result(self):
        """The task's return value (it raises what the task raised)."""

    def done(self) -> bool:
        """Whether its result is there to read without waiting."""


class Executor(Protocol):
    """Runs tasks for the code it is handed to; ``workers``: how many at once, the caller's
    own process included; ``shares_memory``: whether a task sees what this process built
    (its models, by reference) and can give back what refers to it."""

    workers: int
    shares_memory: bool

    def submit(self, fn: Callable, /, *args) -> Task:
        """Start ``fn(*args)`` (or leave it for when its result is read)."""

    def map(self, fn: Callable, items: Iterable) -> list:
        """``[fn(x) for x in items]``, in order, each wherever the executor runs it."""

    def close(self) -> None:
        """End what still runs for it."""

    def ready(self) -> Primed | None:
        """A process made ready when the executor was made (:func:`spare_core`'s
        ``prepare``), taken for one of its tasks: None where there is none (left)."""


class _Later:
    """A task run here, when its result is first read."""

    def __init__(self, fn: Callable, args: tuple) -> None:
        self._fn, self._args, self._done, self._value = fn, args, False, None

    def result(self):
        if not self._done:
            self._value, self._done = self._fn(*self._args), True
            self._fn = self._args = None
        return self._value

    def done(self) -> bool:
        return self._done


class Serial:
    """Every task here, in the order their results are read."""

    workers = 1
    shares_memory = True

    def submit(self, fn: Callable, /, *args) -> Task:
        return _Later(fn, args)

    def map(self, fn: Callable, items: Iterable) -> list:
        return [fn(x) for x in items]

    def close(self) -> None:
        """Nothing to end: every task ran in this process when it was asked for."""

    def ready(self) -> None:
        return None

    def __enter__(self) -> Serial:
        return self

    def __exit__(self, *exc) -> None:
        self.close()


#: the executor of code given none: everything here
SERIAL = Serial()


class _InFork:
    """A task under way in a forked copy of this process."""

    def __init__(self, owner: Forks, fn: Callable, args: tuple) -> None:
        self._owner, self._fn, self._args = owner, fn, args
        self._child: Forked | None = Forked(lambda: fn(*args))
        self._got: tuple | None = None

    def result(self):
        if self._got is None:
            try:
                self._got = (self._child.result(),)
            except WorkerFailed as err:
                self._got = (again_here(err, self._fn, self._args),)
            finally:
                self._child = None
                self._owner._ended(self)
        return self._got[0]

    def done(self) -> bool:
        return self._got is not None

    def stop(self) -> None:
        if self._child is not None:
            self._child.stop()
            self._child = None


class Forks:
    """Tasks in forked copies of this process (where it can fork: :func:`.forks.available`),
    ``workers - 1`` at once in parallel with it; a task submitted while they are all busy runs
    here when its result is read. A forked task sees everything this process had built when it
    was submitted, and what it builds is lost with it: only its return value comes back.
    With ``prepare``, a copy is forked at once and runs it, ready for ``ready`` tasks
    (:class:`~.primed.Primed`: each but the last in a copy of it, so ``prepare`` runs once);
    :meth:`ready` hands it out once for each, :meth:`close` ends it, used or not."""

    shares_memory = True

    def __init__(self, workers: int = 2, prepare: Callable[[], object] | None = None,
                 ready: int = 0) -> None:
        self.workers = workers
        self._running: list[_InFork] = []
        self._primed = [Primed(prepare, ready)] if ready and prepare and available() else []
        self._ready = self._primed * ready

    def submit(self, fn: Callable, /, *args) -> Task:
        if not available() or len(self._running) >= self.workers - 1:
            return _Later(fn, args)
        task = _InFork(self, fn, args)
        self._running.append(task)
        return task

    def map(self, fn: Callable, items: Iterable) -> list:
        items = list(items)
        others = [self.submit(fn, x) for x in items[1:]]
        try:
            first = [fn(x) for x in items[:1]]
            return first + [t.result() for t in others]
        finally:
            for t in others:
                if isinstance(t, _InFork):
                    t.stop()

    def _ended(self, task: _InFork) -> None:
        if task in self._running:
            self._running.remove(task)

    def ready(self) -> Primed | None:
        return self._ready.pop(0) if self._ready else None

    def close(self) -> None:
        for task in list(self._running):
            task.stop()
        self._running.clear()
        for primed in self._primed:   # taken or not: one taken and not used still waits
            primed.close()
        self._primed.clear()
        self._ready.clear()

    def __enter__(self) -> Forks:
        return self

    def __exit__(self, *exc) -> None:
        self.close()


def spare_core(prepare: Callable[[], object] | None = None, ready: int = 0) -> Executor:
    """The executor of a one-off command: a forked copy of the process on a second core where
    the machine has one and the process can fork, else :data:`SERIAL`. With ``prepare``,
    a copy is forked at once and runs it, ready for ``ready`` tasks (:class:`~.primed.Primed`:
    an import done on the idle core while the command starts up, for work it hands them after
    its solve)."""
    if (os.cpu_count() or 1) >= 2 and available():
        return Forks(2, prepare, ready)
    return SERIAL


class _InPool:
    """A task under way in a :class:`Pool`'s worker."""

    def __init__(self, owner: Pool, future, fn: Callable, args: tuple) -> None:
        self._owner, self._future, self._fn, self._args = owner, future, fn, args

    def result(self):
        from concurrent.futures.process import BrokenProcessPool

        try:
            return self._future.result()
        except BrokenProcessPool:   # a worker died (killed, out of memory)
            self._owner.broken = True
            return again_here(WorkerFailed("a worker process died"), self._fn, self._args)

    def done(self) -> bool:
        return self._future.done()


class Pool:
    """Tasks on ``workers`` spawned processes (:class:`~.pools.LocalPool`) for work that shares
    nothing with this process. Once a worker has died, the tasks still to come run here."""

    shares_memory = False

    def __init__(self, workers: int) -> None:
        self.workers = workers
        self.broken = False
        self._pool = LocalPool(workers)

    def submit(self, fn: Callable, /, *args) -> Task:
        if self.broken:
            return _Later(fn, args)
        return _InPool(self, self._pool.submit(fn, *args), fn, args)

    def map(self, fn: Callable, items: Iterable) -> list:
        return [t.result() for t in [self.submit(fn, x) for x in items]]

    def close(self) -> None:
        """End the workers at once, a task still running included (its result is not
        wanted)."""
        self._pool.stop()

    def ready(self) -> None:
        return None

    def __enter__(self) -> Pool:
        return self

    def __exit__(self, *exc) -> None:
        self.close()


class _OnCluster:
    """A task under way on a Dask cluster."""

    def __init__(self, future, fn: Callable, args: tuple) -> None:
        self._future, self._fn, self._args = future, fn, args

    def result(self):
        from distributed import KilledWorker

        try:
            return self._future.result()
        except KilledWorker as err:   # its workers died under it
            return again_here(WorkerFailed(f"a Dask worker died: {err}"), self._fn,
                               self._args)

    def done(self) -> bool:
        return self._future.done()


class Cluster:
    """Tasks on the workers of a Dask ``client``'s cluster (:func:`~.pools.connect`), as many
    at once as it has worker threads. The functions and their arguments travel by pickle;
    its workers need fegear installed. A task that raises raises the same where its result is
    read; one whose workers died is run here, or raised if workers are strict."""

    shares_memory = False

    def __init__(self, client) -> None:
        self.client = client
        self.workers = max(1, sum(client.nthreads().values()))

    def submit(self, fn: Callable, /, *args) -> Task:
        return _OnCluster(self.client.submit(fn, *args, pure=False), fn, args)

    def map(self, fn: Callable, items: Iterable) -> list:
        return [t.result() for t in [self.submit(fn, x) for x in items]]

    def close(self) -> None:
        """Close the client (the cluster itself is its owner's)."""
        self.client.close()

    def ready(self) -> None:
        return None

    def __enter__(self) -> Cluster:
        return self

    def __exit__(self, *exc) -> None:
        self.close()


def pool_or_serial(workers: int) -> Executor:
    """A :class:`Pool` of ``workers`` processes, or :data:`SERIAL` for one."""
    return Pool(workers) if workers > 1 else SERIAL


def in_fresh_process(fn: Callable, /, *args):
    """``fn(*args)`` in a process spawned for it alone, its return value: nothing of this
    process is carried over, so what the task measures of itself (its time after its imports,
    its peak memory) is its own. Raises :class:`~.forks.WorkerFailed` if the process died
    (strict or not: the task cannot run here instead)."""
    from concurrent.futures.process import BrokenProcessPool

    pool = LocalPool(1)
    try:
        return pool.submit(fn, *args).result()
    except BrokenProcessPool:
        raise WorkerFailed("the process spawned for the task died") from None
    finally:
        pool.stop()

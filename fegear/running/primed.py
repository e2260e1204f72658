"""A forked copy of this process made early and made ready (:class:`Primed`): it runs a
preparation at once, an import, and then waits for one task, whose function and arguments
come to it pickled. It is for work whose library costs more to import than its data costs
to send, started while this process still leaves a core idle: a command's start, before its
solve, when the solve's pictures will be drawn after it.

>>> from fegear.running import Primed
>>> with Primed(int) as ready:              # prepared by int(): 0
...     ready.submit(divmod, 7, 2).result()
(3, 1)
"""

from __future__ import annotations

import os
import pickle
from collections.abc import Callable

from .forks import Forked, WorkerFailed, again_here


class Primed:
    """A forked copy of this process that has run ``prepare()`` and waits for one task
    (:meth:`submit`); its answer comes back as a :class:`~.executors.Forks` task's does.
    :meth:`close` ends it, used or not."""

    def __init__(self, prepare: Callable[[], object]) -> None:
        receive, self._send = os.pipe()
        try:
            self._forked: Forked | None = Forked(lambda: _serve(prepare, receive))
        except BaseException:
            os.close(self._send)
            raise
        finally:
            os.close(receive)
        self._task: _InPrimed | None = None

    def submit(self, fn: Callable, /, *args) -> _InPrimed:
        """``fn(*args)`` sent to the copy: its only task."""
        if self._task is not None or self._forked is None:
            raise RuntimeError("a primed process takes one task")
        data = pickle.dumps((fn, args), protocol=5)
        try:
            os.write(self._send, len(data).to_bytes(8, "little"))
            view = memoryview(data)
            while view:
                view = view[os.write(self._send, view):]
        except OSError:   # the copy has died: its result says so
            pass
        self._task = _InPrimed(self, fn, args)
        return self._task

    def close(self) -> None:
        if self._send is not None:
            os.close(self._send)
            self._send = None
        if self._forked is not None:
            self._forked.stop()
            self._forked = None

    def __enter__(self) -> Primed:
        return self

    def __exit__(self, *exc) -> None:
        self.close()


class _InPrimed:
    """The task under way in a :class:`Primed` copy."""

    def __init__(self, owner: Primed, fn: Callable, args: tuple) -> None:
        self._owner, self._fn, self._args = owner, fn, args
        self._got: tuple | None = None

    def result(self):
        if self._got is None:
            forked = self._owner._forked
            try:
                if forked is None:
                    raise WorkerFailed("the primed process was closed before it answered")
                self._got = (forked.result(),)
            except WorkerFailed as err:
                self._got = (again_here(err, self._fn, self._args),)
            finally:
                self._owner.close()
        return self._got[0]

    def done(self) -> bool:
        return self._got is not None


def _serve(prepare: Callable[[], object], receive: int):
    """The copy's work: prepare, then read the task (its length, then its pickle; other
    copies forked meanwhile hold the pipe's other end too, so its end is no sign) and do
    it."""
    prepare()
    with os.fdopen(receive, "rb") as f:
        size = int.from_bytes(_exactly(f, 8), "little")
        fn, args = pickle.loads(_exactly(f, size))
    return fn(*args)


def _exactly(f, size: int) -> bytes:
    data = f.read(size)
    if len(data) != size:
        raise EOFError("the task was cut short: this process's parent closed it unsent")
    return data

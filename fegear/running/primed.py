"""A forked copy of this process made early and made ready (:class:`Primed`): it runs a
preparation at once, an import, and then waits for its tasks, whose functions and arguments
come to it pickled. It is for work whose library costs more to import than its data costs
to send, started while this process still leaves a core idle: a command's start, before its
solve, when the solve's pictures will be drawn after it. Several tasks share the one
preparation: each but the last runs in a copy of the prepared copy, forked as it arrives, so
the import is paid once and the tasks run side by side.

>>> from fegear.running import Primed
>>> with Primed(int) as ready:              # prepared by int(): 0
...     ready.submit(divmod, 7, 2).result()
(3, 1)
"""

from __future__ import annotations

import os
import pickle
import traceback
from collections.abc import Callable
from functools import partial

from .forks import Forked, WorkerFailed, again_here


class Primed:
    """A forked copy of this process that has run ``prepare()`` and waits for up to ``tasks``
    tasks (:meth:`submit`). It runs the last one itself and each one before it in a copy of
    itself forked as that task arrives (prepared, as it is). Each task's answer is read from
    its own :meth:`submit`'s result, as a :class:`~.executors.Forks` task's is; reading one
    tells the copy that no more will come, and waits for all it was sent. :meth:`close` ends
    it, used or not."""

    def __init__(self, prepare: Callable[[], object], tasks: int = 1) -> None:
        receive, self._send = os.pipe()
        try:
            self._forked: Forked | None = Forked(lambda: _serve(prepare, receive, tasks))
        except BaseException:
            os.close(self._send)
            raise
        finally:
            os.close(receive)
        self.tasks = tasks
        self._sent: list[_InPrimed] = []
        self._answers: list | WorkerFailed | None = None

    def submit(self, fn: Callable, /, *args) -> _InPrimed:
        """``fn(*args)`` sent to the copy: one of its ``tasks``."""
        if len(self._sent) >= self.tasks or self._forked is None or self._answers is not None:
            raise RuntimeError(f"a primed process takes {self.tasks} task"
                               f"{'s' if self.tasks > 1 else ''}, sent before any is read")
        self._write(pickle.dumps((fn, args), protocol=5))
        task = _InPrimed(self, len(self._sent), fn, args)
        self._sent.append(task)
        return task

    def _write(self, data: bytes) -> None:
        """``data`` to the copy, after its length (an empty one: no more tasks)."""
        try:
            os.write(self._send, len(data).to_bytes(8, "little"))
            view = memoryview(data)
            while view:
                view = view[os.write(self._send, view):]
        except OSError:   # the copy has died: its results say so
            pass

    def _answer(self, k: int) -> tuple[bool, object]:
        """Task ``k``'s ``(ok, value or why)``, once the copy has answered them all."""
        if self._answers is None:
            forked = self._forked
            try:
                if forked is None:
                    raise WorkerFailed("the primed process was closed before it answered")
                if len(self._sent) < self.tasks:
                    self._write(b"")
                self._answers = forked.result()
            except WorkerFailed as err:
                self._answers = err
            finally:
                self.close()
        if isinstance(self._answers, WorkerFailed):
            return False, self._answers
        return self._answers[k]

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
    """A task under way in a :class:`Primed` copy (the ``k``-th it was sent)."""

    def __init__(self, owner: Primed, k: int, fn: Callable, args: tuple) -> None:
        self._owner, self._k, self._fn, self._args = owner, k, fn, args
        self._got: tuple | None = None

    def result(self):
        if self._got is None:
            ok, value = self._owner._answer(self._k)
            if not ok:
                err = value if isinstance(value, WorkerFailed) else WorkerFailed(value)
                value = again_here(err, self._fn, self._args)
            self._got = (value,)
        return self._got[0]

    def done(self) -> bool:
        return self._got is not None


def _serve(prepare: Callable[[], object], receive: int, tasks: int) -> list:
    """The copy's work: prepare, then read up to ``tasks`` tasks (each its length, then its
    pickle; a length of 0 ends them early: other copies forked meanwhile hold the pipe's other
    end too, so its end is no sign), each but the last started in a copy of this one as it
    comes, the last done here. Every task's ``(ok, value or traceback)``, in order."""
    prepare()
    started: list[Forked | tuple] = []
    with os.fdopen(receive, "rb") as f:
        for k in range(tasks):
            size = int.from_bytes(_exactly(f, 8), "little")
            if size == 0:
                break
            fn, args = pickle.loads(_exactly(f, size))
            started.append(Forked(partial(fn, *args)) if k < tasks - 1 else _here(fn, args))
    return [_outcome(s) for s in started]


def _here(fn: Callable, args: tuple) -> tuple[bool, object]:
    try:
        return True, fn(*args)
    except Exception:   # noqa: BLE001  told to the parent with the others' answers
        return False, traceback.format_exc()


def _outcome(started: Forked | tuple) -> tuple[bool, object]:
    if isinstance(started, tuple):
        return started
    try:
        return True, started.result()
    except WorkerFailed as err:
        return False, str(err)


def _exactly(f, size: int) -> bytes:
    data = f.read(size)
    if len(data) != size:
        raise EOFError("the task was cut short: this process's parent closed it unsent")
    return data

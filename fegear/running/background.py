"""Work in a thread of this process beside its main thread (:func:`meanwhile`): what can run
while the main thread waits outside Python, as it does while gmsh meshes and a factorisation
runs, such as importing the library that the next stage draws with.

A fork made while such a thread still runs waits for it first (:func:`os.register_at_fork`):
a forked copy has only the thread that forked, so a module that another thread was importing
would stay locked in it for good, and the copy would hang on its first import of that module.

>>> from fegear.running import meanwhile
>>> task = meanwhile(sum, [1, 2, 3])
>>> task.result()
6
"""

from __future__ import annotations

import os
import threading
from collections.abc import Callable

#: the threads under way (started and not yet joined): a fork waits for them
_RUNNING: set[Background] = set()
_LOCK = threading.Lock()


class Background:
    """``fn(*args)`` running in a daemon thread of this process; :meth:`result` waits for it
    and returns its value or raises what it raised. Its failure is kept for :meth:`result`,
    never printed: a thread that prepares something (an import) fails again, with its own
    message, where the main thread does it itself."""

    def __init__(self, fn: Callable, args: tuple) -> None:
        self._fn, self._args = fn, args
        self._got: tuple | None = None
        self._thread = threading.Thread(target=self._run, name=getattr(fn, "__name__", "work"),
                                        daemon=True)
        with _LOCK:
            _RUNNING.add(self)
        self._thread.start()

    def _run(self) -> None:
        try:
            self._got = (True, self._fn(*self._args))
        except BaseException as exc:   # noqa: BLE001  kept for result()
            self._got = (False, exc)
        finally:
            with _LOCK:
                _RUNNING.discard(self)

    def done(self) -> bool:
        return self._got is not None

    def result(self):
        self._thread.join()
        ok, value = self._got
        if not ok:
            raise value
        return value


def meanwhile(fn: Callable, /, *args) -> Background:
    """``fn(*args)`` started in a thread of this process, beside its main thread
    (:class:`Background`)."""
    return Background(fn, args)


def _join_all() -> None:
    """Wait for every thread :func:`meanwhile` started (before a fork)."""
    with _LOCK:
        running = list(_RUNNING)
    for task in running:
        if task._thread is not threading.current_thread():
            task._thread.join()


if hasattr(os, "register_at_fork"):
    os.register_at_fork(before=_join_all)

"""Stage times of a computation: what a solve reports it spent where.

Library code marks its stages with :func:`timed` (``with timed("contact"): ...``); a caller
that wants the times opens a :func:`clocked` block and reads its :class:`Clock` after. A stage
inside another counts once, in its own stage only (forming unit responses while the contact is
assembled is "responses", not "assemble"), so the stages of one clock add up to the time spent
in them. With no clock open, :func:`timed` only runs its block.

>>> with clocked() as clock:
...     with timed("mesh"):
...         with timed("gmsh"):
...             pass
>>> sorted(clock.stages)
['gmsh', 'mesh']
>>> with timed("nobody counts"):   # no clock: nothing is counted
...     pass
"""

from __future__ import annotations

import time
from collections import Counter
from collections.abc import Iterator
from contextlib import contextmanager
from contextvars import ContextVar


class Clock:
    """The time (s) spent in each stage, a nested stage's taken out of the stage around it."""

    def __init__(self) -> None:
        self.stages: Counter = Counter()
        self._open: list[list] = []   # per stage under way: its name, start, nested time

    def _enter(self, stage: str) -> None:
        self._open.append([stage, time.perf_counter(), 0.0])

    def _leave(self) -> None:
        stage, start, nested = self._open.pop()
        spent = time.perf_counter() - start
        self.stages[stage] += spent - nested
        if self._open:
            self._open[-1][2] += spent

    def add(self, stages: dict[str, float]) -> None:
        """Count ``stages`` (s) as spent here too (another clock's, say)."""
        self.stages.update(stages)


_CLOCK: ContextVar[Clock | None] = ContextVar("fegear_clock", default=None)


@contextmanager
def clocked() -> Iterator[Clock]:
    """A clock for the stages timed inside the block (those of an enclosing clock do not see
    them)."""
    clock = Clock()
    token = _CLOCK.set(clock)
    try:
        yield clock
    finally:
        _CLOCK.reset(token)


@contextmanager
def timed(stage: str) -> Iterator[None]:
    """Count the block's time to ``stage`` on the clock in use (none: nothing counted)."""
    clock = _CLOCK.get()
    if clock is None:
        yield
        return
    clock._enter(stage)
    try:
        yield
    finally:
        clock._leave()


def note(stages: dict[str, float]) -> None:
    """Count ``stages`` (s; zero to show a stage that did not run) on the clock in use."""
    clock = _CLOCK.get()
    if clock is not None:
        clock.add(stages)


class Stopwatch:
    """The time (s) since it was made: ``watch.s``, for a span that is no stage (a command's
    wall time, a solve's own)."""

    def __init__(self) -> None:
        self._start = time.perf_counter()

    @property
    def s(self) -> float:
        return time.perf_counter() - self._start

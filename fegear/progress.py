"""Progress of a long computation: stages announced by the library, shown by the command line.

Library code never prints (docs/architecture.md); it calls :func:`stage` as each stage of a
solve starts, and :func:`plan` when it knows how many stages there will be. The command line
installs a sink with :func:`reporting` (a progress bar on stderr); with no sink installed both
calls do nothing, so a library user and a study worker see nothing.

>>> seen = []
>>> with reporting(lambda kind, value: seen.append((kind, value))):
...     plan(2)
...     stage("mesh")
...     stage("solve")
>>> seen
[('plan', 2), ('stage', 'mesh'), ('stage', 'solve')]
>>> stage("nobody listens")  # no sink: nothing happens
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from contextlib import contextmanager
from contextvars import ContextVar

#: a sink receives ("plan", number of stages) and ("stage", label)
Sink = Callable[[str, object], None]

_SINK: ContextVar[Sink | None] = ContextVar("fegear_progress", default=None)


@contextmanager
def reporting(sink: Sink) -> Iterator[None]:
    """Send the stages announced inside the ``with`` block to ``sink``."""
    token = _SINK.set(sink)
    try:
        yield
    finally:
        _SINK.reset(token)


def plan(stages: int) -> None:
    """Announce how many stages (calls of :func:`stage`) the computation will make."""
    sink = _SINK.get()
    if sink is not None:
        sink("plan", stages)


def stage(label: str) -> None:
    """Announce that the stage ``label`` starts (the one before it has ended)."""
    sink = _SINK.get()
    if sink is not None:
        sink("stage", label)

"""What the person at the terminal sees besides the results: the stages of a long command as a
progress bar on stderr, a stop by Ctrl-C or SIGTERM as one line, and the wall time of the
whole command.

The bar shows only on a terminal and not with ``--quiet``; it is cleared when the command ends,
so the results stand alone on the screen and nothing of it reaches a file or a pipe.
"""

from __future__ import annotations

import os
import signal
import sys
import time
from contextlib import contextmanager

from ..timing import Stopwatch


class StageBar:
    """A :mod:`fegear.progress` sink: on one line of stderr, the stage under way, its number
    of those planned, and the time so far (``[00:03 stage 2/5] model: …``)."""

    def __init__(self, enabled: bool) -> None:
        self.enabled = enabled
        self.total: int | None = None
        self.done = 0
        self.bar = None

    def __call__(self, kind: str, value: object) -> None:
        if not self.enabled:
            return
        if kind == "plan":
            self.total = self.done + int(value)
            return
        if self.bar is None:
            from tqdm import tqdm

            self.bar = tqdm(file=sys.stderr, leave=False, dynamic_ncols=True,
                            mininterval=0.2, bar_format="[{elapsed} stage {desc}")
        else:
            self.done += 1
        k = self.done + 1
        total = self.total if self.total is not None and self.total >= k else "?"
        self.bar.set_description_str(f"{k}/{total}] {value}")

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()
            self.bar = None


class Stopped(BaseException):
    """The command was stopped by a signal (SIGTERM, or SIGINT: Ctrl-C)."""

    def __init__(self, signum: int) -> None:
        self.signum = signum
        super().__init__(signal.Signals(signum).name)


@contextmanager
def stop_on_signals():
    """Within the block SIGTERM and SIGINT raise :class:`Stopped`, so that ``finally`` blocks
    run (temporary files removed, a directory made by this run taken away)."""
    def stop(signum, frame):
        raise Stopped(signum)

    old = {sig: signal.signal(sig, stop) for sig in (signal.SIGTERM, signal.SIGINT)}
    try:
        yield
    finally:
        for sig, handler in old.items():
            signal.signal(sig, handler)


def command_wall_s() -> float:
    """Seconds since this process started (the whole command, imports included): on Linux
    from the kernel's clock ticks (to 0.01 s; psutil's start time rounds the boot time to the
    second), elsewhere from psutil, and failing both since fegear was imported."""
    try:
        with open("/proc/self/stat") as f:
            after_name = f.read().rsplit(")", 1)[1].split()
        with open("/proc/uptime") as f:
            uptime = float(f.read().split()[0])
        return uptime - int(after_name[19]) / os.sysconf("SC_CLK_TCK")   # field 22: starttime
    except (OSError, ValueError, IndexError):
        pass
    try:
        import psutil

        return time.time() - psutil.Process().create_time()
    except Exception:  # no process table (a restricted container)
        return _IMPORTED.s


_IMPORTED = Stopwatch()

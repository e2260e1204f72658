"""One function run in a forked copy of this process (:class:`Forked`), which shares
everything built so far (a ring model's meshes and factors) without copying it: what
:class:`~.executors.Forks` runs its tasks on.

The answer comes back pickled into an anonymous in-memory file made before the fork (a pipe
only says when it is there: a large answer crosses a pipe, which holds 64 kB, only as fast as
the parent reads it), with its arrays' data beside the pickle (out of band), read in place
through a private mapping, not copied. The child touches none of the parent's streams or locks
(another thread of the parent, the progress bar's, may hold one at the fork): its output goes
nowhere and its progress is not reported. Only on Linux (no ``os.fork`` on Windows; on macOS
a fork after Apple's BLAS has run may crash, which is why multiprocessing spawns there).
"""

from __future__ import annotations

import logging
import os
import pickle
import signal
import sys
import threading
import traceback

from .. import progress
from ..errors import FegearError
from .pools import exit_with_parent

log = logging.getLogger(__name__)

#: the environment variable that makes a failed worker an error instead of a warning
STRICT = "FEGEAR_STRICT_WORKERS"


class WorkerFailed(FegearError):
    """Work given to another process failed there, or the process died."""


def strict() -> bool:
    """Whether a task that fails in a worker is an error (:data:`STRICT` set)."""
    return os.environ.get(STRICT, "") not in ("", "0")


def again_here(err: WorkerFailed, fn, args: tuple):
    """A task that failed in a worker: raised if workers are strict, else run here."""
    if strict():
        raise err
    log.warning("a task failed in a worker process (%s); it runs here instead",
                str(err).strip().splitlines()[-1])
    return fn(*args)


def available() -> bool:
    """Whether this process can fork a copy of itself to work in."""
    return sys.platform.startswith("linux") and hasattr(os, "fork")


class Forked:
    """``fn()`` started in a forked copy of this process (:func:`available` must hold);
    :meth:`result` is its return value, or raises :class:`WorkerFailed` with the child's
    traceback if it failed or died."""

    def __init__(self, fn) -> None:
        try:
            self._memory = os.memfd_create("fegear-forked", os.MFD_CLOEXEC)
        except (AttributeError, OSError):   # pragma: no cover - a kernel before 3.17
            self._memory = None
        r, w = os.pipe()
        try:
            pid = os.fork()
        except OSError as exc:
            os.close(r)
            os.close(w)
            self._close_memory()
            raise WorkerFailed(f"cannot fork a worker: {exc}") from None
        if pid == 0:
            os.close(r)
            _child(fn, w, self._memory)      # never returns
        os.close(w)
        self.pid, self._pipe = pid, os.fdopen(r, "rb")

    def result(self):
        """The child's return value, once it has ended."""
        if self._pipe is None:
            raise WorkerFailed("the worker was stopped before it answered")
        try:
            data = self._pipe.read()
            ok, value = _loaded(self._memory if data == _IN_MEMORY else data)
        finally:
            self.stop()
        if not ok:
            raise WorkerFailed(value)
        return value

    def stop(self) -> None:
        """End the child if it still runs, and let go of what it answered through."""
        if self.pid is not None:
            try:
                os.kill(self.pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
            try:
                os.waitpid(self.pid, 0)
            except ChildProcessError:
                pass
            self.pid = None
        if self._pipe is not None:
            self._pipe.close()
            self._pipe = None
        self._close_memory()

    def _close_memory(self) -> None:
        if self._memory is not None:
            os.close(self._memory)
            self._memory = None


#: what the pipe says when the answer is in the in-memory file
_IN_MEMORY = b"m"
ALIGN = 64   # bytes: an array read in place starts on a cache line


def _loaded(answer: bytes | int | None) -> tuple[bool, object]:
    """A child's ``(ok, value)``: from its pickle, or from the in-memory file that holds
    them (:func:`_written`), read in place; ``(False, why)`` if it was cut short."""
    import mmap

    try:
        if isinstance(answer, bytes):
            return pickle.loads(answer)
        # a private mapping: the arrays read from it may be written to (their pages are then
        # copied); it lasts as long as they do
        m = mmap.mmap(answer, os.fstat(answer).st_size, access=mmap.ACCESS_COPY)
        view = memoryview(m)
        head = int.from_bytes(view[:8], "little")
        at, buffers = 8 + head, []
        while at < len(view):
            size = int.from_bytes(view[at:at + 8], "little")
            at = _aligned(at + 8)
            buffers.append(view[at:at + size])
            at += size
        return pickle.loads(view[8:8 + head], buffers=buffers)
    except Exception as exc:   # cut short: the child died before writing all of it, or
        # what it wrote does not load here
        return False, ("the worker process died before it answered, or its answer does not "
                       f"load here ({type(exc).__name__}: {exc})")


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


def _aligned(at: int) -> int:
    return -(-at // ALIGN) * ALIGN


def _child(fn, fd: int, memory: int | None) -> None:
    """The forked child: Ctrl-C left to the parent, SIGTERM ending it, its output discarded;
    it ends with the parent, and writes (ok, value or traceback) into the in-memory file
    ``memory`` and then :data:`_IN_MEMORY` to ``fd`` (without that file, the pickle itself to
    ``fd``)."""
    import logging

    code = 1
    try:
        signal.signal(signal.SIGINT, signal.SIG_IGN)
        signal.signal(signal.SIGTERM, signal.SIG_DFL)
        # the log's handlers hold the parent's stderr, whose lock another thread may have
        # held at the fork
        logging.disable(logging.CRITICAL)
        sys.stdout = sys.stderr = open(os.devnull, "w")
        threading.Thread(target=exit_with_parent, args=(os.getppid(),), daemon=True).start()
        with progress.reporting(None):
            answer = (True, fn())
        code = 0
    except BaseException:   # noqa: BLE001  told to the parent, which decides
        answer = (False, traceback.format_exc())
    try:
        data = _answer(answer, memory)
    except BaseException:   # noqa: BLE001  a value that does not pickle
        data, code = pickle.dumps((False, traceback.format_exc())), 1
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
    finally:
        os._exit(code)


def _answer(answer: tuple, memory: int | None) -> bytes:
    """What the pipe carries: :data:`_IN_MEMORY` once ``answer`` is written into the in-memory
    file ``memory``, or (without one) its pickle."""
    if memory is None:
        return pickle.dumps(answer, protocol=pickle.HIGHEST_PROTOCOL)
    with os.fdopen(memory, "wb", closefd=False) as f:
        _written(f, answer)
    return _IN_MEMORY

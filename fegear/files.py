"""Writing results: atomic files (nothing half-written is ever left behind), CSV, JSON."""

from __future__ import annotations

import json
import os
import tempfile
from collections.abc import Callable, Iterable, Sequence
from pathlib import Path

import numpy as np

from .errors import FegearError


class OutputError(FegearError):
    """An output path cannot be created or written."""


def prepare_dir(path: str | os.PathLike) -> Path:
    """Prove ``path`` can be a writable directory (:func:`check_dir`), then create it (and
    its parents); raise :class:`OutputError`."""
    out = check_dir(path)
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise OutputError(f"--out {str(out)!r} cannot be created: {exc.strerror}") from None
    return out


def check_dir(path: str | os.PathLike) -> Path:
    """Check that ``path`` is, or can be made, a writable directory, and leave nothing behind:
    raise :class:`OutputError` if not. A command checks its ``--out`` with this before it
    computes, and makes the directory with :func:`prepare_dir` only when it has results to
    write. The check is proof, not permission bits (``os.access`` says yes to root on /proc
    and on a read-only mount): a probe directory is made and removed in ``path``, or in its
    nearest existing ancestor, where the directory would be made."""
    out = Path(path)
    base = out.absolute()
    while not base.exists() and base != base.parent:
        base = base.parent
    if not base.is_dir():
        what = "is a file, not a directory" if base == out.absolute() else (
            f"cannot be created: {str(base)!r} is a file, not a directory")
        raise OutputError(f"--out {str(out)!r} {what}")
    try:
        probe = tempfile.mkdtemp(prefix=".fegear-probe-", dir=base)
    except OSError as exc:
        where = "is not writable" if base == out.absolute() else (
            f"cannot be created in {str(base)!r}")
        raise OutputError(f"--out {str(out)!r} {where}: {exc.strerror or exc}") from None
    os.rmdir(probe)
    return out


def write_atomic(path: Path, writer: Callable[[Path], None]) -> Path:
    """Call ``writer(tmp)`` on a temporary file beside ``path``, then rename it into place
    with the permissions an ordinary file gets (the temporary file is private: 0600)."""
    path = Path(path)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=path.suffix, dir=path.parent)
    os.close(fd)
    try:
        writer(Path(tmp))
        os.chmod(tmp, 0o666 & ~_umask())
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return path


def _umask() -> int:
    mask = os.umask(0o022)  # reading the mask means setting it: put it back at once
    os.umask(mask)
    return mask


def write_points_csv(path: Path, points: np.ndarray, extra: dict | None = None) -> Path:
    """Write an (n, 2) point array as CSV with header ``x_mm,y_mm`` (full float precision),
    and the ``extra`` columns (name → (n,) values) after them."""
    extra = extra or {}
    table = np.column_stack([points, *extra.values()]) if extra else points

    def w(tmp: Path) -> None:
        np.savetxt(tmp, table, delimiter=",", header=",".join(["x_mm", "y_mm", *extra]),
                   comments="", fmt="%.17g")

    return write_atomic(path, w)


def write_csv(path: Path, header: Sequence[str], rows: Iterable[Sequence]) -> Path:
    """Write a table as CSV: floats at full precision (``repr``), anything else as ``str``; a
    cell with a comma, quote or line break (a refused design's reason) quoted."""
    import csv

    def cell(v) -> str:
        return repr(float(v)) if isinstance(v, (float, np.floating)) else str(v)

    def w(tmp: Path) -> None:
        with open(tmp, "w", newline="") as f:
            writer = csv.writer(f, lineterminator="\n")
            writer.writerow(header)
            writer.writerows([cell(v) for v in row] for row in rows)

    return write_atomic(path, w)


def write_json(path: Path, data: dict) -> Path:
    def w(tmp: Path) -> None:
        tmp.write_text(json.dumps(data, indent=2, allow_nan=False) + "\n")

    return write_atomic(path, w)

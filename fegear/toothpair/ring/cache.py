"""The model cache: the ring model's per-geometry work kept in files, for another process to
find: the two templates' meshes, stiffness, static modes and ring flexibilities, the unit-load
responses formed so far and the contact submodels' meshes (docs/model.md, "The model cache").

Reading an entry back is several times cheaper than building the model again: only the
factors are made again (they do not pickle: each template's interior is factorised anew).
What an entry costs and weighs: docs/model.md, "The model cache".

On where the environment variable :data:`ENV` says "on": ``fegear study`` and ``fegear
relief`` set it for themselves and their workers unless ``--no-cache``; ``fegear solve
--cache`` and the Python API's ``cache=True`` for one solve. An entry is named by the SHA-256
of the model's geometry key and fegear's code version (its source hash and the numerical
libraries' versions, :func:`~fegear.provenance.code_version`): an edit to the code that
computes results, or another library version, never reads an older entry. The directory
(:data:`ENV_DIR`, else ``$XDG_CACHE_HOME/fegear``, else ``~/.cache/fegear``) is held under
:data:`ENV_CAP` GB: the entries used least recently go first. ``fegear cache`` lists it and
``fegear cache --clear`` empties it.

Entries are Python pickles: read only what this user's fegear wrote there. One that does not
read is dropped and the model built again; one that cannot be written is left out with a
warning, never failing the solve.
"""

from __future__ import annotations

import contextlib
import hashlib
import logging
import os
import pickle
import tempfile
from pathlib import Path

from ...errors import FegearError

log = logging.getLogger(__name__)

ENV = "FEGEAR_CACHE"            # "on" or "off" (the default)
ENV_DIR = "FEGEAR_CACHE_DIR"    # the directory
ENV_CAP = "FEGEAR_CACHE_GB"     # its size cap, GB (default CAP_GB)
CAP_GB = 2.0
SUFFIX = ".ring"
FORMAT = 1                      # the layout of an entry's dictionary
ON = ("on", "1", "yes", "true")


def setting() -> bool | None:
    """What :data:`ENV` says: on (True), off (False) or nothing (None)."""
    text = os.environ.get(ENV, "").strip().lower()
    return None if not text else text in ON


def enabled() -> bool:
    """Whether ring models are read from and kept in the model cache in this process."""
    return bool(setting())


def use(on: bool) -> None:
    """Turn the model cache on or off for this process and the workers it spawns later (they
    inherit the environment)."""
    os.environ[ENV] = "on" if on else "off"


@contextlib.contextmanager
def model_cache(on: bool | None, folder: str | Path | None = None):
    """The cache on or off (None: as it was), in ``folder`` if given, within the block (for
    the workers spawned there too); both as they were after."""
    before = {k: os.environ.get(k) for k in (ENV, ENV_DIR)}
    if on is not None:
        use(on)
    if folder is not None:
        os.environ[ENV_DIR] = str(folder)
    try:
        yield
    finally:
        for k, v in before.items():
            if v is None:
                os.environ.pop(k, None)
            else:
                os.environ[k] = v


def directory() -> Path:
    """The cache's directory (not made here)."""
    if os.environ.get(ENV_DIR):
        return Path(os.environ[ENV_DIR]).expanduser()
    base = os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache"
    return Path(base) / "fegear"


def cap_bytes() -> int:
    """The size cap (bytes) from :data:`ENV_CAP`; a value that is no positive number is
    refused by name (:class:`~fegear.errors.FegearError`)."""
    text = os.environ.get(ENV_CAP)
    if text is None:
        return int(CAP_GB * 1e9)
    try:
        gb = float(text)
    except ValueError:
        gb = -1.0
    if not 0 < gb < float("inf"):
        raise FegearError(f"{ENV_CAP} = {text!r} is not admissible; admissible: a size cap "
                          "in GB above 0, e.g. 2")
    return int(gb * 1e9)


def entry(key: str) -> Path:
    """The file of ``key`` (a full description of what it holds, code version included)."""
    return directory() / (hashlib.sha256(key.encode()).hexdigest()[:32] + SUFFIX)


def load(key: str) -> dict | None:
    """The dictionary kept under ``key``, or None (none kept, or one that does not read: it
    is dropped). A hit counts as a use for the cap's order."""
    path = entry(key)
    try:
        f = open(path, "rb")
    except OSError:            # none kept, or no folder to keep one in
        return None
    with f:
        try:
            data = pickle.load(f)
        except Exception as err:   # a truncated or foreign file: drop it, build again
            log.warning("dropped unreadable cache entry %s (%s)", path, err)
            with contextlib.suppress(OSError):
                path.unlink(missing_ok=True)
            return None
    if not isinstance(data, dict) or data.get("format") != FORMAT or data.get("key") != key:
        return None
    try:
        os.utime(path)
    except OSError:
        pass
    log.info("read %s (%.0f MB)", path, path.stat().st_size / 1e6)
    return data


def keep(key: str, data: dict) -> None:
    """Write ``data`` under ``key`` (atomically: a reader sees the old entry or the new one,
    never half of one), then hold the directory under its cap. A failure to write is a
    warning, not an error: the result it would have sped up is already computed."""
    path, tmp = entry(key), None
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        fd, name = tempfile.mkstemp(prefix=path.name + ".", suffix=".tmp", dir=path.parent)
        tmp = Path(name)
        with os.fdopen(fd, "wb") as f:
            pickle.dump({**data, "format": FORMAT, "key": key}, f,
                        protocol=pickle.HIGHEST_PROTOCOL)
        os.replace(tmp, path)
    except OSError as err:
        log.warning("could not keep the model in the cache %s (%s)", path.parent, err)
        if tmp is not None:
            with contextlib.suppress(OSError):
                tmp.unlink(missing_ok=True)
        return
    log.info("kept %s (%.0f MB)", path, path.stat().st_size / 1e6)
    try:
        cap = cap_bytes()
    except FegearError as err:   # the commands refuse it before they start
        log.warning("%s; the cache is held under %g GB", err, CAP_GB)
        cap = int(CAP_GB * 1e9)
    evict(cap)


def entries() -> list[tuple[Path, int, float]]:
    """The cache's entries: (path, bytes, last use), least recently used first."""
    out = []
    folder = directory()
    if not folder.is_dir():
        return out
    for path in folder.glob("*" + SUFFIX):
        try:
            st = path.stat()
        except FileNotFoundError:   # evicted by another process meanwhile
            continue
        out.append((path, st.st_size, st.st_mtime))
    return sorted(out, key=lambda e: e[2])


def evict(cap: int) -> list[Path]:
    """Remove the least recently used entries until the rest fit in ``cap`` bytes; returns
    the removed paths."""
    rows = entries()
    total = sum(size for _, size, _ in rows)
    gone = []
    for path, size, _ in rows:
        if total <= cap:
            break
        path.unlink(missing_ok=True)
        total -= size
        gone.append(path)
    return gone


def clear() -> tuple[int, int]:
    """Remove every entry (and a writer's leftover temporary files); returns (entries,
    bytes) removed."""
    rows = entries()
    for path, _, _ in rows:
        path.unlink(missing_ok=True)
    folder = directory()
    if folder.is_dir():
        for tmp in folder.glob(f"*{SUFFIX}.*.tmp"):
            tmp.unlink(missing_ok=True)
    return len(rows), sum(size for _, size, _ in rows)

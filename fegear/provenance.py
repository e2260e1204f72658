"""What produced a result: fegear's version and source hash, and the library versions."""

from __future__ import annotations

import functools
import hashlib
from importlib import metadata
from pathlib import Path

from . import __version__

#: the libraries whose versions a result records (those that can change a number, and its files)
LIBRARIES = ("numpy", "scipy", "scikit-fem", "gmsh", "meshio", "pyvista", "matplotlib")


def library_versions(names=LIBRARIES) -> dict[str, str | None]:
    """Installed version of each library (None if it is not installed), read once a process
    (5 ms a time: a study's worker records them with every case)."""
    return dict(_versions(tuple(names)))


@functools.cache
def _versions(names: tuple[str, ...]) -> dict[str, str | None]:
    out = {}
    for name in names:
        try:
            out[name] = metadata.version(name)
        except metadata.PackageNotFoundError:
            out[name] = None
    return out


#: the stages that compute a solve's numbers and files, and the shared modules they use;
#: the others (cli, study, verify, drive) run, schedule, present or compare results, and
#: editing them keeps a study's finished cases valid
IN_RESULTS = ("geometry", "fe", "contact", "toothpair", "figures", "checks.py", "errors.py",
              "files.py", "planar.py", "quantities.py")


@functools.cache
def source_hash(root: Path | None = None) -> str:
    """SHA-256 (first 12 hex digits) of the source files that compute results
    (:data:`IN_RESULTS`, under ``root``, default: this fegear): it changes with any edit to
    them, installed or not, where the version number only changes on a release."""
    root = Path(__file__).parent if root is None else Path(root)
    h = hashlib.sha256()
    for part in IN_RESULTS:
        paths = [root / part] if part.endswith(".py") else sorted((root / part).rglob("*.py"))
        for path in paths:
            h.update(path.relative_to(root).as_posix().encode())
            h.update(path.read_bytes())
    return h.hexdigest()[:12]


@functools.cache
def code_version() -> str:
    """fegear's version and source hash plus the numerical libraries' versions, e.g.
    ``0.1.0+3f2a…; numpy 2.3.1; scipy 1.16.0; …``: two results with equal inputs and equal
    code versions are the same result."""
    libs = library_versions(("numpy", "scipy", "scikit-fem", "gmsh"))
    return "; ".join([f"{__version__}+{source_hash()}"] + [f"{k} {v}" for k, v in libs.items()])

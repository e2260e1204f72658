"""What produced a result: fegear's version and source hash, and the library versions."""

from __future__ import annotations

import functools
import hashlib
from importlib import metadata
from pathlib import Path

#: the libraries whose versions a result records (those that can change a number, and its files)
LIBRARIES = ("numpy", "scipy", "scikit-fem", "gmsh", "meshio", "pyvista", "matplotlib")


def library_versions(names=LIBRARIES) -> dict[str, str | None]:
    """Installed version of each library (None if it is not installed)."""
    out = {}
    for name in names:
        try:
            out[name] = metadata.version(name)
        except metadata.PackageNotFoundError:
            out[name] = None
    return out


#: modules that run, schedule, present or compare results but compute none of a solve's
#: numbers: editing them keeps a study's finished cases valid
NOT_IN_RESULTS = ("__main__", "cli", "bench", "bench_study", "peer", "peer_pair", "plot",
                  "study", "studyfile", "studyout")


@functools.cache
def source_hash() -> str:
    """SHA-256 (first 12 hex digits) of fegear's source files that compute results: it
    changes with any edit to them, installed or not, where the version number only changes
    on a release."""
    h = hashlib.sha256()
    root = Path(__file__).parent
    for path in sorted(root.glob("*.py")):
        if path.stem in NOT_IN_RESULTS:
            continue
        h.update(path.name.encode())
        h.update(path.read_bytes())
    return h.hexdigest()[:12]


@functools.cache
def code_version() -> str:
    """fegear's version and source hash plus the numerical libraries' versions, e.g.
    ``0.1.0+3f2a…; numpy 2.3.1; scipy 1.16.0; …``: two results with equal inputs and equal
    code versions are the same result."""
    from . import __version__

    libs = library_versions(("numpy", "scipy", "scikit-fem", "gmsh"))
    return "; ".join([f"{__version__}+{source_hash()}"] + [f"{k} {v}" for k, v in libs.items()])

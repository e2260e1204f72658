"""The libraries the FE stage imports where it first uses them, imported at once; and how
the process's memory allocator is set for a solve."""

from __future__ import annotations

import ctypes
import sys

#: glibc's mallopt parameters: M_TRIM_THRESHOLD, M_TOP_PAD, M_MMAP_THRESHOLD
_TRIM, _TOP_PAD, _MMAP = -1, -2, -3
#: what they are set to for a solve (bytes): freed memory is kept by the process for the next
#: array rather than handed back to the system, and arrays up to 32 MB (glibc's largest) come
#: from that kept memory rather than each from a fresh mapping
_KEPT = {_TRIM: 1 << 40, _TOP_PAD: 256 << 20, _MMAP: 32 << 20}
_set = False


def keep_freed_memory() -> None:
    """Let the allocator keep the memory a solve frees (glibc; elsewhere nothing changes).

    A solve allocates and frees the same large numpy temporaries over and over (scikit-fem's
    assembly: a few hundred arrays of 0.1-1 MB a template). By default glibc serves each from
    a fresh mapping, or hands the top of its heap back once 128 kB lie free, and every page is
    then faulted in again at its first touch: 0.08 s of the baseline's 0.38 s of template
    assembly and factorisation (docs/benchmark.md, "Freed memory kept"). Kept, the process's
    resident memory stays at its peak (which does not grow) until it ends. Once a process."""
    global _set
    if _set or not sys.platform.startswith("linux"):
        return
    _set = True
    try:
        mallopt = ctypes.CDLL(None).mallopt
    except (OSError, AttributeError):   # not glibc (musl has no mallopt)
        return
    for param, value in _KEPT.items():
        mallopt(ctypes.c_int(param), ctypes.c_int(min(value, 2**31 - 1)))


def import_libraries() -> None:
    """Import gmsh, scikit-fem, SciPy's sparse solvers and cholespy now, for timings that
    start after import (fegear bench); the allocator set as for a solve
    (:func:`keep_freed_memory`)."""
    keep_freed_memory()
    import scipy.sparse.linalg  # noqa: F401
    import scipy.spatial  # noqa: F401
    import skfem.models.elasticity  # noqa: F401

    from . import assembly, cyclic, mesh, probe, stress, submodel  # noqa: F401

    mesh.import_gmsh()
    try:
        import cholespy  # noqa: F401
    except ImportError:  # pragma: no cover - the wheel is a dependency
        pass

"""The libraries the FE stage imports where it first uses them, imported at once; and how
the process's memory allocator is set for a solve."""

from __future__ import annotations

import ctypes
import sys

#: glibc's mallopt parameter M_TOP_PAD, and what it is set to for a solve (bytes): the heap
#: grows, and is handed back, in steps this large
_TOP_PAD, _PAD = -2, 256 << 20
_set = False


def keep_freed_memory() -> None:
    """Let the allocator keep the memory a solve frees (glibc; elsewhere nothing changes).

    A solve allocates and frees the same numpy temporaries over and over; by default glibc
    grows its heap by what each asks for and hands the top back once 128 kB of it lie free,
    and every page handed back is faulted in again at its next use. With the heap grown and
    kept in 256 MB steps (M_TOP_PAD) a cycle of the baseline ran a few per cent faster, one
    position as fast; setting the trim and mmap thresholds as well gained nothing more. The
    process's resident memory stays near its peak until it ends. Once a process."""
    global _set
    if _set or not sys.platform.startswith("linux"):
        return
    _set = True
    try:
        mallopt = ctypes.CDLL(None).mallopt
    except (OSError, AttributeError):   # not glibc (musl has no mallopt)
        return
    mallopt(ctypes.c_int(_TOP_PAD), ctypes.c_int(_PAD))


def import_libraries() -> None:
    """Import gmsh, scikit-fem, SciPy's sparse solvers and cholespy now, for timings that
    start after import (fegear bench); the allocator set as for a solve
    (:func:`keep_freed_memory`)."""
    keep_freed_memory()
    import scipy.sparse.linalg  # noqa: F401
    import scipy.spatial  # noqa: F401
    import skfem.models.elasticity  # noqa: F401

    from . import assembly, cyclic, probe, stress, submodel  # noqa: F401  # lazy: heavy: scikit-fem
    from .mesh import import_gmsh  # lazy: heavy: scikit-fem, imported here when asked

    import_gmsh()
    try:
        import cholespy  # noqa: F401
    except ImportError:  # pragma: no cover - the wheel is a dependency
        pass

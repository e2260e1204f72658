"""The libraries the FE stage imports where it first uses them, imported at once."""

from __future__ import annotations


def import_libraries() -> None:
    """Import gmsh, scikit-fem, SciPy's sparse solvers and cholespy now, for timings that
    start after import (fegear bench)."""
    import scipy.sparse.linalg  # noqa: F401
    import scipy.spatial  # noqa: F401
    import skfem.models.elasticity  # noqa: F401

    from . import assembly, cyclic, mesh, probe, stress, submodel  # noqa: F401

    mesh.import_gmsh()
    try:
        import cholespy  # noqa: F401
    except ImportError:  # pragma: no cover - the wheel is a dependency
        pass

"""VTU files of FE fields: quadratic triangles with nodal displacement and stresses, written
atomically for ParaView."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..files import (
    write_atomic,
)


def vtu_fields(mesh, u: np.ndarray, stress, extra: dict[str, np.ndarray] | None = None) -> dict:
    """Point data for a quadratic-triangle VTU: displacement (mm, 3 components), stress
    components, σzz, von Mises, σ1 and σ2 (MPa), plus ``extra`` nodal fields."""
    n = mesh.doflocs.shape[1]
    disp = np.zeros((n, 3))
    disp[:, :2] = np.asarray(u).reshape(-1, 2)
    data = {"displacement": disp, "sxx": stress.sxx, "syy": stress.syy, "sxy": stress.sxy,
            "szz": stress.szz, "von_mises": stress.von_mises, "s1": stress.s1, "s2": stress.s2}
    for name, values in (extra or {}).items():
        data[name] = np.asarray(values, dtype=float)
    return data


def write_vtu(path: Path, mesh, point_data: dict[str, np.ndarray],
              xy: np.ndarray | None = None) -> Path:
    """Write a MeshTri2 with nodal fields as a ParaView-readable ``triangle6`` VTU (atomic).

    Node order: the mesh's corner nodes, then one midside node per facet; each cell lists its
    corners and then the midside nodes of edges 01, 12, 20 (VTK's quadratic triangle).
    ``xy`` (n, 2) replaces the node coordinates (e.g. a body placed in the fixed frame)."""
    import meshio

    points = np.zeros((mesh.doflocs.shape[1], 3))
    points[:, :2] = mesh.doflocs.T if xy is None else xy
    cells = [("triangle6", mesh.dofs.element_dofs.T.astype(np.int64))]
    out = meshio.Mesh(points, cells, point_data=point_data)

    def w(tmp: Path) -> None:
        meshio.write(tmp, out, file_format="vtu", binary=True)

    return write_atomic(path, w)

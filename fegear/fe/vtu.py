"""VTU files of FE fields: quadratic triangles with nodal displacement and stresses, written
atomically for ParaView."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..files import (
    write_atomic,
)


def vtu_fields(u: np.ndarray, stress, extra: dict[str, np.ndarray] | None = None) -> dict:
    """Point data for a quadratic-triangle VTU: displacement (mm, 3 components), stress
    components, σzz, von Mises, σ1 and σ2 (MPa), plus ``extra`` nodal fields."""
    n = len(stress.sxx)
    disp = np.zeros((n, 3))
    disp[:, :2] = np.asarray(u).reshape(-1, 2)
    data = {"displacement": disp, "sxx": stress.sxx, "syy": stress.syy, "sxy": stress.sxy,
            "szz": stress.szz, "von_mises": stress.von_mises, "s1": stress.s1, "s2": stress.s2}
    for name, values in (extra or {}).items():
        data[name] = np.asarray(values, dtype=float)
    return data


def write_vtu(path: Path, points: np.ndarray, cells: np.ndarray,
              point_data: dict[str, np.ndarray]) -> Path:
    """Write quadratic triangles with nodal fields as a ParaView-readable ``triangle6`` VTU
    (atomic): ``points`` (n, 2, mm), ``cells`` (m, 6) listing each triangle's corners and then
    the midside nodes of edges 01, 12, 20 (scikit-fem's ``element_dofs`` order, VTK's too)."""
    import meshio

    xyz = np.zeros((len(points), 3))
    xyz[:, :2] = points
    out = meshio.Mesh(xyz, [("triangle6", np.asarray(cells, dtype=np.int64))],
                      point_data=point_data)

    def w(tmp: Path) -> None:
        meshio.write(tmp, out, file_format="vtu", binary=True)

    return write_atomic(path, w)

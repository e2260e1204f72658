"""VTU files of FE fields: quadratic triangles with nodal displacement and stresses, written
atomically for ParaView, their field names carrying their units (``von_mises_MPa``,
``displacement_mm``) as ParaView shows them."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..files import write_atomic

#: the written name of each field: its name in memory and its unit
UNITS = {"displacement": "mm", "sxx": "MPa", "syy": "MPa", "sxy": "MPa", "szz": "MPa",
         "von_mises": "MPa", "s1": "MPa", "s2": "MPa", "contact_pressure": "MPa"}


def written_name(name: str) -> str:
    """The field's name in a VTU file: ``name_unit`` (``von_mises`` → ``von_mises_MPa``); a
    field without a unit in :data:`UNITS` keeps its name."""
    return f"{name}_{UNITS[name]}" if name in UNITS else name


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
    the midside nodes of edges 01, 12, 20 (scikit-fem's ``element_dofs`` order, VTK's too).
    The fields are written under :func:`written_name`."""
    import meshio

    xyz = np.zeros((len(points), 3))
    xyz[:, :2] = points
    out = meshio.Mesh(xyz, [("triangle6", np.asarray(cells, dtype=np.int64))],
                      point_data={written_name(k): v for k, v in point_data.items()})

    def w(tmp: Path) -> None:
        meshio.write(tmp, out, file_format="vtu", binary=True)

    return write_atomic(path, w)

"""VTU files of FE fields: quadratic triangles with nodal displacement and stresses, written
atomically for ParaView, their field names carrying their units (``von_mises_MPa``,
``displacement_mm``) as ParaView shows them, in the type the arrays have (a solve's fields:
:data:`FIELD_DTYPE`)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..files import write_atomic

#: the type of the fields a solve draws and writes (the whole gears, the contact submodels):
#: seven significant digits, more than a picture or ParaView shows (4 nm on a point 60 mm from
#: the centre, 0.0001 MPa on 1000 MPa); the results' numbers are in summary.json at full
#: precision. Half the memory and half the files of float64
FIELD_DTYPE = np.float32

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
    (atomic): ``points`` (n, 2, mm), ``cells`` (m, 6, integers) listing each triangle's
    corners and then the midside nodes of edges 01, 12, 20 (scikit-fem's ``element_dofs``
    order, VTK's too). The fields are written under :func:`written_name`; every array in its
    own type, little-endian.

    VTK's XML with its arrays appended raw, uncompressed (meshio and ParaView read it). meshio
    writes them zlib-compressed and base64-encoded: 1.35 s of compression on one core for the
    baseline's four files, most of writing a solve's files, for files 22 % smaller than raw."""
    xyz = np.zeros((len(points), 3), dtype=_little(points).dtype)
    xyz[:, :2] = points
    cells = np.ascontiguousarray(_little(cells))
    arrays = [("Points", None, xyz),
              ("Cells", "connectivity", cells.ravel()),
              ("Cells", "offsets", np.arange(1, len(cells) + 1, dtype=cells.dtype) * 6),
              ("Cells", "types", np.full(len(cells), _VTK_QUADRATIC_TRIANGLE, dtype=np.uint8))]
    arrays += [("PointData", written_name(k), _little(v)) for k, v in point_data.items()]
    head = ['<?xml version="1.0"?>\n<VTKFile type="UnstructuredGrid" version="1.0" '
            'byte_order="LittleEndian" header_type="UInt64">\n<UnstructuredGrid>\n'
            f'<Piece NumberOfPoints="{len(xyz)}" NumberOfCells="{len(cells)}">\n']
    section, offset, blobs = None, 0, []
    for where, name, a in arrays:
        if where != section:
            head.append((f"</{section}>\n" if section else "") + f"<{where}>\n")
            section = where
        named = f' Name="{name}"' if name else ""
        # scalars without NumberOfComponents: meshio reads them back as (n,), not (n, 1)
        components = f' NumberOfComponents="{a.shape[1]}"' if a.ndim == 2 else ""
        head.append(f'<DataArray type="{_VTK_TYPES[a.dtype.str[1:]]}"{named}{components} '
                    f'format="appended" offset="{offset}"/>\n')
        data = np.ascontiguousarray(a)
        blobs += [np.uint64(data.nbytes).tobytes(), data]
        offset += 8 + data.nbytes
    head.append(f'</{section}>\n</Piece>\n</UnstructuredGrid>\n'
                '<AppendedData encoding="raw">\n_')
    tail = "\n</AppendedData>\n</VTKFile>\n"

    def w(tmp: Path) -> None:
        with open(tmp, "wb") as f:
            f.write("".join(head).encode("ascii"))
            for blob in blobs:     # an array's own memory, not a copy of it
                f.write(memoryview(blob).cast("B"))
            f.write(tail.encode("ascii"))

    return write_atomic(path, w)


def _little(a) -> np.ndarray:
    """``a`` as a little-endian array of its own type (itself where it is one already)."""
    a = np.asarray(a)
    return a.astype(a.dtype.newbyteorder("<"), copy=False)


_VTK_QUADRATIC_TRIANGLE = 22
_VTK_TYPES = {"f8": "Float64", "f4": "Float32", "i8": "Int64", "i4": "Int32", "u1": "UInt8"}

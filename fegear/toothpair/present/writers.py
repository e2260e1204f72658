"""What the analyses' writers share: a series of positions for ParaView
(:func:`write_cycle_series`: a cycle's, a revolution's frame a pitch) and a summary entry's
rows as a CSV table (:func:`write_rows`: the sensitivities', the rating's)."""

from __future__ import annotations

import math
from pathlib import Path
from xml.sax.saxutils import quoteattr

from ...fe import write_vtu
from ...files import write_atomic, write_csv

#: sectors written either side of the loaded ones at each position of a cycle's series
SERIES_AROUND = 1


def write_cycle_series(sols, out: Path, name: str = "cycle") -> dict[str, Path]:
    """A time series over the rolling angle for ParaView: per position both gears' loaded
    sectors (and :data:`SERIES_AROUND` either side) as <name>/gear1_000.vtu, …, and
    <name>.pvd, the collection that lists them with β in degrees as their time."""
    folder = out / name
    folder.mkdir(exist_ok=True)
    entries = []
    for k, sol in enumerate(sols):
        beta = math.degrees(sol.case.beta)
        for part, b in enumerate(sol.detail.body_fields(around=SERIES_AROUND)):
            file = f"{b.name}_{k:03d}.vtu"
            write_vtu(folder / file, b.points, b.cells, b.data)
            entries.append(f'    <DataSet timestep="{beta:.9g}" part="{part}" '
                           f'name={quoteattr(b.name)} file={quoteattr(f"{name}/{file}")}/>')
    xml = "\n".join(['<?xml version="1.0"?>',
                     '<VTKFile type="Collection" version="0.1" byte_order="LittleEndian">',
                     "  <Collection>", *entries, "  </Collection>", "</VTKFile>", ""])
    return {"pvd": write_atomic(out / f"{name}.pvd", lambda tmp: tmp.write_text(xml))}


def write_rows(path: Path, rows: list[dict]) -> Path:
    """``rows`` (a summary entry's: the sensitivities', the rating's) as a CSV table, a
    column a key in the order they first come, a key a row lacks (or holds None) blank."""
    cols = list(dict.fromkeys(k for r in rows for k in r))
    return write_csv(path, cols, (["" if r.get(c) is None else r[c] for c in cols]
                                  for r in rows))

"""Results of the tooth-pair solve: JSON summary, table, VTU files and the von Mises picture.

Files are written in the fixed frame (gear 2 centred at the origin, gear 1 at (0, e), both at
the solved rolling angle), so the two VTUs overlay in ParaView. Stress components are rotated
into that frame; invariants (von Mises, σ1, σ2) need no rotation.
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path
from xml.sax.saxutils import quoteattr

from ..fe import write_vtu
from ..figures import write_png
from ..files import write_atomic, write_csv, write_json
from ..running import SERIAL, Executor
from .case import PairSolution
from .pictured import PicturedDetail, for_pictures
from .plot import chart_pngs, von_mises_bytes

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


def write_pair_outputs(sol: PairSolution, out: Path, summary: dict, fields: bool = True,
                       pictures: bool = True, executor: Executor = SERIAL) -> dict[str, Path]:
    """gear1.vtu, gear2.vtu and the ring model's contact submodels (gear1_contact.vtu, …;
    fixed frame; ``fields``), von_mises.png, flank_pressure.png and root_stress.png
    (``pictures``) and summary.json in ``out``.

    Where ``executor`` holds processes made ready to draw (a one-off command's:
    :func:`~fegear.running.spare_core` with :func:`~.plot.prepare_pictures`, which imported
    matplotlib while the command started up), the charts go to one at once and von Mises,
    from the part of the fields it shows (:func:`~.pictured.for_pictures`), to the other as soon
    as the fields are formed, while this process writes the VTUs; else every picture is
    drawn here. They come back as bytes, the same either way, and every file is written
    here, atomically."""
    files = {}
    painters = [executor.ready(), executor.ready()] if pictures else []
    charts = _drawn(painters[0] if painters else None, chart_pngs, sol, summary) \
        if pictures else None
    bodies = sol.detail.body_fields() if fields or pictures else ()
    peaks = sol.detail.peak_fields() if fields or pictures else ()
    if pictures:
        shown = for_pictures(sol, bodies, peaks)
        von_mises = _drawn(painters[1], von_mises_bytes, shown.sol, summary, shown.bodies,
                           shown.peaks, shown.spots)
    if fields:
        for b in (*bodies, *peaks):
            files[b.name] = write_vtu(out / f"{b.name}.vtu", b.points, b.cells, b.data)
    if pictures:
        files["png"] = write_png(out / "von_mises.png", von_mises.result())
        drawn = charts.result()
        for key, name in (("flank_png", "flank_pressure.png"), ("root_png", "root_stress.png")):
            if name in drawn:
                files[key] = write_png(out / name, drawn[name])
    summary = {**summary, "files": {**summary.get("files", {}),
                                    **{k: str(v) for k, v in files.items()}}}
    files["summary"] = write_json(out / "summary.json", summary)
    return files


def _drawn(painter, fn, sol: PairSolution, *args):
    """``fn(sol, *args)`` handed to ``painter`` (a :class:`~fegear.running.Primed`) with the
    solution made light to send (:class:`~.pictured.PicturedDetail`), or here where there is
    none; a task either way."""
    if painter is None:
        return SERIAL.submit(fn, sol, *args)
    light = sol if isinstance(sol.detail, PicturedDetail) else \
        dataclasses.replace(sol, detail=PicturedDetail(sol.detail))
    return painter.submit(fn, light, *args)

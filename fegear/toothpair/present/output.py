"""A solved job's files (:func:`write_job`): each analysis's the summary holds, through the
registry (:mod:`..analyses`), then the pair's own: summary.json, the VTU fields and the
pictures of the pictured position (:func:`write_pair_outputs`); and :func:`run_job`, a job
solved (:func:`~..job.solve_job`) and its files written, what ``fegear solve`` and a study
case call.

Files are written in the fixed frame (gear 2 centred at the origin, gear 1 at (0, e), both at
the solved rolling angle), so the two VTUs overlay in ParaView. Stress components are rotated
into that frame; invariants (von Mises, σ1, σ2) need no rotation.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from ... import progress
from ...fe import write_vtu
from ...figures import write_png
from ...files import prepare_dir, write_json
from ...running import SERIAL, Executor, Task
from ..analyses import Writing, shown
from ..case import PairSolution
from ..job import Job, Solved, solve_job
from .html_report import write_report
from .pictured import PICTURED_AROUND, ToDraw, for_pictures, light, same_drawing
from .plot import chart_pngs, von_mises_bytes


@dataclass(frozen=True)
class Drawing:
    """Where a pair's pictures are drawn: on ``executor``'s processes made ready to draw
    (else here), the charts' task ``charts`` where they were handed out already
    (:func:`run_job`: while the submodels were solved)."""

    executor: Executor = SERIAL
    charts: Task | None = None


def write_pair_outputs(sol: PairSolution, out: Path, summary: dict, fields: bool = True,
                       pictures: bool = True, drawing: Drawing = Drawing()) -> dict[str, Path]:
    """gear1.vtu, gear2.vtu and the ring model's contact submodels (gear1_contact.vtu, …;
    fixed frame; ``fields``), von_mises.png, flank_pressure.png and root_stress.png
    (``pictures``) and summary.json in ``out``.

    Where ``drawing``'s executor holds a process made ready to draw (a one-off command's:
    :func:`~fegear.running.spare_core` with :func:`~.plot.prepare_pictures`, which imported
    matplotlib while the command started up), the charts go to it at once (drawn in a copy of
    it), and von Mises as soon as the loaded sectors' fields are formed (:data:`PICTURED_AROUND`: a
    tenth of the whole gears'), while this process forms the whole fields and writes the
    VTUs; else every picture is drawn here. The whole fields then confirm that the picture
    had every cell it shows (:func:`~.pictured.for_pictures` of both is the same); where it
    had not, von Mises is drawn again here from the whole fields. The pictures come back as
    bytes, the same either way, and every file is written here, atomically."""
    files = {}
    executor, charts = drawing.executor, drawing.charts
    # the solution as the pictures read it, formed once for both of them
    drawn_sol = light(sol) if pictures else sol
    if pictures and charts is None:
        charts = _drawn(executor.ready(), chart_pngs, drawn_sol, summary)
    peaks = sol.detail.peak_fields() if fields or pictures else ()
    if pictures:
        near = for_pictures(drawn_sol, sol.detail.body_fields(around=PICTURED_AROUND), peaks)
        von_mises = _drawn(executor.ready(), von_mises_bytes, *_drawing(near, summary))
    bodies = sol.detail.body_fields() if fields or pictures else ()
    if fields:
        for b in (*bodies, *peaks):
            files[b.name] = write_vtu(out / f"{b.name}.vtu", b.points, b.cells, b.data)
    if pictures:
        whole = for_pictures(drawn_sol, bodies, peaks)
        if not same_drawing(near, whole):
            von_mises = SERIAL.submit(von_mises_bytes, *_drawing(whole, summary))
        files["png"] = write_png(out / "von_mises.png", von_mises.result())
        drawn = charts.result()
        for key, name in (("flank_png", "flank_pressure.png"), ("root_png", "root_stress.png")):
            if name in drawn:
                files[key] = write_png(out / name, drawn[name])
    summary = {**summary, "files": {**summary.get("files", {}),
                                    **{k: str(v) for k, v in files.items()}}}
    files["summary"] = write_json(out / "summary.json", summary)
    return files


def _drawing(shown: ToDraw, summary: dict) -> tuple:
    """The arguments of :func:`~.plot.von_mises_bytes` for ``shown``."""
    return shown.sol, summary, shown.bodies, shown.peaks, shown.spots


def _drawn(painter, fn, *args):
    """``fn(*args)`` handed to ``painter`` (a :class:`~fegear.running.Primed`), or here where
    there is none; a task either way."""
    return (SERIAL if painter is None else painter).submit(fn, *args)


@dataclass(frozen=True)
class JobResult:
    """What a solve produced: the JSON summary (``fegear solve --json``), the files written
    (name → path), the cycle rows (``--positions``; else None) and the time of the solve
    itself (s, without writing files)."""

    summary: dict
    files: dict[str, Path]
    rows: list[dict] | None
    solve_s: float


def run_job(job: Job, out: Path | None, fields: bool = True, pictures: bool = True,
            executor: Executor = SERIAL, report: str | None = None) -> JobResult:
    """Solve ``job`` (on ``executor``: :func:`solve_job`); write summary.json, and the VTUs
    (``fields``) and pictures (``pictures``) into ``out`` unless it is None, and with
    ``report`` (the command that gives the numbers again) report.html
    (:mod:`.html_report`). ``out`` is made only after the solve, so a solve that fails
    leaves nothing behind."""
    progress.plan(2 + len(job.betas) + job.estimate + (out is not None))
    charts: list[Task] = []

    def meanwhile(sol: PairSolution, summary: dict) -> None:
        # the charts read no field and no submodel: handed out while the submodels are solved
        charts.append(_drawn(executor.ready(), chart_pngs, light(sol), summary))

    solved = solve_job(job, executor, meanwhile if out is not None and pictures else None)
    files = {} if out is None else write_job(solved, out, fields, pictures, executor,
                                             charts[0] if charts else None)
    if report is not None and out is not None:
        files["report"] = write_report(solved.summary, files, out, report)
    return JobResult(solved.summary, files, solved.rows, solved.solve_s)


def write_job(solved: Solved, out: Path, fields: bool = True, pictures: bool = True,
              executor: Executor = SERIAL, charts: Task | None = None) -> dict[str, Path]:
    """Write a solved job's files into ``out`` (made here): each analysis's that the summary
    holds (:mod:`.analyses`: a cycle's table, PVD series and plot, a revolution's, …), then
    summary.json, the VTUs (``fields``) and the pictures (``pictures``) of the pictured
    position, those that need no fields drawn on ``executor`` meanwhile
    (:func:`write_pair_outputs`; ``charts``: their task where they were handed out already).
    Returns name → path.

    The fields are formed with BLAS on one thread, as the solve's are: the pictures are drawn
    on the other core meanwhile, and a second BLAS thread there only spins against them
    (docs/benchmark.md, the files' sixth pass)."""
    from ...fe import blas_threads  # lazy: heavy: scipy (a refused input imports none)

    progress.stage(f"writing files to {out}")
    out = prepare_dir(out)
    summary = solved.summary
    writing = Writing(solved, out, pictures_title(solved), fields, pictures)
    files: dict[str, Path] = {}
    with blas_threads():
        for analysis in shown(summary):
            files.update(analysis.write(summary[analysis.key], writing))
        files.update(write_pair_outputs(solved.solution, out, {**summary, "files": {
            k: str(v) for k, v in files.items()}}, fields, pictures, Drawing(executor, charts)))
    return files


def pictures_title(solved: Solved) -> str:
    """The pictures' title: the design, the torque, the positions and the quality; a class's
    pairs over a revolution on a line of their own (one line would be wider than a narrow
    picture)."""
    i = solved.summary["inputs"]
    n = len(solved.solutions)
    design = f"m {i['m']:g}, h1 {i['h1']:g}, f1 {i['f1']:g}, T {i['torque_Nm']:g} N·m"
    if solved.job.revolution and "revolution" not in solved.summary:   # a class's pairs
        screened = solved.summary.get("samples", {}).get("positions_solved_per_pair")
        return (f"{design}, quality {i['quality']}\n{n} positions a pitch over a revolution "
                f"({len(solved.job.betas)}"
                + (f"; screened: {screened:.0f} a pair solved)" if screened else ")"))
    return f"{design}, {n} position{'s' if n > 1 else ''}, quality {i['quality']}"

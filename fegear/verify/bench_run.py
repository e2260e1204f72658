"""One ``fegear bench``: which benchmarks run and in what order, the report they make and the
files they leave (bench.json, bench.png, bench_scaling.png, the history).

The command line checks its options into a :class:`BenchPlan`; :func:`run_bench` runs it and
hands each block of the report to ``say`` as soon as it is measured (a bench takes minutes;
the command prints each block). The benchmarks are taken from this stage's face when they
run, as the command took them, so a test can stand in for any of them there.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace
from pathlib import Path
from typing import TYPE_CHECKING

from .. import verify
from ..errors import ParameterError
from ..files import prepare_dir, write_json
from ..provenance import code_version
from ..toothpair import SolveCase
from . import bench, history
from .ccx_files import PeerError
from .pair_targets import PEER_KEYS, PairRuns, pair_targets, sector_error
from .peer_contact import CASES, LEVELS, contact_peer, peer_table
from .ring_bench import (
    SINGLE_TARGET,
    class_run,
    face_run,
    revolution_run,
    search_run,
    spectrum_run,
)
from .sector import cross_check, cross_table

if TYPE_CHECKING:
    from ..geometry import PairParameters
    from .bench import FilesRun, Ladder

#: what a bench can run alone instead of everything ("": everything)
ONLY = ("", "study", "contact-peer", "sector", "files")

Say = Callable[[str], None]

#: the files' cost's name in the history (:func:`~.bench.files_run`)
FILES_METRIC = "`fegear solve --out`, the files over the solve [s]"


@dataclass(frozen=True)
class BenchPlan:
    """What one ``fegear bench`` runs, its options checked by the command line.

    ``params`` and ``torque`` (N·m): the pair and its load; ``quality``: the level of the
    estimate, cycle, model-cache and scaling runs; ``pair_args``: the pair's options as given,
    for the whole ``fegear solve`` commands the model cache's runs time; ``repeat``: repetitions
    of the in-process runs (the best kept); ``cycle``: positions of the timed mesh cycle (0:
    none); ``disk_levels``: the Hertz case's elements across b; ``pair_levels`` and
    ``sector_levels``: the ring and sector models' quality levels (no sector levels: no sector
    ladder; with ``only="contact-peer"`` none means the comparison's own); ``scaling``: teeth
    of gear 2 for the cost-growth runs (none: skipped); ``study_cases``: solves of the study
    runner's benchmark (0: skipped); ``peer``: CalculiX beside the ladders; ``paper_study``:
    also time studies/paper_trends.toml; ``tolerance_class``: also time a tolerance class's
    samples over the cycle (:func:`~.ring_bench.class_run`); ``spectrum``: also time a 4-level
    load spectrum over the cycle against the cycle (:func:`~.ring_bench.spectrum_run`);
    ``face``: also time one position and a cycle across the face against the 2D pair
    (:func:`~.ring_bench.face_run`); ``revolution``: also time whole revolutions, one deviated
    pair's and 200 pairs', against one position (:func:`~.ring_bench.revolution_run`);
    ``search``: also time the design search over a turn (:func:`~.ring_bench.search_run`);
    ``files``: pairs of whole ``fegear solve`` commands without and with ``--out`` that time
    the files' cost (:func:`~.bench.files_run`; 0: none); ``only``: one of :data:`ONLY`;
    ``out``: the directory (checked, made when there is something to write); ``history``: the
    file this run is appended to and compared with (None: :data:`~.history.HISTORY` in
    ``out``)."""

    params: PairParameters
    torque: float
    out: Path
    quality: str
    repeat: int
    cycle: int
    disk_levels: tuple[float, ...]
    pair_levels: tuple[str, ...]
    sector_levels: tuple[str, ...]
    scaling: tuple[int, ...]
    study_cases: int
    pair_args: tuple[str, ...] = ()
    peer: bool = True
    paper_study: bool = False
    tolerance_class: bool = False
    spectrum: bool = False
    face: bool = False
    revolution: bool = False
    search: bool = False
    files: int = 0
    only: str = ""
    history: Path | None = None

    def __post_init__(self) -> None:
        if self.only not in ONLY:
            raise ParameterError("only", self.only, " / ".join(map(repr, ONLY)))


def run_bench(plan: BenchPlan, say: Say) -> None:
    """Run ``plan``, handing the report to ``say`` a block at a time."""
    if plan.only == "study":
        study_bench(plan, say)
    elif plan.only == "contact-peer":
        contact_peer_bench(plan, say)
    elif plan.only == "sector":
        sector_check(plan, say)
    elif plan.only == "files":
        files_bench(plan, say)
    else:
        _everything(plan, say)


def _everything(plan: BenchPlan, say: Say) -> None:
    """Every benchmark of ``plan``, in the report's order (the command without a mode)."""
    prepare_dir(plan.out)
    say(verify.geometry_bench(plan.params, plan.repeat))
    say("")
    disks = _disk_ladder(plan, say)
    say("")
    runs = _ring_runs(plan, say)
    sector = _sector_ladder(plan, say)
    scale = _scaling(plan, runs.ring, say)
    runs = replace(runs, sector=sector,
                   study=verify.paper_study_s() if plan.paper_study else None,
                   tolerance=class_run(plan.pair_args) if plan.tolerance_class else None,
                   spectrum=spectrum_run(plan.pair_args) if plan.spectrum else None,
                   face=face_run(plan.pair_args) if plan.face else None,
                   revolution=revolution_run(plan.pair_args) if plan.revolution else None,
                   search=search_run() if plan.search else None)
    files = None
    if plan.files:
        say("")
        files = files_bench(plan, say)
    _report(plan, disks, runs, scale, say, files)
    if plan.study_cases:
        say("")
        study_bench(plan, say)


def _disk_ladder(plan: BenchPlan, say: Say) -> Ladder:
    """The Hertz case's ladder, its table and its target."""
    disks = verify.disk_ladder(plan.disk_levels, plan.repeat, peer=plan.peer)
    say(verify.ladder_table(disks))
    say("")
    for t in verify.ladder_targets(disks):
        say(f"* {t.line()}")
    return disks


def _ring_runs(plan: BenchPlan, say: Say) -> PairRuns:
    """The ring model's ladder, one position at the default quality (from the ladder if it is
    on it), with the estimate, over a mesh cycle and with the model cache, each in a fresh
    process; their tables."""
    params, torque, quality = plan.params, plan.torque, plan.quality
    say(f"### Tooth pair, ring model: {params.describe()}, T {torque:g} N·m, one position, "
        "each level in a fresh process")
    say("")
    ring = verify.ring_ladder(params, torque, list(plan.pair_levels))
    say(verify.ring_table(ring))
    default = next((r for r in ring if r.label == quality), None)
    if default is None:
        default = verify.run_fresh(quality, params, torque, quality)
    extra = verify.run_fresh(f"{quality}, with estimate", params, torque, quality, estimate=True)
    cycle = (verify.run_fresh(f"{quality}, {plan.cycle}-position cycle", params, torque,
                              quality, cycle=plan.cycle) if plan.cycle else None)
    cached = verify.cache_runs(params, torque, quality, list(plan.pair_args))
    say("")
    say(f"### The model cache (`--cache`): the model built, or read back (`{quality}`, "
        "each in a fresh process)")
    say("")
    say(verify.cache_table(cached, default, extra))
    return PairRuns(default, extra, ring, cycle=cycle, cached=cached)


def _sector_ladder(plan: BenchPlan, say: Say) -> Ladder | None:
    """The sector model's ladder, with CalculiX on its meshes, where levels are asked for."""
    if not plan.sector_levels:
        return None
    say("")
    sector = verify.pair_ladder(plan.params, plan.torque, list(plan.sector_levels),
                                peer=plan.peer)
    say(verify.ladder_table(sector))
    return sector


def _scaling(plan: BenchPlan, ring: list, say: Say) -> list:
    """How the cost grows with more, smaller teeth: the runs, their table and picture."""
    scale = (verify.scaling_runs(plan.params, plan.torque, plan.quality, list(plan.scaling))
             if plan.scaling else [])
    if scale:
        say("")
        say("### How the cost grows: the same pair with more, smaller teeth "
            f"(`{plan.quality}`)")
        say("")
        say(verify.scaling_table(scale))
        verify.scaling_png(plan.out / "bench_scaling.png", ring, scale)
    return scale


def _report(plan: BenchPlan, disks: Ladder, runs: PairRuns, scale: list, say: Say,
            files: FilesRun | None = None) -> None:
    """The targets (the files' cost's with them, where it was timed), the plot, bench.json
    and the history, beside the last run's numbers."""
    say("")
    out = plan.out
    lines = pair_targets(runs) + (files.lines()[-1:] if files is not None else [])
    say("\n".join(lines))
    verify.ladder_png(out / "bench.png", _series(plan, disks, runs))
    everything = {**verify.ladder_json([disks] + ([runs.sector] if runs.sector else []),
                                       verify.ladder_targets(disks)),
                  "ring": _ring_record(runs, scale, lines, files)}
    kept = plan.history or out / history.HISTORY
    before = history.last_run(kept)
    write_json(out / "bench.json", everything)
    metrics = history.bench_metrics(everything)
    if files is not None:
        metrics[FILES_METRIC] = files.cost_s
    if before is not None:
        say("")
        say(f"### Beside the last run in {kept}")
        say("")
        say(history.beside_table(before, metrics))
    history.remember(kept, metrics, code_version(), everything["machine"])
    say(f"\nbench.json, bench.png{', bench_scaling.png' if scale else ''} in {out}; this run "
        f"appended to {kept}")


def _ring_record(runs: PairRuns, scale: list, targets: list[str],
                 files: FilesRun | None = None) -> dict:
    """bench.json's record of the tooth pair's runs and targets."""
    cached = runs.cached
    record = {"ring": [r.__dict__ for r in runs.ring], "default": runs.default.__dict__,
              "extras": runs.extra.__dict__,
              "cycle": runs.cycle.__dict__ if runs.cycle else None,
              "cache": {"read": cached.read.__dict__,
                       "read_estimate": cached.read_estimate.__dict__,
                       "commands_s": cached.commands_s}}
    if scale:
        record["scaling"] = [r.__dict__ for r in scale]
    if runs.study is not None:
        record["paper_study_s"] = runs.study[0]
    if runs.tolerance is not None:
        record["tolerance_class"] = {"seconds": runs.tolerance[0], **runs.tolerance[1]}
    if runs.spectrum is not None:
        record["spectrum"] = {"cycle_s": runs.spectrum[0], "spectrum_s": runs.spectrum[1]}
    if runs.face is not None:
        record["face"] = {name: {"flat_s": flat, "face_s": face}
                          for name, (flat, face) in runs.face.items()}
    if runs.revolution is not None:
        record["revolution"] = runs.revolution
    if runs.search is not None:
        record["search"] = runs.search
    if files is not None:
        record["files"] = {"args": list(files.args), "without_s": list(files.without),
                           "with_out_s": list(files.written), "cost_s": files.cost_s}
    record["targets"] = targets
    return record


def _series(plan: BenchPlan, disks: Ladder, runs: PairRuns) -> list:
    """bench.png's lines: run time against error for each ladder, CalculiX beside them."""
    read = runs.cached.read
    series = [verify.Series("Hertz disks",
                            [(r.total_s, disks.error_pct(r.values, disks.judged), r.level)
                             for r in disks.rungs],
                            [(r.peer_s, disks.error_pct(r.peer_values, disks.judged))
                             for r in disks.rungs if r.peer_s], bench.HERTZ_TARGET),
              verify.Series("tooth pair, ring model",
                            [(r.total_s, sector_error(r.values), r.label) for r in runs.ring],
                            target=SINGLE_TARGET),
              verify.Series("tooth pair, ring model read from the model cache",
                            [(read.total_s, sector_error(read.values),
                              f"{plan.quality}, read back")])]
    if runs.sector is not None:
        series.append(verify.Series("tooth pair, sector model",
                                    [(r.total_s, sector_error(r.values), r.level)
                                     for r in runs.sector.rungs],
                                    [(r.peer_s, sector_error(r.peer_values, PEER_KEYS))
                                     for r in runs.sector.rungs if r.peer_s],
                                    peer_note=" (root stresses)"))
    return series


def sector_check(plan: BenchPlan, say: Say) -> None:
    """The design by both models, side by side (one position, ``plan.quality``)."""
    params, torque, quality = plan.params, plan.torque, plan.quality
    ring, sector = cross_check(SolveCase(params, torque=torque, quality=quality))
    say(f"{params.describe()}, T {torque:g} N·m, β 0, quality {quality}: the ring model "
        "(fegear solve) and the sector model (its full-FE peer, docs/sector.md)\n")
    say(cross_table(ring, sector))


def files_bench(plan: BenchPlan, say: Say) -> FilesRun:
    """What ``fegear solve --out`` adds to the solve: ``plan.files`` alternated pairs of the
    whole command at the pair, its torque and quality (at least one), without and with
    ``--out``; their table and target line."""
    args = [*plan.pair_args, "--torque", f"{plan.torque:g}", "--quality", plan.quality]
    run = bench.files_run(args, max(plan.files, 1))
    say("\n".join(run.lines()))
    return run


def study_bench(plan: BenchPlan, say: Say) -> None:
    """The study runner's overhead over ``plan.study_cases`` solves on one worker."""
    say(verify.overhead_table(verify.study_overhead(plan.params, plan.study_cases, workers=1),
                              workers=1))


def contact_peer_bench(plan: BenchPlan, say: Say) -> None:
    """The contact pressures beside CalculiX's, read alike (:mod:`.peer_contact`), at
    ``plan.sector_levels`` (none: its ``LEVELS``); the table said and kept in
    ``contact_peer.json``."""
    from .calculix import ccx_available  # lazy: heavy: scikit-fem, off `fegear bench`'s check

    if not ccx_available():
        raise PeerError("fegear bench --contact-peer needs CalculiX's ccx on the PATH "
                        "(Debian: apt install calculix-ccx)")
    results = []
    for name, torque, beta in CASES:
        for level in plan.sector_levels or LEVELS:
            results.append(contact_peer(name, torque, beta, level))
            say(f"{name} at `{level}` done (ccx {results[-1].ccx_s:.0f} s)")
    table = peer_table(results)
    say("")
    say(table)
    directory = prepare_dir(plan.out)
    write_json(directory / "contact_peer.json", {"table": table, "cases": [
        {**{k: v for k, v in r.__dict__.items() if k != "teeth"},
         "teeth": [t.__dict__ for t in r.teeth]} for r in results]})
    say(f"\ncontact_peer.json in {directory}")

"""Benchmarks: time per pipeline stage, printed as markdown tables (never asserted in tests).

Ladders (:func:`disk_ladder`, and :func:`pair_ladder` for the sector model) solve one case on
meshes each twice as fine as the last and measure every level's error against the Richardson
extrapolation of the three finest (:func:`richardson`); where CalculiX is installed, it solves
the same meshes beside ours (:mod:`fegear.verify.calculix`). :func:`ladder_targets` checks the
Hertz case's run-time-versus-error target; the ring model's pair benchmark is
:mod:`.ring_bench`. :func:`files_run` times what ``fegear solve --out`` adds to the solve.
"""

from __future__ import annotations

import logging
import math
import os
import platform
import shutil
import statistics
import subprocess
import tempfile
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .. import __version__
from ..geometry import Gear1Profile, PairParameters, ToothContact, gear2_curve
from ..provenance import library_versions
from ..timing import Stopwatch
from ..toothpair import pair_summary, write_pair_outputs
from . import ring_bench
from .ccx_files import PeerError
from .sector import SectorCase

GEOMETRY_TARGET_S = 1.0


def _best(fn, repeat: int):
    best, value = np.inf, None
    for _ in range(repeat):
        watch = Stopwatch()
        value = fn()
        best = min(best, watch.s)
    return best, value


def geometry_bench(params: PairParameters, repeat: int = 3, chord_error: float = 1e-4) -> str:
    """Time the geometry stage: profiles plus clearance table (target < 1 s), and backlash."""
    rows = []
    t_env, g1 = _best(lambda: Gear1Profile(params), repeat)
    rows.append(("gear-1 envelope (exact pieces)", t_env))
    t_poly, _ = _best(lambda: (g1.polyline(chord_error),
                               gear2_curve(params).polyline(chord_error)), repeat)
    rows.append((f"polylines, both gears (chord error {chord_error * 1e3:g} µm)", t_poly))
    t_tca, _ = _best(lambda: ToothContact(params, g1).state(0.0), repeat)
    rows.append((f"clearance table at β = 0 ({params.z1} teeth × 2 directions)", t_tca))
    total = t_env + t_poly + t_tca
    t_bl, bl = _best(lambda: ToothContact(params, g1).backlash(), 1)
    lines = [
        f"fegear geometry benchmark: {params.describe()}",
        f"python {platform.python_version()}, numpy {np.__version__}, "
        f"{platform.machine()}, best of {repeat}",
        "",
        "| stage | time [s] |",
        "|---|---:|",
    ]
    lines += [f"| {name} | {t:.3f} |" for name, t in rows]
    status = "met" if total < GEOMETRY_TARGET_S else "MISSED"
    lines.append(f"| **profiles + clearance table** (target < {GEOMETRY_TARGET_S:g} s: {status})"
                 f" | **{total:.3f}** |")
    lines.append(f"| backlash over one mesh cycle (+ {bl.plus_um:.3f} µm, − {bl.minus_um:.3f} µm)"
                 f" | {t_bl:.3f} |")
    return "\n".join(lines)


# --- run time against error ----------------------------------------------------------------

log = logging.getLogger(__name__)

HERTZ_TARGET = (0.5, 0.3)   # the Hertz case within 0.5 % of its reference in 0.3 s
PEER_TARGET = 20.0          # at least 20× faster than CalculiX on the same mesh
DISK_LEVELS = (2, 4, 8, 16, 32)  # elements across the Hertz half-width
PAIR_LEVELS = ("coarse", "fast", "standard", "fine")


def richardson(values: Sequence[float], ratio: float = 2.0) -> tuple[float, float]:
    """Limit and order of a sequence of results on meshes refined by ``ratio`` each step:
    the observed order of the last three if their changes shrink by between √ratio and
    ratio⁶ (same sign), else the nominal order 2 of P2 elements on the last two."""
    if len(values) < 2:
        raise ValueError("Richardson extrapolation needs at least two levels")
    order = 2.0
    if len(values) >= 3:
        d1, d2 = values[-2] - values[-3], values[-1] - values[-2]
        if d1 * d2 > 0 and math.sqrt(ratio) <= d1 / d2 <= ratio**6:
            order = math.log(d1 / d2) / math.log(ratio)
    return values[-1] + (values[-1] - values[-2]) / (ratio**order - 1.0), order


@dataclass(frozen=True)
class Rung:
    """One mesh level: DOFs, best time per stage (s, ``output`` included), the compared values
    and, where CalculiX solved the same mesh, its wall time (s) and values."""

    level: str
    dofs: int
    timings_s: dict[str, float]
    values: dict[str, float]
    peer_s: float | None = None
    peer_values: dict[str, float] | None = None
    peer_failure: str | None = None  # why CalculiX gave no answer on this mesh

    @property
    def total_s(self) -> float:
        return sum(self.timings_s.values())

    @property
    def solve_s(self) -> float:
        """Everything after meshing: what CalculiX does on the same mesh."""
        return self.total_s - self.timings_s.get("profile", 0.0) - self.timings_s.get("mesh", 0.0)

    @property
    def peer_ratio(self) -> float | None:
        """CalculiX's wall time over ours after meshing (both solve the same mesh)."""
        return self.peer_s / self.solve_s if self.peer_s else None


@dataclass(frozen=True)
class Ladder:
    """Rungs from coarse to fine, the Richardson reference and order of every value, and the
    analytic values where there are any (Hertz)."""

    name: str
    rungs: tuple[Rung, ...]
    reference: dict[str, float] = field(init=False)
    order: dict[str, float] = field(init=False)
    analytic: dict[str, float] = field(default_factory=dict)

    def __post_init__(self) -> None:
        fits = {k: richardson([r.values[k] for r in self.rungs]) for k in self.rungs[0].values}
        object.__setattr__(self, "reference", {k: v[0] for k, v in fits.items()})
        object.__setattr__(self, "order", {k: v[1] for k, v in fits.items()})

    @property
    def judged(self) -> list[str]:
        """The values a target is judged on: the Hertz case its peak pressure, the pair every
        headline stress."""
        return ["p_max_MPa"] if "p_max_MPa" in self.reference else list(self.reference)

    def deviation_pct(self, key: str, value: float) -> float:
        """value / reference − 1 (%), signed."""
        return 100.0 * (value / self.reference[key] - 1.0)

    def error_pct(self, values: dict[str, float], keys: Sequence[str] | None = None) -> float:
        """Largest |value / reference − 1| (%) over ``keys`` (default: all)."""
        keys = keys if keys is not None else list(self.reference)
        return max(abs(self.deviation_pct(k, values[k])) for k in keys)


def _best_of(solve, repeat: int):
    runs = [solve() for _ in range(repeat)]
    best = {k: min(r.timings_s[k] for r in runs) for k in runs[0].timings_s}
    return runs[0], best


def _timed_output(write, repeat: int = 2) -> float:
    """Best time of writing the outputs (the first write also starts VTK: seconds)."""
    best = math.inf
    for _ in range(max(2, repeat)):
        with tempfile.TemporaryDirectory() as tmp:
            watch = Stopwatch()
            write(Path(tmp))
            best = min(best, watch.s)
    return best


def disk_ladder(levels: Sequence[float] = DISK_LEVELS, repeat: int = 3,
                peer: bool = True) -> Ladder:
    """The Hertz case (two 10 mm disks, 1000 N, 5 mm, plane stress) at each number of
    elements across b; CalculiX beside it if ``peer`` and installed."""
    from .calculix import (  # lazy: heavy: scikit-fem, off `fegear bench`'s check
        ccx_available,
        ccx_disks,
    )
    from .disks import (  # lazy: heavy: scikit-fem, off `fegear bench`'s check
        DiskCase,
        solve_disks,
        write_disk_outputs,
    )

    def disk_peer(case, r):
        with tempfile.TemporaryDirectory() as tmp:
            _, c = ccx_disks(case, tmp, result=r)
        return c.wall_s, {"p_max_MPa": c.p_max}

    peer = peer and ccx_available()
    rungs = []
    for n in levels:
        case = DiskCase(quality=float(n))
        r, best = _best_of(lambda case=case: solve_disks(case), repeat)
        best["output"] = _timed_output(lambda out, r=r: write_disk_outputs(r, out), repeat)
        beside = _peer(disk_peer, case, r) if peer else (None, None, None)
        rungs.append(Rung(f"{n:g} per b", r.dofs, best,
                          {"p_max_MPa": r.p_max, "half_width_mm": r.half_width}, *beside))
    h = DiskCase().hertz
    return Ladder("Hertz disks r 10 mm, P 1000 N, t 5 mm", tuple(rungs),
                  analytic={"p_max_MPa": h.p0, "half_width_mm": h.b})


def pair_ladder(params: PairParameters, torque: float = 200.0,
                levels: Sequence[str] = PAIR_LEVELS, peer: bool = False) -> Ladder:
    """The sector model's tooth pair at one position at each quality level (headline
    stresses), CalculiX beside it on the same meshes (``peer``)."""
    from .sector import solve_pair  # lazy: heavy: scikit-fem, off `fegear bench`'s check

    rungs = []
    for quality in levels:
        case = SectorCase(params, torque=torque, quality=quality)
        sol = solve_pair(case, Gear1Profile(params))
        timings = dict(sol.timings_s)
        timings["output"] = _timed_output(
            lambda out, sol=sol: write_pair_outputs(sol, out, pair_summary(sol)))
        beside = _peer(_pair_peer, case, sol) if peer else (None, None, None)
        rungs.append(Rung(quality, sol.dofs, timings, sol.headline(), *beside))
    return Ladder(f"sector model, tooth pair {params.describe()}, T {torque:g} N·m, one "
                  "position", tuple(rungs))


def _peer(run, case, ours) -> tuple[float | None, dict | None, str | None]:
    """CalculiX's wall time and values beside ours, or why it gave none: a failed peer is
    reported in the table, it does not stop the benchmark."""
    try:
        return (*run(case, ours), None)
    except PeerError as err:
        log.warning("CalculiX at %s: %s", case.quality, err)
        return None, None, str(err)


PEER_PAIR_LEVELS = ("coarse", "fast")  # CalculiX takes minutes per position beyond these


def _pair_peer(case, sol) -> tuple[float | None, dict | None]:
    from .calculix import ccx_available  # lazy: heavy: scikit-fem, off `fegear bench`'s check
    from .calculix_pair import ccx_pair  # lazy: heavy: scikit-fem, off `fegear bench`'s check

    if not ccx_available() or case.quality not in PEER_PAIR_LEVELS:
        return None, None
    with tempfile.TemporaryDirectory() as tmp:
        _, c = ccx_pair(case, tmp, solution=sol)
    return c.wall_s, {"root_stress_gear1_MPa": c.root_stress[0],
                      "root_stress_gear2_MPa": c.root_stress[1],
                      "contact_pressure_MPa": c.pressure}


@dataclass(frozen=True)
class Target:
    """A run-time-versus-error target: the cheapest rung within ``error_pct`` of the
    reference and whether it took at most ``seconds``."""

    name: str
    error_pct: float
    seconds: float
    rung: Rung | None
    met: bool

    def line(self) -> str:
        if self.rung is None:
            return f"{self.name}: no level within {self.error_pct:g} %: MISSED"
        status = "met" if self.met else "MISSED"
        return (f"{self.name} within {self.error_pct:g} % in {self.seconds:g} s: {status} "
                f"(`{self.rung.level}`, {self.rung.total_s:.2f} s)")


def ladder_targets(disks: Ladder | None) -> list[Target]:
    """The Hertz case's target (the pair's: :mod:`.ring_bench`)."""
    out = []
    for ladder, name, (err, sec) in ((disks, "Hertz case", HERTZ_TARGET),):
        if ladder is None:
            continue
        ok = [r for r in ladder.rungs if ladder.error_pct(r.values, ladder.judged) <= err]
        rung = min(ok, key=lambda r: r.total_s) if ok else None
        out.append(Target(name, err, sec, rung, rung is not None and rung.total_s <= sec))
    return out


def ladder_table(ladder: Ladder) -> str:
    """Markdown: per rung DOFs, stage times, values and errors against the reference (and
    the analytic values), CalculiX's time and value beside ours."""
    stages = list(dict.fromkeys(k for r in ladder.rungs for k in r.timings_s))
    keys = list(ladder.reference)
    peer = any(r.peer_s or r.peer_failure for r in ladder.rungs)
    peer_keys = list(dict.fromkeys(k for r in ladder.rungs for k in (r.peer_values or {})))
    head = (["level", "DOFs"] + stages + ["total [s]"] + keys + ["max err %"]
            + (["ccx [s]"] + [f"ccx {k}" for k in peer_keys] + ["ccx / ours"] if peer else []))
    lines = [f"{ladder.name}: errors against the Richardson extrapolation of the finest levels",
             "", "| " + " | ".join(head) + " |", "|---|" + "---:|" * (len(head) - 1)]
    for r in ladder.rungs:
        cells = [r.level, str(r.dofs)] + [f"{r.timings_s.get(k, 0.0):.3f}" for k in stages]
        cells += [f"{r.total_s:.3f}"]
        cells += [f"{r.values[k]:.5g} ({ladder.deviation_pct(k, r.values[k]):+.3f} %)"
                  for k in keys]
        cells += [f"{ladder.error_pct(r.values):.3f}"]
        if peer:
            if r.peer_s:
                cells += [f"{r.peer_s:.2f}"]
                cells += [f"{r.peer_values[k]:.5g} "
                          f"({ladder.deviation_pct(k, r.peer_values[k]):+.3f} %)"
                          for k in peer_keys]
                cells += [f"{r.peer_ratio:.1f}×"]
            else:
                cells += ["–"] * (len(peer_keys) + 2)
        lines.append("| " + " | ".join(cells) + " |")
    ref = ", ".join(f"{k} {v:.6g} (order {ladder.order[k]:.2f})"
                    for k, v in ladder.reference.items())
    lines += ["", f"reference: {ref}"]
    if ladder.analytic:
        lines.append("analytic: " + ", ".join(
            f"{k} {v:.6g} (reference {100 * (ladder.reference[k] / v - 1):+.3f} %)"
            for k, v in ladder.analytic.items()))
    if peer:
        lines.append("ccx / ours: CalculiX's wall time over ours after meshing (the same mesh)")
    lines += [f"ccx failed at `{r.level}`: {r.peer_failure}" for r in ladder.rungs
              if r.peer_failure]
    return "\n".join(lines)


def machine() -> dict:
    """Machine, Python and library versions for the benchmark JSON."""
    libs = library_versions()
    try:
        ccx = subprocess.run(["ccx", "-v"], capture_output=True, text=True, timeout=30)
        libs["ccx"] = " ".join(ccx.stdout.split()) or None
    except (OSError, subprocess.SubprocessError):
        libs["ccx"] = None
    mem = None
    try:
        with open("/proc/meminfo") as f:
            mem = int(f.readline().split()[1]) / 2**20
    except (OSError, ValueError, IndexError):
        pass
    return {"fegear": __version__, "python": platform.python_version(),
            "platform": platform.platform(), "machine": platform.machine(),
            "processor": platform.processor() or None, "cpus": os.cpu_count(),
            "memory_GiB": mem, "libraries": libs}


def ladder_json(ladders: Sequence[Ladder], targets: Sequence[Target]) -> dict:
    """JSON-ready record of the ladders, their targets and the machine."""
    def rung(r: Rung) -> dict:
        return {"level": r.level, "dofs": r.dofs, "timings_s": r.timings_s,
                "total_s": r.total_s, "solve_s": r.solve_s, "values": r.values,
                "peer_s": r.peer_s, "peer_values": r.peer_values,
                "peer_failure": r.peer_failure}
    return {"machine": machine(),
            "ladders": [{"name": lad.name, "reference": lad.reference, "order": lad.order,
                         "analytic": lad.analytic,
                         "rungs": [{**rung(r), "error_pct": lad.error_pct(r.values)}
                                   for r in lad.rungs]} for lad in ladders],
            "targets": [{"name": t.name, "error_pct": t.error_pct, "seconds": t.seconds,
                         "level": t.rung.level if t.rung else None,
                         "time_s": t.rung.total_s if t.rung else None, "met": t.met}
                        for t in targets]}


# --- the files of `fegear solve --out` ------------------------------------------------------

#: what the files of ``fegear solve --out`` (summary.json, the VTUs, three pictures) may add
#: to the whole command: at most this many seconds (issue 67)
FILES_TARGET_S = 0.5


@dataclass(frozen=True)
class FilesRun:
    """Wall times (s) of whole ``fegear solve ARGS`` commands, each in a fresh process, run
    in alternated pairs: ``without`` files and ``written`` with ``--out``, a pair per run."""

    args: tuple[str, ...]
    without: tuple[float, ...]
    written: tuple[float, ...]

    @property
    def costs(self) -> list[float]:
        """Each pair's difference (s): what its files added."""
        return [w - o for o, w in zip(self.without, self.written)]

    @property
    def cost_s(self) -> float:
        """The files' cost (s): the median of the pairs' differences."""
        return statistics.median(self.costs)

    @property
    def met(self) -> bool:
        return self.cost_s <= FILES_TARGET_S

    def lines(self) -> list[str]:
        """Markdown: the commands' medians and ranges, then the target line."""
        def row(name: str, values) -> str:
            return (f"| {name} | {statistics.median(values):.2f} | "
                    f"{min(values):.2f}-{max(values):.2f} |")

        command = " ".join(["fegear", "solve", *self.args])
        return [f"### The files of `--out`: `{command}`, {len(self.costs)} alternated pairs "
                "of whole commands", "",
                "| | median [s] | range [s] |", "|---|---:|---:|",
                row("without `--out`", self.without),
                row("with `--out DIR` (summary.json, the VTUs, three pictures)", self.written),
                row("the files: each pair's difference", self.costs), "",
                f"* the files of `fegear solve --out`: {self.cost_s:.2f} s over the solve "
                f"(median of {len(self.costs)} pairs, {min(self.costs):.2f}-"
                f"{max(self.costs):.2f} s) (target <= {FILES_TARGET_S:g} s): "
                f"{'met' if self.met else 'MISSED'}"]


def files_run(args: Sequence[str], runs: int) -> FilesRun:
    """``fegear solve ARGS`` without and with ``--out`` (a fresh folder each time, removed
    after), ``runs`` pairs, which of the two goes first alternating from pair to pair; the
    model cache off, as a first solve of a design runs."""
    env = {"FEGEAR_CACHE": "off"}
    without, written = [], []
    with tempfile.TemporaryDirectory(prefix="fegear-bench-files-") as tmp:
        for k in range(runs):
            out = Path(tmp) / f"out{k}"
            pair = [(without, []), (written, ["--out", str(out)])]
            for times, extra in pair if k % 2 == 0 else pair[::-1]:
                times.append(ring_bench.command_s([*args, *extra], env))
            shutil.rmtree(out)
    return FilesRun(tuple(args), tuple(without), tuple(written))

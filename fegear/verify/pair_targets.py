"""The tooth pair's targets in ``fegear bench``: each line a target, its number and whether it
is met or MISSED (the Hertz case's are :func:`~.bench.ladder_targets`).

The runs judged are :class:`~.ring_bench.RingRun` records, each from a fresh process; errors
are taken against the sector model's `fine` references (:data:`~.ring_bench.SECTOR_REFERENCE`),
von Mises also against its resolved value (:data:`~.ring_bench.VON_MISES_RESOLVED`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from . import ring_bench as rb
from .bench import PEER_TARGET

if TYPE_CHECKING:
    from .bench import Ladder
    from .ring_bench import CacheRuns, RingRun

#: what CalculiX gives that means what ours means: its largest CSTR is a pointwise penalty
#: pressure at one integration point, not a contact pressure (docs/benchmark.md)
PEER_KEYS = ("root_stress_gear1_MPa", "root_stress_gear2_MPa")
#: the references with von Mises resolved
RESOLVED = dict(rb.SECTOR_REFERENCE, von_mises_max_MPa=rb.VON_MISES_RESOLVED)


@dataclass(frozen=True)
class PairRuns:
    """The tooth pair's runs the targets judge: one position at the default quality
    (``default``), the same with the error estimate (``extra``), the ring model's ladder, and
    where they were run the mesh cycle, the sector model's ladder (with CalculiX's times on
    its meshes), the paper study (s, cases), the model cache's runs and a tolerance class's
    samples (s, their counts: :func:`~.ring_bench.class_run`) and a load spectrum's cycle (s
    alone, s with the spectrum: :func:`~.ring_bench.spectrum_run`), the pair across the
    face against the 2D one (:func:`~.ring_bench.face_run`), whole revolutions against one
    position (:func:`~.ring_bench.revolution_run`) and the design search over a turn
    (:func:`~.ring_bench.search_run`)."""

    default: RingRun
    extra: RingRun
    ring: list[RingRun]
    cycle: RingRun | None = None
    sector: Ladder | None = None
    study: tuple[float, int] | None = None
    cached: CacheRuns | None = None
    tolerance: tuple[float, dict] | None = None
    spectrum: tuple[float, float] | None = None
    face: dict[str, tuple[float, float]] | None = None
    revolution: dict[str, float] | None = None
    search: dict[str, float] | None = None


def sector_error(values: dict, keys=None) -> float:
    """Largest error (%) of ``values`` against the references (those of ``keys``, default
    all), von Mises against the resolved one."""
    keys = RESOLVED if keys is None else keys
    return max(abs(100.0 * (values[k] / RESOLVED[k] - 1.0)) for k in keys)


def _status(ok: bool) -> str:
    return "met" if ok else "MISSED"


def pair_targets(runs: PairRuns, peer_target: float = PEER_TARGET) -> list[str]:
    """The issue's targets, each met or MISSED with its number, under a heading;
    ``peer_target``: how many times faster than CalculiX at equal error."""
    lines = ["### Targets", "", _single(runs.default)]
    if runs.cached is not None:
        lines += _cache_targets(runs.default, runs.cached)
    lines += _estimate(runs.extra) + _cycle(runs.cycle, runs.default)
    peak = max(r.peak_mb for r in (runs.default, runs.extra, runs.cycle)
               if r is not None) / 1024.0
    lines.append(f"* peak memory, default quality with estimate and cycle: {peak:.2f} GB "
                 f"(target <= {rb.MEMORY_TARGET_GB:g} GB): "
                 f"{_status(peak <= rb.MEMORY_TARGET_GB)}")
    if runs.study is not None:
        seconds, cases = runs.study
        lines.append(f"* studies/paper_trends.toml, {cases} cases with estimates, 2 workers: "
                     f"{seconds:.1f} s (target <= {rb.STUDY_TARGET_S:g} s): "
                     f"{_status(seconds <= rb.STUDY_TARGET_S)}")
    if runs.tolerance is not None:
        seconds, counts = runs.tolerance
        lines.append(f"* `fegear solve {' '.join(rb.CLASS_ARGS)}`: {seconds:.1f} s, "
                     f"{counts['solved']} pairs solved at every position, {counts['jammed']} "
                     f"jammed, {counts['failed']} failed (target <= {rb.CLASS_TARGET_S:g} s): "
                     f"{_status(seconds <= rb.CLASS_TARGET_S)}")
    if runs.spectrum is not None:
        alone, rated = runs.spectrum
        lines.append(f"* `fegear solve {' '.join(rb.SPECTRUM_ARGS)}` with a 4-level "
                     f"`--spectrum` at `--KA {rb.SPECTRUM_KA}`: {rated:.2f} s against "
                     f"{alone:.2f} s alone, "
                     f"{rated / alone:.2f}× (target <= {rb.SPECTRUM_TARGET:g}×): "
                     f"{_status(rated / alone <= rb.SPECTRUM_TARGET)}")
    lines += _revolution(runs.revolution) + _search(runs.search)
    for name, (flat, face) in (runs.face or {}).items():
        target = rb.FACE_TARGETS[name]
        lines.append(f"* {name} across the face (`{' '.join(rb.FACE_ARGS)}`): {face:.2f} s "
                     f"against {flat:.2f} s for the 2D pair, {face / flat:.2f}× (target <= "
                     f"{target:g}×): {_status(face / flat <= target)}")
    if runs.sector is not None:
        lines += _peer(runs.sector, runs.ring, peer_target)
    return lines


def _single(default: RingRun) -> str:
    """One position at the default quality: every headline within the error in the time."""
    err = max(abs(v) for v in default.error_pct(rb.SECTOR_REFERENCE).values())
    err_resolved = max(abs(v) for v in default.error_pct(RESOLVED).values())
    worst = max(default.timings_s, key=default.timings_s.get)
    e_lim, t_lim = rb.SINGLE_TARGET
    return (f"* baseline pair, default quality (`{default.label}`), every headline within "
            f"{e_lim:g} % in {t_lim:g} s: {default.total_s:.2f} s, largest error "
            f"{err:.2f} % against the sector references, {err_resolved:.2f} % with the "
            f"resolved von Mises reference: "
            f"{_status(default.total_s <= t_lim and err_resolved <= e_lim)} "
            f"({default.total_s / rb.GOAL_S:.1f}× the {rb.GOAL_S:g} s goal; largest stage "
            f"{worst} {default.timings_s[worst]:.2f} s)")


def _cache_targets(default: RingRun, cached: CacheRuns) -> list[str]:
    """The targets a model read back from the model cache meets: one position in the goal's
    second, the whole command in two."""
    read = cached.read
    e_lim = rb.SINGLE_TARGET[0]
    read_err = max(abs(v) for v in read.error_pct(RESOLVED).values())
    cmd = cached.commands_s
    return [f"* one position with its model read from the model cache (`--cache`): "
            f"{read.total_s:.2f} s after import, largest error {read_err:.2f} % "
            f"(goal <= {rb.GOAL_S:g} s within {e_lim:g} %): "
            f"{_status(read.total_s <= rb.GOAL_S and read_err <= e_lim)}; built: "
            f"{default.total_s:.2f} s ({default.total_s / rb.GOAL_S:.1f}× the goal)",
            f"* the whole `fegear solve` without `--out` (imports, checks, the estimate): "
            f"{cmd['without the cache']:.2f} s, {cmd['models read from the cache']:.2f} s "
            f"with the models read from the cache (target <= {rb.COMMAND_TARGET_S:g} s): "
            f"{_status(cmd['without the cache'] <= rb.COMMAND_TARGET_S)} built, "
            f"{_status(cmd['models read from the cache'] <= rb.COMMAND_TARGET_S)} read back"]


def _estimate(extra: RingRun) -> list[str]:
    """The error estimate's cost against the single solve (none if it was not run)."""
    est = extra.extra.get("estimate_s")
    if est is None:
        return []
    ratio = est / extra.total_s
    return [f"* with the error estimate (second level "
            f"`{extra.extra['estimate_from']}`): {est:.2f} s, {ratio:.2f}× the single "
            f"solve (target <= {rb.ESTIMATE_TARGET:g}×): "
            f"{_status(ratio <= rb.ESTIMATE_TARGET)}"]


def _cycle(cycle: RingRun | None, default: RingRun) -> list[str]:
    """The mesh cycle against one position, each in its own process, from nothing."""
    if cycle is None:
        return []
    ratio = cycle.extra["cycle_s"] / default.total_s
    later = cycle.extra["cycle_later_s"]
    top = max(later, key=later.get)
    return [f"* {cycle.label}: {cycle.extra['cycle_s']:.2f} s, "
            f"{ratio:.2f}× one position (target <= {rb.CYCLE_TARGET:g}×): "
            f"{_status(ratio <= rb.CYCLE_TARGET)}; each later position "
            f"{sum(later.values()):.2f} s, most in {top} ({later[top]:.2f} s)"]


def _revolution(run: dict[str, float] | None) -> list[str]:
    """One deviated pair's revolution and 200 pairs', each against its seconds' target, with
    its multiple of one position's whole command (none if they were not run)."""
    if run is None:
        return []
    one = run["solve_s"]
    return [f"* `fegear solve {' '.join(rb.REVOLUTION_ARGS)}`: {run['pair_s']:.1f} s, "
            f"{run['pair_s'] / one:.1f}× one position's {one:.2f} s (target <= "
            f"{rb.REVOLUTION_TARGET_S:g} s): {_status(run['pair_s'] <= rb.REVOLUTION_TARGET_S)}",
            f"* `fegear solve {' '.join(rb.REVOLUTION_CLASS_ARGS)}`: {run['class_s']:.1f} s, "
            f"{run['class_s'] / one:.0f}× one position, "
            f"{run['positions_solved_per_pair']:.0f} positions solved a pair (target <= "
            f"{rb.REVOLUTION_CLASS_TARGET_S:g} s): "
            f"{_status(run['class_s'] <= rb.REVOLUTION_CLASS_TARGET_S)}"]


def _search(run: dict[str, float] | None) -> list[str]:
    """The design search over a turn against its seconds' target, with its trials, how many
    were feasible and the best (none if it was not run)."""
    if run is None:
        return []
    best = "none" if run["best_trial"] is None else f"trial {run['best_trial']}"
    return [f"* `fegear optimize {' '.join(rb.SEARCH_ARGS)}`: {run['seconds']:.0f} s, "
            f"{run['trials']} trials, {run['feasible']} feasible, best {best} (target <= "
            f"{rb.SEARCH_TARGET_S:g} s): {_status(run['seconds'] <= rb.SEARCH_TARGET_S)}"]


def _peer(sector: Ladder, ring: list[RingRun], peer_target: float) -> list[str]:
    """CalculiX on each sector mesh it solved against the cheapest ring level at no larger
    error on the root stresses."""
    lines = []
    for r in sector.rungs:
        if not r.peer_s:
            continue
        peer_err = sector_error(r.peer_values, PEER_KEYS)
        ours = [x for x in ring if sector_error(x.values, PEER_KEYS) <= peer_err]
        if not ours:
            lines.append(f"* CalculiX on the sector model's `{r.level}` mesh, "
                         f"{r.peer_s:.0f} s, root stresses within {peer_err:.2f} %: no "
                         f"ring level is as close (target >= {peer_target:g}× at equal "
                         "error): MISSED")
            continue
        fastest = min(ours, key=lambda x: x.total_s)
        ratio = r.peer_s / fastest.total_s
        lines.append(f"* CalculiX on the sector model's `{r.level}` mesh, {r.peer_s:.0f} s, "
                     f"root stresses within {peer_err:.2f} % of the references, against the "
                     f"ring model's `{fastest.label}` "
                     f"({sector_error(fastest.values, PEER_KEYS):.2f} %), "
                     f"{fastest.total_s:.2f} s: {ratio:.1f}× (target >= {peer_target:g}× "
                     f"at equal error): {_status(ratio >= peer_target)}")
    return lines

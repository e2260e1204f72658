"""One ``fegear optimize``: the search over a space, the best designs (and the baselines)
solved again at ``standard`` with the error estimate, the final table, the pictures and the
report's lines.

The command line checks its options into a :class:`SearchSettings` (the directory made);
:func:`run_optimize` runs it and gives back a :class:`SearchOutcome` to print. The search's
pieces are taken from this stage's face when they run, as the command took them, so a test
can stand in for any of them there.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from .. import progress
from ..errors import FegearError
from ..files import write_json
from ..timing import Stopwatch
from .plot import search_pngs
from .report import baselines, final_table, headline_table, resolve
from .search import best_trials, binding, load_trials, run_search
from .space import Space


@dataclass(frozen=True)
class SearchSettings:
    """What one ``fegear optimize`` runs: the ``space``, the search's directory ``out``
    (made; a search there is resumed), ``trials`` finished in all, ``workers`` local
    processes (or the Dask cluster whose scheduler is at ``scheduler``), how many of the
    ``best`` designs are solved again at standard (0: none), the ``sampler`` and its ``seed``,
    and whether the ``baselines`` are solved again too."""

    space: Space
    out: Path
    trials: int
    workers: int
    best: int
    sampler: str = "tpe"
    seed: int = 0
    baselines: bool = True
    scheduler: str | None = None


@dataclass(frozen=True)
class SearchOutcome:
    """A finished search: the ``lines`` of its report, and ``final``, the designs solved again
    as final.json holds them (``search_s``: the search's time, s; ``rows``: by design), or
    None where no design was feasible (nothing solved again, nothing written)."""

    lines: tuple[str, ...]
    final: dict | None


def run_optimize(settings: SearchSettings) -> SearchOutcome:
    """Search, solve the best again beside the baselines, write final.json, final.md and the
    pictures into ``settings.out``; raise :class:`~.search.SearchInterrupted` on a stop."""
    s, space = settings, settings.space
    watch = Stopwatch()
    result = run_search(space, s.out, s.trials, s.workers, s.sampler, s.seed,
                        report=progress.stage, scheduler=s.scheduler, keep=max(s.best, 1))
    search_s = watch.s
    table = load_trials(s.out)
    best = best_trials(result.study, space, max(s.best, 1))
    head = (f"{result.found} trials found finished, {result.solved} solved now in "
            f"{search_s:.0f} s ({len(table)} in the journal; "
            f"{int((table['feasible'].astype(str) == 'True').sum())} feasible)")
    if not best:
        return SearchOutcome((head, "no feasible design: the constraint that binds is "
                                    f"{binding(result.study)}"), None)
    rows, failed = _solve_again(s, best)
    pictures = _pictures(s, table, rows)
    md = _final_md(space, rows)
    final = {"search_s": search_s, "rows": rows}
    write_json(s.out / "final.json", final)
    (s.out / "final.md").write_text(md + "\n")
    files = {"trials": result.table, **pictures, "final": s.out / "final.md",
             "best design": s.out / "best"}
    lines = [head, *failed, *_final_lines(space, rows, md),
             "", *(f"{k:14s} {v}" for k, v in files.items() if Path(v).exists())]
    return SearchOutcome(tuple(lines), final)


def _solve_again(s: SearchSettings, best: list) -> tuple[dict[str, dict], list[str]]:
    """The baselines (unless left out) and the ``s.best`` best trials solved again at
    standard over the cycle with the estimate (the first's files in ``best/``); a design that
    cannot be is said, not fatal: the search's results stand."""
    rows: dict[str, dict] = {}
    failed: list[str] = []

    def again(name: str, values: dict, files: Path | None) -> None:
        try:
            rows[name] = resolve(values, s.space.positions, files)
        except FegearError as exc:
            failed.append(f"{name} could not be solved again at standard: {exc}")

    if s.baselines:
        for name, values in baselines(s.space).items():
            progress.stage(f"the {name} at standard over the cycle")
            again(name, values, None)
    for k, t in enumerate(best[:s.best] if s.best else []):
        progress.stage(f"best design {k + 1} (trial {t.number}) at standard with the estimate")
        again(f"trial {t.number}", s.space.values(t.params), s.out / "best" if k == 0 else None)
    return rows, failed


def _pictures(s: SearchSettings, table, rows: dict[str, dict]) -> dict[str, Path]:
    """The search's pictures, the baselines' safety marked where safety is the objective."""
    space = s.space
    safety = space.objectives[0] == "safety"
    return search_pngs(table, [v.name for v in space.variables], list(space.objectives), s.out,
                       f"{s.trials} trials, {s.sampler}, {space.positions} positions at "
                       f"{space.quality}, T {space.fixed['torque']:g} N·m",
                       rows.get("baseline", {}).get("safety") if safety else None,
                       rows.get("relieved baseline", {}).get("safety") if safety else None)


def _final_md(space: Space, rows: dict[str, dict]) -> str:
    """final.md: the designs solved again and their headline stresses (empty: none)."""
    return (final_table(rows, space) + "\n\nthe headline stresses over the cycle (MPa) and "
            "their error estimates:\n\n" + headline_table(rows)) if rows else ""


def _final_lines(space: Space, rows: dict[str, dict], md: str) -> list[str]:
    """The report's final table and the best design's verdict with its ``fegear solve``."""
    lines = []
    if rows:
        lines += ["", f"over the cycle at {space.fixed['torque']:g} N·m, {space.positions} "
                      "positions, solved again at standard; smallest: the least safety factor "
                      "of all four (S_H with a loaded tip round); gain: against the relieved "
                      "baseline; est. %: the largest error estimate of the headline stresses:",
                  "", md]
    first = next((r for n, r in rows.items() if n.startswith("trial")), None)
    if first is not None:
        passes = first["safety"] >= 1.0 and first["edge_load_N"] <= 0.0
        verdict = ("every safety factor >= 1 over the cycle, no load on a tip round"
                   if passes else "it does not pass: a safety factor below 1 or a loaded round")
        lines += ["", f"best: {verdict}; its numbers again:", f"  {first['command']}"]
    return lines

"""``fegear optimize``: the design that carries the torque with the largest safety margin over a
mesh cycle, inside bounds and constraints (:mod:`fegear.optimize`, docs/optimize.md)."""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from pathlib import Path

from ..checks import Input
from ..errors import FegearError
from ..optimize.space import CONSTRAINT_INPUTS
from ..toothpair.inputs import QUALITY, SOLVE_INPUTS
from .args import add_inputs, checked, given_values, workers_input

#: the solve inputs a search holds fixed by option (the cycle, the estimate and the screening
#: quality are its own options)
TAKEN = [row for name, row in SOLVE_INPUTS.items()
         if name not in ("position", "positions", "no-estimate", "quality")]
WORKERS = 2
#: the search's own inputs (its constraints are :data:`~fegear.optimize.space.
#: CONSTRAINT_INPUTS`)
SEARCH_INPUTS = (
    Input("trials", int, 200, "finished trials in all, a resumed search's included", low=1,
          high=100_000),
    Input("positions", int, 12, "rolling angles of each trial's mesh cycle", low=2,
          high=360),
    Input("seed", int, 0, "the sampler's seed", low=0, high=2**32 - 1),
    workers_input("worker processes", f"the machine's cores, at most {WORKERS}"),
    Input("best", int, 3, "best designs solved again at standard with the estimate", low=0,
          high=20),
)


def add_parser(sub) -> None:
    p = sub.add_parser("optimize", help="search m, h1, f1, relief, … for the design with the "
                                        "largest safety margin over a mesh cycle")
    add_inputs(p, TAKEN, "fixed inputs (any varied one is left out)")
    g = p.add_argument_group("search")
    g.add_argument("--vary", action="append", default=None, metavar="NAME=LOW:HIGH",
                   help="a design variable and its bounds, repeated (default: the seed "
                        "paper's ranges m=1:2.5, h1=0.2:0.4, f1=0.1:0.2 with relief=0:10 µm "
                        "and tip-clearance=0.01:0.04 mm, less any given a value); names: m, "
                        "h1, f1, "
                        "shift, rotation, tip-clearance, relief, relief-extent, relief-start, "
                        "tip-round, face-width, rim1, rim2")
    g.add_argument("--objectives", default="safety",
                   help="safety (the smallest of S_F1, S_F2, S_H flank: maximised), te (the "
                        "transmission error's peak to peak: minimised), stiffness (the mean "
                        "mesh stiffness: maximised); two or more, comma-separated, give a "
                        "Pareto front (default safety)")
    add_inputs(p, SEARCH_INPUTS, into=g)
    g.add_argument("--quality", default="coarse", choices=QUALITY,
                   help="the trials' mesh quality (default coarse; the best are solved again "
                        "at standard)")
    g.add_argument("--sampler", default="tpe", choices=("tpe", "random"),
                   help="tpe: 40 trials from a scrambled Sobol sequence, then Optuna's TPE "
                        "with the constraints (default); random: for comparison")
    g.add_argument("--scheduler", default=None,
                   help="solve the trials on this Dask distributed scheduler (e.g. "
                        "tcp://host:8786; its workers need fegear) instead of the local pool")
    g.add_argument("--no-baselines", action="store_true",
                   help="leave the baseline and the relieved baseline out of the final table")
    g.add_argument("--out", default="out/optimize",
                   help="the search's directory: journal, trials, plots, the best design's "
                        "files (default out/optimize; a search there is resumed)")
    g.add_argument("--json", action="store_true", help="print the final table as JSON")
    add_inputs(p, CONSTRAINT_INPUTS, "constraints")


def run(a: argparse.Namespace) -> int:
    from .. import progress
    from ..files import check_dir, prepare_dir, write_json
    from ..optimize import (
        DEFAULT_RANGES,
        SearchInterrupted,
        Space,
        baselines,
        best_trials,
        binding,
        check_space,
        final_table,
        headline_table,
        load_trials,
        parse_variables,
        resolve,
        run_search,
        search_pngs,
    )

    if a.workers is not None and a.scheduler:
        raise FegearError("--workers sets the local pool; with --scheduler the cluster's "
                          "workers solve the trials (leave --workers out)")
    own = checked(a, SEARCH_INPUTS)
    workers = own["workers"] or min(os.cpu_count() or 1, WORKERS)
    trials, positions, best_count, seed = (own[k] for k in ("trials", "positions", "best",
                                                            "seed"))
    fixed = given_values(a, TAKEN)
    # without --vary, the default variables less those given a value
    variables = parse_variables(a.vary or [f"{k}={lo}:{hi}" for k, (lo, hi)
                                           in DEFAULT_RANGES.items() if k not in fixed])
    fixed.setdefault("torque", SOLVE_INPUTS["torque"].default)
    constraints = {row.dest: getattr(a, row.dest) for row in CONSTRAINT_INPUTS
                   if getattr(a, row.dest) is not None}
    space = Space(variables, fixed, positions, a.quality, constraints,
                  tuple(o.strip() for o in a.objectives.split(",") if o.strip()))
    check_space(space)
    check_dir(a.out)                       # every check before the directory is made
    out = prepare_dir(a.out)
    where = f"the cluster at {a.scheduler}" if a.scheduler else f"{workers} workers"
    print(f"fegear optimize: {trials} trials of {positions} positions at {a.quality} on "
          f"{where}, varying " + ", ".join(f"{v.name} {v.low:g}-{v.high:g}"
                                                   for v in variables)
          + f"; results in {out}", file=sys.stderr, flush=True)
    t0 = time.perf_counter()
    try:
        result = run_search(space, out, trials, workers, a.sampler, seed,
                            report=progress.stage, scheduler=a.scheduler)
    except SearchInterrupted as exc:
        print(f"fegear: {exc}", file=sys.stderr)
        return 128 + exc.signum
    search_s = time.perf_counter() - t0
    table = load_trials(out)
    best = best_trials(result.study, space, max(best_count, 1))
    lines = [f"{result.found} trials found finished, {result.solved} solved now in "
             f"{search_s:.0f} s ({len(table)} in the journal; "
             f"{int((table['feasible'].astype(str) == 'True').sum())} feasible)"]
    if not best:
        lines.append(f"no feasible design: the constraint that binds is {binding(result.study)}")
        print("\n".join(lines))
        return 0
    rows: dict[str, dict] = {}
    failed: list[str] = []

    def again(name: str, values: dict, files: Path | None) -> None:
        try:
            rows[name] = resolve(values, positions, files)
        except FegearError as exc:    # said, not fatal: the search's results stand
            failed.append(f"{name} could not be solved again at standard: {exc}")

    if not a.no_baselines:
        for name, values in baselines(space).items():
            progress.stage(f"the {name} at standard over the cycle")
            again(name, values, None)
    for k, t in enumerate(best[:best_count] if best_count else []):
        progress.stage(f"best design {k + 1} (trial {t.number}) at standard with the estimate")
        again(f"trial {t.number}", space.values(t.params), out / "best" if k == 0 else None)
    objective = space.objectives[0]
    pictures = search_pngs(table, [v.name for v in variables], list(space.objectives), out,
                           f"{trials} trials, {a.sampler}, {positions} positions at "
                           f"{a.quality}, T {fixed['torque']:g} N·m",
                           rows.get("baseline", {}).get("safety") if objective == "safety"
                           else None,
                           rows.get("relieved baseline", {}).get("safety")
                           if objective == "safety" else None)
    md = (final_table(rows, space) + "\n\nthe headline stresses over the cycle (MPa) and "
          "their error estimates:\n\n" + headline_table(rows)) if rows else ""
    write_json(out / "final.json", {"search_s": search_s, "rows": rows})
    (out / "final.md").write_text(md + "\n")
    if a.json:
        print(json.dumps({"search_s": search_s, "rows": rows}, indent=2))
        return 0
    lines += failed
    if rows:
        lines += ["", f"over the cycle at {fixed['torque']:g} N·m, {positions} positions, solved "
                      "again at standard; smallest: the least safety factor of all four (S_H "
                      "with a loaded tip round); gain: against the relieved baseline; est. %: the "
                      "largest error estimate of the headline stresses:", "", md]
    first = next((r for n, r in rows.items() if n.startswith("trial")), None)
    if first is not None:
        passes = first["safety"] >= 1.0 and first["edge_load_N"] <= 0.0
        verdict = ("every safety factor >= 1 over the cycle, no load on a tip round"
                   if passes else "it does not pass: a safety factor below 1 or a loaded round")
        lines += ["", f"best: {verdict}; its numbers again:", f"  {first['command']}"]
    files = {"trials": result.table, **pictures, "final": out / "final.md",
             "best design": out / "best"}
    lines += ["", *(f"{k:14s} {v}" for k, v in files.items() if Path(v).exists())]
    print("\n".join(lines))
    return 0

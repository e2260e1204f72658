"""``fegear optimize``: the design that carries the torque with the largest safety margin over a
mesh cycle, inside bounds and constraints (:mod:`fegear.optimize`, docs/optimize.md)."""

from __future__ import annotations

import argparse
import json
import os
import sys
from typing import TYPE_CHECKING

from ..checks import Input
from ..errors import FegearError
from ..optimize.space import CONSTRAINT_INPUTS
from ..toothpair.inputs import FACE_INPUTS, QUALITY, SOLVE_INPUTS, TOLERANCE_INPUTS
from .args import add_inputs, checked, given_values, workers_input

if TYPE_CHECKING:
    from ..optimize import SearchSettings

#: the solve inputs a search holds fixed by option (the cycle, the estimate and the screening
#: quality are its own options)
TAKEN = [row for name, row in SOLVE_INPUTS.items()
         if name not in ("position", "positions", "no-estimate", "quality")]
#: a tolerance class's inputs: each design measured on the class's pairs (the draw's seed
#: fixed: every design meets the same pairs)
CLASS = [row for row in TOLERANCE_INPUTS
         if row.name in ("grade", "samples", "quantile", "centre-distance-tolerance")]
#: the condition across the face every design is solved under (a misalignment, a tilt) and
#: the face's modifications held fixed (a crowning, an end relief: or varied, --vary)
ACROSS = [row for row in FACE_INPUTS if row.name not in ("helix-slope-deviation",
                                                         "helix-form-deviation", "lead")]
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
    add_inputs(p, ACROSS, "across the face: each design solved under a misalignment, its "
                          "stresses the worst section's (--vary crowning=0:5 sizes a crowning "
                          "with the rest)")
    add_inputs(p, CLASS, "a tolerance class: each design's safety factors at --quantile of "
                         "its --samples pairs (the same pairs for every design)")


def run(a: argparse.Namespace) -> int:
    from ..optimize import SearchInterrupted, run_optimize

    settings = _settings(a)
    print(_start_line(settings), file=sys.stderr, flush=True)
    try:
        outcome = run_optimize(settings)
    except SearchInterrupted as exc:
        print(f"fegear: {exc}", file=sys.stderr)
        return 128 + exc.signum
    if a.json and outcome.final is not None:
        print(json.dumps(outcome.final, indent=2))
    else:
        print("\n".join(outcome.lines))
    return 0


def _settings(a: argparse.Namespace) -> SearchSettings:
    """The search's settings from its options, every one checked before its directory is
    made."""
    from ..files import check_dir, prepare_dir
    from ..optimize import DEFAULT_RANGES, SearchSettings, Space, check_space, parse_variables

    if a.workers is not None and a.scheduler:
        raise FegearError("--workers sets the local pool; with --scheduler the cluster's "
                          "workers solve the trials (leave --workers out)")
    own = checked(a, SEARCH_INPUTS)
    fixed = {**given_values(a, TAKEN), **given_values(a, CLASS), **given_values(a, ACROSS)}
    # without --vary, the default variables less those given a value
    variables = parse_variables(a.vary or [f"{k}={lo}:{hi}" for k, (lo, hi)
                                           in DEFAULT_RANGES.items() if k not in fixed])
    fixed.setdefault("torque", SOLVE_INPUTS["torque"].default)
    constraints = {row.dest: getattr(a, row.dest) for row in CONSTRAINT_INPUTS
                   if getattr(a, row.dest) is not None}
    space = Space(variables, fixed, own["positions"], a.quality, constraints,
                  tuple(o.strip() for o in a.objectives.split(",") if o.strip()))
    check_space(space)
    check_dir(a.out)                       # every check before the directory is made
    return SearchSettings(space=space, out=prepare_dir(a.out), trials=own["trials"],
                          workers=own["workers"] or min(os.cpu_count() or 1, WORKERS),
                          best=own["best"], sampler=a.sampler, seed=own["seed"],
                          baselines=not a.no_baselines, scheduler=a.scheduler)


def _start_line(s: SearchSettings) -> str:
    """What the search is about to do, for stderr."""
    space = s.space
    where = f"the cluster at {s.scheduler}" if s.scheduler else f"{s.workers} workers"
    return (f"fegear optimize: {s.trials} trials of {space.positions} positions at "
            f"{space.quality} on {where}, varying "
            + ", ".join(f"{v.name} {v.low:g}-{v.high:g}" for v in space.variables)
            + f"; results in {s.out}")

"""``fegear relief``: the smallest tip relief that keeps the loaded teeth off their tip rounds
over a mesh cycle (:mod:`fegear.toothpair.relief_rule`)."""

from __future__ import annotations

import argparse
import json
import os

from ..checks import require_range
from ..toothpair.inputs import SOLVE_INPUTS
from .args import add_inputs, given_values
from .cache import add_switch, apply_switch

#: the solve inputs the relief search takes (the amount is what it finds; one model, no
#: estimate, its own number of positions; no safety factors, so no allowable stresses)
WORKERS = 2   # the search's guess ahead pays for one more worker, seldom two

TAKEN = [row for name, row in SOLVE_INPUTS.items()
         if name not in ("relief", "position", "positions", "no-estimate") and not row.post]


def add_parser(sub) -> None:
    p = sub.add_parser("relief", help="the smallest tip relief that keeps the teeth off their "
                                      "tip rounds over a mesh cycle")
    add_inputs(p, TAKEN)
    p.add_argument("--cycle-positions", type=int, default=12,
                   help="rolling angles per trial across one tooth pitch (default 12)")
    p.add_argument("--margin", type=float, default=0.2,
                   help="torque overload the relief must cover, 0 <= margin <= 2 (default 0.2)")
    p.add_argument("--keep-tip-clearance", action="store_true",
                   help="refuse, rather than raise the tip clearance, when far-side tips land "
                        "on their rounds")
    p.add_argument("--workers", type=int, default=None,
                   help="processes that solve trials at once, the next one guessed ahead "
                        "(default: the machine's cores, at most 2; 1 solves one at a time)")
    p.add_argument("--json", action="store_true", help="print the result as JSON")
    add_switch(p, default=True)


def run(a: argparse.Namespace) -> int:
    from .. import progress
    from ..toothpair.relief_rule import size_relief, sizing_table

    values = given_values(a, TAKEN)
    positions = int(require_range("cycle_positions", a.cycle_positions, 2, 360))
    margin = require_range("margin", a.margin, 0.0, 2.0)
    cores = os.cpu_count() or 1
    workers = int(require_range("workers", a.workers, 1, 4 * cores)
                  if a.workers is not None else min(cores, WORKERS))
    apply_switch(a, default=True)   # before the workers start: they inherit it
    result = size_relief(values, positions=positions, margin=margin,
                         clearance=not a.keep_tip_clearance,
                         report=progress.stage,  # each relief tried: a stage on the bar
                         workers=workers)
    print(json.dumps(result.summary(), indent=2) if a.json else sizing_table(result))
    return 0

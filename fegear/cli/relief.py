"""``fegear relief``: the smallest tip relief that keeps the loaded teeth off their tip rounds
over a mesh cycle (:mod:`fegear.toothpair.relief_rule`)."""

from __future__ import annotations

import argparse
import json
import os

from ..checks import Input
from ..toothpair.inputs import SOLVE_INPUTS
from .args import add_inputs, checked, given_values, workers_input
from .cache import add_switch, apply_switch

#: the solve inputs the relief search takes (the amount is what it finds; one model, no
#: estimate, its own number of positions; no safety factors, so no allowable stresses)
WORKERS = 2   # the search's guess ahead pays for one more worker, seldom two

TAKEN = [row for name, row in SOLVE_INPUTS.items()
         if name not in ("relief", "position", "positions", "no-estimate") and not row.post]


#: the search's own inputs
RELIEF_INPUTS = (
    Input("cycle-positions", int, 12, "rolling angles per trial across one tooth pitch",
          low=2, high=360),
    Input("margin", float, 0.2, "torque overload the relief must cover", low=0.0, high=2.0),
    workers_input("processes that solve trials at once, the next one guessed ahead (1 solves "
                  "one at a time)", f"the machine's cores, at most {WORKERS}"),
)


def add_parser(sub) -> None:
    p = sub.add_parser("relief", help="the smallest tip relief that keeps the teeth off their "
                                      "tip rounds over a mesh cycle")
    add_inputs(p, TAKEN)
    add_inputs(p, RELIEF_INPUTS)
    p.add_argument("--keep-tip-clearance", action="store_true",
                   help="refuse, rather than raise the tip clearance, when far-side tips land "
                        "on their rounds")
    p.add_argument("--json", action="store_true", help="print the result as JSON")
    add_switch(p, default=True)


def run(a: argparse.Namespace) -> int:
    from .. import progress
    from ..running import pool_or_serial
    from ..toothpair.relief_rule import ReliefSearch, size_relief, sizing_table

    values = given_values(a, TAKEN)
    own = checked(a, RELIEF_INPUTS)
    search = ReliefSearch(positions=own["cycle_positions"], margin=own["margin"],
                          clearance=not a.keep_tip_clearance)
    workers = own["workers"] or min(os.cpu_count() or 1, WORKERS)
    apply_switch(a, default=True)   # before the workers start: they inherit it
    with pool_or_serial(workers) as executor:   # a guess still running is not waited for
        result = size_relief(values, search, executor,
                             report=progress.stage)  # each relief tried: a stage on the bar
    print(json.dumps(result.summary(), indent=2) if a.json else sizing_table(result))
    return 0

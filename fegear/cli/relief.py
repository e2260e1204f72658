"""``fegear relief``: the smallest tip relief that keeps the loaded teeth off their tip rounds
over a mesh cycle (:mod:`fegear.optimize.relief_rule`)."""

from __future__ import annotations

import argparse
import json
import os
from dataclasses import replace

from ..checks import Input
from ..toothpair.inputs import SOLVE_INPUTS, TOLERANCE_INPUTS
from .args import add_inputs, checked, given_values, workers_input
from .cache import add_switch, apply_switch

#: the solve inputs the relief search takes (the amount is what it finds; one model, no
#: estimate, its own number of positions; no safety factors, so no allowable stresses)
WORKERS = 2   # the search's guess ahead pays for one more worker, seldom two

TAKEN = [row for name, row in SOLVE_INPUTS.items()
         if name not in ("relief", "position", "positions", "no-estimate") and not row.post]
#: a tolerance class's inputs: the relief then keeps the rounds unloaded in --quantile of its
#: pairs (docs/tolerance.md, "A relief for a class")
CLASS = [replace(row, help={
    "grade": "ISO 1328-1:2013 flank tolerance class of both gears: the relief that keeps the "
             "rounds unloaded in --quantile of the --samples pairs the class admits",
    "quantile": "the share of the class's pairs (those that turn) the relief keeps off their "
                "rounds"}.get(row.name, row.help))
         for row in TOLERANCE_INPUTS if row.name not in ("sensitivities", "misalignment-band")]


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
    add_inputs(p, CLASS, "a tolerance class: the relief that keeps the rounds unloaded in "
                         "--quantile of its pairs")
    p.add_argument("--keep-tip-clearance", action="store_true",
                   help="refuse, rather than raise the tip clearance, when far-side tips land "
                        "on their rounds")
    p.add_argument("--json", action="store_true", help="print the result as JSON")
    add_switch(p, default=True)


def run(a: argparse.Namespace) -> int:
    from .. import progress
    from ..optimize.relief_rule import ReliefSearch, size_relief, sizing_table
    from ..running import pool_or_serial

    values = given_values(a, TAKEN)
    own = checked(a, RELIEF_INPUTS)
    graded, solve = _graded(values, given_values(a, CLASS))
    search = ReliefSearch(positions=own["cycle_positions"], margin=own["margin"],
                          clearance=not a.keep_tip_clearance)
    workers = own["workers"] or min(os.cpu_count() or 1, WORKERS)
    apply_switch(a, default=True)   # before the workers start: they inherit it
    with pool_or_serial(workers) as executor:   # a guess still running is not waited for
        result = size_relief(values, search, executor, solve=solve,
                             report=progress.stage)  # each relief tried: a stage on the bar
    summary = {**result.summary(), **({"class": graded} if graded else {})}
    if a.json:
        print(json.dumps(summary, indent=2))
        return 0
    if graded:
        print(f"for {100 * graded['quantile']:g} % of the pairs of ISO 1328-1:2013 class "
              f"{graded['grade']} ({graded['samples']} drawn, seed {graded['seed']}): the "
              "rounds count as loaded where more of the pairs that turn load them; the "
              "pressures below are the exact pair's\n")
    print(sizing_table(result))
    return 0


def _graded(values: dict, given: dict):
    """A class's draw and the trial that solves its pairs (None, None without ``--grade``),
    its inputs checked as ``fegear solve`` checks them."""
    from ..optimize.relief_rule import Graded
    from ..toothpair import prepare_job

    if given.get("grade") is None:
        prepare_job({**values, **given})   # refuses a class's input without the class
        return None, None
    job = prepare_job({**values, **given})
    draw = job.draw
    return ({"grade": draw.grade.grade, "samples": draw.count, "seed": draw.seed,
             "quantile": job.quantile},
            Graded(draw, job.quantile))

"""``fegear crowning``: the smallest lead crowning (or end relief) that keeps K_Hβ at most a
target over a misalignment band (:mod:`fegear.optimize.crowning`)."""

from __future__ import annotations

import argparse
import json
from dataclasses import replace

from ..checks import Input
from ..toothpair.inputs import FACE_INPUTS, SOLVE_INPUTS
from .args import add_inputs, checked, given_values
from .cache import add_switch, apply_switch

#: the solve inputs the search takes: the pair's and the load's (its own positions and
#: quality; the crowning and misalignment are what it varies; no estimate, no safety factors)
TAKEN = [row for name, row in SOLVE_INPUTS.items()
         if name not in ("positions", "revolution", "quality", "no-estimate") and not row.post]
#: across the face: the sections only (the rest is what the search sets)
SECTIONS = [row for row in FACE_INPUTS if row.name == "face-sections"]
#: an end relief's length, when the search sizes an end relief
END_LENGTH = replace(next(row for row in FACE_INPUTS if row.name == "end-length"),
                     help="the end relief's length from each end (with --modification "
                          "end-relief)")

#: the search's own inputs (defaults: :mod:`fegear.optimize.crowning`)
CROWNING_INPUTS = (
    Input("misalignment-band", float, None, "the misalignment band ±F the crowning must cover "
          "(gear 1's axis against gear 2's across the line of centres, over the face); "
          "required", "µm", low=0.0, low_open=True, high=200.0,
          rule="none: required"),
    Input("target", float, 1.15, "the largest K_Hβ allowed over the band (1.15: ISO "
          "6336-1's method C for a mismatch of 0.3 times the mesh's approach)", low=1.0,
          low_open=True, high=3.0),
    Input("positions", int, 6, "rolling angles a trial is solved at across one tooth pitch "
          "(1: only --position)", low=1, high=360),
    replace(SOLVE_INPUTS["quality"], default="coarse",
            help="mesh refinement of every solve (coarse: a trial in 3-5 s on two cores)"),
    Input("tolerance", float, 0.5, "the search ends when its bracket is this narrow", "µm",
          low=0.0, low_open=True, high=10.0),
    Input("modification", str, "crowning", "what the search sizes: gear 1's lead crowning "
          "C_β, or an end relief C_I over --end-length from each end",
          choices=("crowning", "end-relief")),
    END_LENGTH,
)


def add_parser(sub) -> None:
    p = sub.add_parser("crowning", help="the smallest lead crowning (or end relief) that "
                                        "keeps K_Hβ under a target over a misalignment band")
    add_inputs(p, TAKEN)
    add_inputs(p, SECTIONS)
    add_inputs(p, CROWNING_INPUTS, "the search")
    p.add_argument("--json", action="store_true", help="print the result as JSON")
    add_switch(p, default=True)


def run(a: argparse.Namespace) -> int:
    from .. import progress
    from ..optimize.crowning import CrowningSearch, size_crowning, sizing_table
    from ..running import spare_core
    from ..toothpair import prepare_job

    values = {**given_values(a, TAKEN), **given_values(a, SECTIONS)}
    prepare_job(values)   # the pair's and the load's inputs refused by name first, as solve's
    own = checked(a, CROWNING_INPUTS)
    search = CrowningSearch(own["misalignment_band"], own["target"], own["positions"],
                            own["quality"], own["tolerance"], own["modification"],
                            own["end_length"])
    apply_switch(a, default=True)   # before the forked copy starts: it inherits it
    with spare_core() as executor:   # a trial's positions on the machine's second core
        result = size_crowning(values, search, executor, report=progress.stage)
    if a.json:
        print(json.dumps(result.summary(), indent=2))
        return 0
    print(sizing_table(result))
    return 0

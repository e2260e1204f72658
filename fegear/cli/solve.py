"""``fegear solve``: the tooth-pair stress solve at one position or over a mesh cycle."""

from __future__ import annotations

import argparse
import json

from ..toothpair.inputs import PAIR_INPUTS, SOLVE_INPUTS
from .args import add_inputs, input_values


def add_parser(sub) -> None:
    p = sub.add_parser("solve", help="tooth-pair FE solve: stresses, load sharing, stiffness")
    rows = list(SOLVE_INPUTS.values())
    add_inputs(p, rows[:len(PAIR_INPUTS)], "pair")
    add_inputs(p, rows[len(PAIR_INPUTS):])
    p.add_argument("--out", required=True, help="output directory (VTU, PNG, summary.json)")
    p.add_argument("--json", action="store_true", help="print the summary as JSON")


def run(a: argparse.Namespace) -> int:
    from ..files import prepare_dir
    from ..toothpair import cycle_table, pair_table, prepare_job, run_job

    job = prepare_job(input_values(a, SOLVE_INPUTS.values()))
    result = run_job(job, prepare_dir(a.out))
    files = {k: str(v) for k, v in result.files.items()}
    if a.json:
        print(json.dumps({**result.summary, "files": files}, indent=2))
    else:
        if result.rows:
            print(cycle_table(result.rows))
            print(f"\n{len(result.rows)} positions on one mesh in "
                  f"{result.summary['cycle']['solve_s']:.1f} s; the details below are at the "
                  "position of the largest gear-1 root stress\n")
        print(pair_table(result.summary))
        for k, v in files.items():
            print(f"{k:10s} {v}")
    return 0

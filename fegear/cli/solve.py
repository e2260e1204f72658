"""``fegear solve``: the tooth-pair stress solve at one position or over a mesh cycle."""

from __future__ import annotations

import argparse
import json

from ..toothpair.inputs import JOB_INPUTS, PAIR_INPUTS
from .args import add_inputs, given_values
from .cache import add_switch, apply_switch


def add_parser(sub) -> None:
    p = sub.add_parser("solve", help="tooth-pair FE solve: stresses, load sharing, stiffness")
    rows = list(JOB_INPUTS.values())
    add_inputs(p, rows[:len(PAIR_INPUTS)], "pair")
    add_inputs(p, rows[len(PAIR_INPUTS):])
    p.add_argument("--out", default=None,
                   help="output directory for summary.json, VTU files and pictures, made when "
                        "the solve has succeeded (default: none, the table only)")
    p.add_argument("--json", action="store_true", help="print the summary as JSON")
    p.add_argument("--report", action="store_true",
                   help="write report.html into --out: one self-contained page, the verdict "
                        "first (docs/outputs.md, \"The report\")")
    p.add_argument("--scheduler", default=None,
                   help="with --grade: solve the class's pairs on this Dask distributed "
                        "scheduler (e.g. tcp://host:8786; its workers need fegear) instead of "
                        "this machine's second core")
    add_switch(p, default=False)


def run(a: argparse.Namespace) -> int:
    import shlex
    import shutil

    from ..errors import FegearError
    from ..files import check_dir
    from ..running import Cluster, connect, spare_core
    from ..toothpair import cycle_table, pair_table, prepare_job, run_job
    from ..toothpair.revolution import revolution_table
    from .terminal import command_wall_s

    job = prepare_job(given_values(a, JOB_INPUTS.values()))
    if a.report and a.out is None:
        raise FegearError("--report: with --out DIR (the page is written there, beside the "
                          "pictures it shows)")
    if a.scheduler and job.draw is None:
        raise FegearError("--scheduler: with --grade only (a class's pairs are the work a "
                          "cluster shares)")
    apply_switch(a, default=False)
    out = None if a.out is None else check_dir(a.out)
    made = out is not None and not out.exists()
    try:
        with Cluster(connect(a.scheduler)) if a.scheduler else spare_core() as executor:
            result = run_job(job, out, executor=executor,
                             report=shlex.join(["fegear", *a.argv]) if a.report else None)
    except BaseException:
        if made and out.exists():  # made by this run: nothing half-written stays
            shutil.rmtree(out, ignore_errors=True)
        raise
    files = {k: str(v) for k, v in result.files.items()}
    if a.json:
        print(json.dumps({**result.summary, "files": files}, indent=2))
        return 0
    if "revolution" in result.summary:
        rev = result.summary["revolution"]
        print(revolution_table(rev))
        print(f"\n{rev['positions']} positions over {rev['pitches']} pitches (one turn of gear "
              f"1) in {result.summary['cycle']['solve_s']:.1f} s; the details below are at the "
              "position of the largest gear-1 root stress\n")
    elif result.rows:
        print(cycle_table(result.rows))
        also = " (and the class's pairs)" if "samples" in result.summary else ""
        print(f"\n{len(result.rows)} positions on one mesh{also} in "
              f"{result.summary['cycle']['solve_s']:.1f} s; the details below are at the "
              "position of the largest gear-1 root stress\n")
    print(pair_table(result.summary))
    if "samples" in result.summary:
        from ..toothpair.samples_report import samples_table

        sampled = result.summary["samples"]
        over = ("the same positions" if sampled["over"] == "cycle" else
                f"a whole revolution each ({sampled['positions_per_pair']} positions: the "
                "cycle's at every pitch of gear 1)")
        print(f"\nThe exact pair above; the pairs of its tolerance class over {over} (von "
              "Mises from the templates' surface estimate, as the samples' is read):\n")
        print(samples_table(sampled))
    if "sensitivities" in result.summary:
        from ..toothpair.sensitivity_report import sensitivity_table

        print("\nSensitivities: each stress's rate with each deviation of the teeth in mesh "
              "(the largest first):\n")
        print(sensitivity_table(result.summary["sensitivities"]))
    if "rating" in result.summary:
        from ..toothpair.rating_report import rating_table

        rating = result.summary["rating"]
        print(f"\nRated for a life: each level of the spectrum solved over the positions "
              f"({rating['solve_s']:.1f} s):\n")
        print(rating_table(rating))
    for k, v in files.items():
        print(f"{k:10s} {v}")
    if out is None:
        print("(no files written: --out DIR writes summary.json, VTU files and pictures)")
    print(f"wall {command_wall_s():.1f} s for the whole command")
    return 0


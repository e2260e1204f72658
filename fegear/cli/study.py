"""``fegear study``: a parameter study from a TOML file, on a local pool or a Dask cluster."""

from __future__ import annotations

import argparse
import sys

from ..errors import FegearError
from .args import add_inputs, workers_input
from .cache import add_switch, apply_switch

WORKERS = workers_input("local worker processes", "all cores")
#: refused cases listed one by one when a study starts; the rest are counted
SHOWN = 20


def add_parser(sub) -> None:
    p = sub.add_parser("study", help="run a parameter study (TOML file): table and plots")
    p.add_argument("file", help="study file (TOML), e.g. studies/paper_trends.toml")
    add_inputs(p, [WORKERS])
    p.add_argument("--scheduler", default=None,
                   help="run on this Dask distributed scheduler (e.g. tcp://host:8786) "
                        "instead of the local pool")
    p.add_argument("--out", default=None, help="output directory (default out/study/NAME)")
    p.add_argument("--retry-failed", action="store_true",
                   help="run the cases that failed before again (default: keep their record)")
    p.add_argument("--no-progress", action="store_true",
                   help="no progress bar (as fegear --quiet; it shows only on a terminal)")
    add_switch(p, default=True)


def run(a: argparse.Namespace) -> int:

    from ..files import check_dir
    from ..study import StudyInterrupted, load_study, run_study

    if a.workers is not None:
        if a.scheduler:
            raise FegearError("--workers sets the local pool; with --scheduler the cluster's "
                              "workers run the cases (leave --workers out)")
        WORKERS.check(a.workers)
    study = load_study(a.file)
    apply_switch(a, default=True)   # before the workers start: they inherit it
    out = check_dir(a.out or f"out/study/{study.name}")   # before the workers start

    refused = study.refused

    def started(found: int, todo: int) -> None:
        varied = f", varying {', '.join(study.varied)}" if study.varied else ""
        aside = f", {len(refused)} refused" if refused else ""
        lines = [f"{study.name}: {len(study.cases) + len(refused)} cases{varied} ({found} "
                 f"finished before, {todo} to compute{aside}); results in {out}"]
        lines += [f"refused: {r.describe(study.path)}" for r in refused[:SHOWN]]
        if len(refused) > SHOWN:
            lines.append(f"refused: {len(refused) - SHOWN} more (results.md and study.json "
                         "list them all)")
        print("\n".join(lines), file=sys.stderr, flush=True)

    try:
        report = run_study(study, out, workers=a.workers, scheduler=a.scheduler,
                           retry_failed=a.retry_failed,
                           progress=sys.stderr.isatty() and not (a.no_progress or a.quiet),
                           on_start=started)
    except StudyInterrupted as exc:
        print(f"fegear: {exc}", file=sys.stderr)
        return 128 + exc.signum
    md = report.files.get("md")
    if md is not None:
        print(md.read_text(), end="")
    aside = f", {report.refused} refused (listed under the table)" if report.refused else ""
    print(f"\n{report.cases + report.refused} cases: {report.found} found finished, "
          f"{report.computed} computed ({report.failed} failed){aside} in "
          f"{report.wall_s:.1f} s")
    for k, v in report.files.items():
        print(f"{k:12s} {v}")
    return 0

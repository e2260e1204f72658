"""``fegear bench``: run time against error, per pipeline stage, with CalculiX beside it."""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING

from ..checks import Input, number
from ..errors import ParameterError
from ..geometry.parameters import PAIR_INPUTS
from ..toothpair.inputs import QUALITY, SOLVE_INPUTS, check_torque
from .args import add_inputs, checked, given_values

if TYPE_CHECKING:
    from ..verify import BenchPlan

#: the bench's own inputs beside the pair's (its torque is the solve's row)
BENCH_INPUTS = (
    Input("repeat", int, 3, "repetitions (the best is kept)", low=1, high=100),
    Input("pair-quality", str, "standard", "quality of the estimate, cycle and scaling runs "
          "(the default of fegear solve)", choices=QUALITY),
    Input("cycle", int, 24, "positions in the benchmarked mesh cycle (0: skip)", low=0,
          high=360, limits="an integer 0 (skip) or 2 <= cycle <= 360"),
    Input("disk-levels", str, "2,4,8,16,32", "Hertz-case ladder: elements across b, "
          "comma-separated", limits="two or more numbers 1 <= n <= 200"),
    Input("pair-levels", str, "coarse,fast,standard,fine", "tooth-pair (ring model) ladder: "
          "quality levels, comma-separated", limits="two or more of " + " / ".join(QUALITY)),
    Input("sector-levels", str, None, "also the sector model at these levels, with CalculiX "
          "on its meshes (e.g. coarse,fast; minutes each)",
          limits="two or more of " + " / ".join(QUALITY) + " (with --contact-peer, one or "
          "more)", rule="none"),
    SOLVE_INPUTS["torque"],
    Input("scaling", str, "45,90,180", "teeth of gear 2 for the cost-growth runs, module "
          "scaled to keep the pitch radius (empty: skip)",
          limits="numbers of teeth 12 <= z2 <= 400, comma-separated, or none"),
    Input("study-cases", int, 6, "solves in the study-runner overhead benchmark (0: skip)",
          low=0, high=1000, limits="an integer 0 (skip) or 2 <= study-cases <= 1000"),
    Input("files", int, 5, "alternated pairs of the whole `fegear solve` without and with "
          "--out that time what its files add (0: skip)", low=0, high=50),
)
_ROW = {row.name: row for row in BENCH_INPUTS}


def add_parser(sub) -> None:
    p = sub.add_parser("bench", help="time the pipeline stages and print a table")
    add_inputs(p, PAIR_INPUTS, "pair")
    add_inputs(p, BENCH_INPUTS)
    p.add_argument("--paper-study", action="store_true",
                   help="also time studies/paper_trends.toml on 2 workers (about a minute)")
    p.add_argument("--tolerance-class", action="store_true",
                   help="also time fegear solve --grade 6 --samples 1000 --positions 24 on "
                        "the pair (about a minute on the baseline)")
    p.add_argument("--spectrum", action="store_true",
                   help="also time fegear solve --positions 24 with a 4-level --spectrum "
                        "against the cycle alone, 3 runs each (about half a minute)")
    p.add_argument("--face", action="store_true",
                   help="also time fegear solve across the face (--misalignment 8) against "
                        "the 2D pair, one position and 24, 3 runs each (about a minute)")
    p.add_argument("--revolution", action="store_true",
                   help="also time fegear solve over a revolution, one deviated pair's and "
                        "200 class-5 pairs', against one position (about three minutes)")
    p.add_argument("--search", action="store_true",
                   help="also time fegear optimize over a revolution, 200 trials of 50 "
                        "class-5 pairs (about 18 minutes)")
    p.add_argument("--no-peer", action="store_true",
                   help="do not run CalculiX beside the ladders even if ccx is installed")
    p.add_argument("--study-only", action="store_true",
                   help="run only the study-runner overhead benchmark")
    p.add_argument("--files-only", action="store_true",
                   help="run only what `fegear solve --out` adds to the solve: --files pairs "
                        "of the whole command without and with --out, alternated (about half "
                        "a minute)")
    p.add_argument("--contact-peer", action="store_true",
                   help="run only the contact-pressure comparison with CalculiX (an edge and a "
                        "flank-only case on the baseline pair at --sector-levels, default "
                        "coarse,fast; about 15 minutes; needs ccx)")
    p.add_argument("--sector", action="store_true",
                   help="only cross-check this design: solve it (one position, --torque, "
                        "--pair-quality) with the ring model and with the sector model, the "
                        "full-FE peer, and print both (standard: a minute or two; coarse: "
                        "seconds)")
    p.add_argument("--out", default="out/bench",
                   help="directory for bench.json and the plots (default out/bench)")
    p.add_argument("--history", default=None,
                   help="the history file this run is appended to and compared with (default: "
                        "bench_history.jsonl in --out; `make bench` keeps the repository's, "
                        "docs/bench/history.jsonl)")
    p.add_argument("--show-history", action="store_true",
                   help="only print the history (--history) as a table: a column a run")
    p.add_argument("--against", default=None, metavar="CHECKOUT",
                   help="only time the user's commands (solve, a cycle, relief, the paper "
                        "study, a 40-trial search) here and in the fegear checkout CHECKOUT "
                        "(with its .venv), alternately, --repeat times each, and print both "
                        "and their ratio (minutes)")


def _levels(name: str, text: str | None, allowed, least: int) -> list[str]:
    levels = [q.strip() for q in (text or "").split(",") if q.strip()]
    if ((text or "").strip() or least) and (len(levels) < least or any(q not in allowed
                                                                       for q in levels)):
        raise ParameterError(name, text, _ROW[name].range_text)
    return levels


def _numbers(name: str, text: str) -> list[float]:
    """The comma-separated numbers of option ``name``; text that is none is refused with
    the option's range."""
    values = [number(_read(x)) for x in text.split(",") if x.strip()]
    if any(v is None for v in values):
        raise ParameterError(name, text, _ROW[name].range_text)
    return values


def _read(text: str) -> object:
    try:
        return float(text)
    except ValueError:
        return text


def _skip_or(name: str, value: int, skip: bool = True) -> int:
    """A count that is 0 (skip, where ``skip``) or at least 2."""
    if value == 1 or value == 0 and not skip:
        raise ParameterError(name, value, _ROW[name].range_text)
    return value


def run(a: argparse.Namespace) -> int:
    from pathlib import Path

    from ..verify import run_bench

    def say(text: str) -> None:
        print(text, flush=True)

    if a.show_history:
        from ..verify.history import HISTORY, history_table, runs

        kept = runs(Path(a.history) if a.history else Path(a.out) / HISTORY)
        print(history_table(kept) if kept else "(no bench run kept there yet)")
        return 0
    if a.against:
        from ..verify.against import against_table, checkout, time_against

        there = checkout(a.against)
        repeat = checked(a, [_ROW["repeat"]])["repeat"]
        say(against_table(time_against(there, repeat), there))
        return 0
    run_bench(_plan(a), say=say)
    return 0


def _plan(a: argparse.Namespace) -> BenchPlan:
    """The bench's plan from its options, each checked (and --out) before any work."""
    from pathlib import Path

    from ..files import check_dir
    from ..geometry import admissible_pair
    from ..verify import BenchPlan

    own = checked(a, [row for row in BENCH_INPUTS if not row.limits or row.kind is int])
    cycle = _skip_or("cycle", own["cycle"])
    pair_levels = _levels("pair-levels", a.pair_levels, QUALITY, 2)
    # a ladder's extrapolation takes two levels or more; the contact comparison takes one
    sector_levels = _levels("sector-levels", a.sector_levels, QUALITY,
                            0 if not a.sector_levels else 1 if a.contact_peer else 2)
    disk_levels = _numbers("disk-levels", a.disk_levels)
    if len(disk_levels) < 2 or not all(1 <= n <= 200 for n in disk_levels):
        raise ParameterError("disk-levels", a.disk_levels, _ROW["disk-levels"].range_text)
    teeth = _numbers("scaling", a.scaling)
    if not all(float(z).is_integer() and 12 <= z <= 400 for z in teeth):
        raise ParameterError("scaling", a.scaling, _ROW["scaling"].range_text)
    study_cases = _skip_or("study-cases", own["study_cases"], skip=not a.study_only)
    given = given_values(a, PAIR_INPUTS)
    params = admissible_pair(given)
    material = {k: SOLVE_INPUTS[k].default for k in ("E", "face-width")}
    torque = check_torque(a.torque, material["E"], params.m, material["face-width"],
                          params.r1)
    out = check_dir(a.out)         # before any work: --sector writes nothing, the rest do
    only = ("study" if a.study_only else "contact-peer" if a.contact_peer
            else "sector" if a.sector else "files" if a.files_only else "")
    return BenchPlan(params=params, torque=torque, out=out, quality=a.pair_quality,
                     repeat=own["repeat"], cycle=cycle, disk_levels=tuple(disk_levels),
                     pair_levels=tuple(pair_levels), sector_levels=tuple(sector_levels),
                     scaling=tuple(int(z) for z in teeth), study_cases=study_cases,
                     pair_args=tuple(x for k, v in given.items() for x in (f"--{k}", f"{v}")),
                     peer=not a.no_peer, paper_study=a.paper_study,
                     tolerance_class=a.tolerance_class, spectrum=a.spectrum, face=a.face,
                     revolution=a.revolution, search=a.search,
                     files=own["files"], only=only,
                     history=None if a.history is None else Path(a.history))

"""``fegear bench``: run time against error, per pipeline stage, with CalculiX beside it."""

from __future__ import annotations

import argparse

from ..checks import require_range
from ..geometry.parameters import PAIR_INPUTS
from .args import add_inputs, input_values
from .hertz import number


def add_parser(sub) -> None:
    p = sub.add_parser("bench", help="time the pipeline stages and print a table")
    add_inputs(p, PAIR_INPUTS, "pair")
    p.add_argument("--repeat", type=int, default=3, help="repetitions (best is kept)")
    p.add_argument("--pair-quality", default="standard",
                   help="quality of the tooth-pair benchmark (coarse / fast / standard / fine)")
    p.add_argument("--cycle", type=int, default=24,
                   help="positions in the benchmarked mesh cycle (default 24; 0: skip)")
    p.add_argument("--disk-levels", default="2,4,8,16,32",
                   help="Hertz-case ladder: elements across b, comma-separated (>= 2)")
    p.add_argument("--pair-levels", default="coarse,fast,standard,fine",
                   help="tooth-pair ladder: quality levels, comma-separated (>= 2)")
    p.add_argument("--torque", type=float, default=200.0,
                   help="tooth-pair torque on gear 1 [N·m] (default 200)")
    p.add_argument("--no-peer", action="store_true",
                   help="do not run CalculiX beside the ladders even if ccx is installed")
    p.add_argument("--study-cases", type=int, default=6,
                   help="solves in the study-runner overhead benchmark (default 6; 0: skip)")
    p.add_argument("--study-only", action="store_true",
                   help="run only the study-runner overhead benchmark")
    p.add_argument("--out", default="out/bench",
                   help="directory for bench.json and bench.png (default out/bench)")


def run(a: argparse.Namespace) -> int:
    from ..errors import ParameterError
    from ..files import prepare_dir, write_json
    from ..geometry import admissible_pair
    from ..toothpair import QUALITY

    repeat = int(require_range("repeat", a.repeat, 1, 100))
    cycle = int(a.cycle)
    if cycle != 0:
        require_range("cycle", cycle, 2, 360)
    torque = require_range("torque", a.torque, 0.0, 1e4, lo_open=True, unit="N·m")
    if a.pair_quality not in QUALITY:
        raise ParameterError("pair_quality", a.pair_quality, " / ".join(QUALITY))
    pair_levels = [q.strip() for q in a.pair_levels.split(",")]
    if len(pair_levels) < 2 or any(q not in QUALITY for q in pair_levels):
        raise ParameterError("pair_levels", a.pair_levels,
                             "two or more of " + " / ".join(QUALITY) + ", comma-separated")
    disk_levels = [number("disk_levels", x) for x in a.disk_levels.split(",")]
    if len(disk_levels) < 2 or not all(1 <= n <= 200 for n in disk_levels):
        raise ParameterError("disk_levels", a.disk_levels,
                             "two or more numbers 1 <= elements across b <= 200")
    study_cases = int(a.study_cases)
    if study_cases != 0 or a.study_only:
        require_range("study_cases", study_cases, 2, 1000)
    params = admissible_pair(input_values(a, PAIR_INPUTS))
    if a.study_only:
        return _study_bench(params, study_cases)
    out = prepare_dir(a.out)
    from ..verify import (  # the FE stack, once every input is sound
        PEER_TARGET,
        disk_ladder,
        geometry_bench,
        ladder_json,
        ladder_png,
        ladder_table,
        ladder_targets,
        pair_bench,
        pair_ladder,
        peer_speedups,
    )
    print(geometry_bench(params, repeat))
    print()
    disks = disk_ladder(disk_levels, repeat, peer=not a.no_peer)
    print(ladder_table(disks))
    print()
    pair = pair_ladder(params, torque, pair_levels, peer=not a.no_peer)
    print(ladder_table(pair))
    print()
    targets = ladder_targets(disks, pair)
    for t in targets:
        print(f"* {t.line()}")
    for ladder in (disks, pair):
        for rung, ratio in peer_speedups(ladder):
            status = "met" if ratio >= PEER_TARGET else "MISSED"
            print(f"* {ladder.name.split(':')[0]}, `{rung.level}`: CalculiX / fegear = "
                  f"{ratio:.1f}× (target >= {PEER_TARGET:g}×: {status})")
    write_json(out / "bench.json", ladder_json((disks, pair), targets))
    ladder_png(out / "bench.png", (disks, pair), targets)
    print(f"\nbench.json, bench.png in {out}")
    if cycle:
        print()
        print(pair_bench(params, torque, quality=a.pair_quality, positions=cycle))
    if study_cases:
        print()
        _study_bench(params, study_cases)
    return 0


def _study_bench(params, cases: int) -> int:
    from ..verify import overhead_table, study_overhead

    print(overhead_table(study_overhead(params, cases, workers=1), workers=1))
    return 0

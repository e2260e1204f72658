"""Command line: ``fegear profile``, ``hertz``, ``solve``, ``study``, ``drive`` and ``bench``.

User errors (bad parameters, unwritable output) print one line ``fegear: error: …`` on stderr
and exit with code 2, without a traceback.
"""

from __future__ import annotations

import argparse
import json
import logging
import math
import sys

from .cli_drive import add_parsers as add_drive_parsers
from .cli_drive import cmd_drive
from .errors import FegearError
from .job import add_material_args, add_pair_args, add_solve_args, pair_params, prepare, run
from .params import require_range

EXIT_USAGE = 2


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> None:  # one line, no usage dump
        self.exit(EXIT_USAGE, f"fegear: error: {message}\n")


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="fegear", description=__doc__.splitlines()[0])
    parser.add_argument("-v", "--verbose", action="store_true", help="log progress")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)

    prof = sub.add_parser("profile", help="generate both tooth profiles and the clearance table")
    add_pair_args(prof)
    prof.add_argument("--chord-error", type=float, default=1e-4,
                      help="max chord error of the written polylines [mm] (default 1e-4)")
    prof.add_argument("--positions", type=int, default=16,
                      help="rolling positions scanned for the backlash (default 16)")
    prof.add_argument("--out", required=True, help="output directory")
    prof.add_argument("--json", action="store_true", help="print the summary as JSON")

    hz = sub.add_parser("hertz", help="FE line contact of two disks (or disk in bore) vs Hertz")
    hz.add_argument("--r1", type=float, default=10.0, help="disk 1 radius [mm] (default 10)")
    hz.add_argument("--r2", type=float, default=10.0,
                    help="disk 2 radius [mm]; negative = a bore holding disk 1 (default 10)")
    hz.add_argument("--load", type=float, default=1000.0, help="normal load [N] (default 1000)")
    add_material_args(hz, "thickness")
    hz.add_argument("--plane", choices=("stress", "strain"), default="stress",
                    help="plane assumption (default stress)")
    hz.add_argument("--quality", default="standard",
                    help="coarse / standard / fine = 4 / 8 / 16 elements across b, or a number")
    hz.add_argument("--penalty-factor", type=float, default=None,
                    help="penalty κ = factor·E*/h (default 300)")
    hz.add_argument("--out", default=None, help="write VTU files and summary.json here")
    hz.add_argument("--json", action="store_true", help="print the summary as JSON")

    sv = sub.add_parser("solve", help="tooth-pair FE solve: stresses, load sharing, stiffness")
    add_solve_args(sv)
    sv.add_argument("--out", required=True, help="output directory (VTU, PNG, summary.json)")
    sv.add_argument("--json", action="store_true", help="print the summary as JSON")

    st = sub.add_parser("study", help="run a parameter study (TOML file): table and plots")
    st.add_argument("file", help="study file (TOML), e.g. studies/paper_trends.toml")
    st.add_argument("--workers", type=int, default=None,
                    help="local worker processes (default: all cores)")
    st.add_argument("--scheduler", default=None,
                    help="run on this Dask distributed scheduler (e.g. tcp://host:8786) "
                         "instead of the local pool")
    st.add_argument("--out", default=None, help="output directory (default out/study/NAME)")
    st.add_argument("--retry-failed", action="store_true",
                    help="run the cases that failed before again (default: keep their record)")
    st.add_argument("--no-progress", action="store_true", help="no progress bar")

    dr = sub.add_parser("drive", help="drive level: ratios and efficiencies, bearing forces "
                                      "(seed 000), torsional dynamics from the mesh stiffness")
    add_drive_parsers(dr, _Parser)

    bench = sub.add_parser("bench", help="time the pipeline stages and print a table")
    add_pair_args(bench)
    bench.add_argument("--repeat", type=int, default=3, help="repetitions (best is kept)")
    bench.add_argument("--pair-quality", default="standard",
                       help="quality of the tooth-pair benchmark (coarse / fast / standard / fine)")
    bench.add_argument("--cycle", type=int, default=24,
                       help="positions in the benchmarked mesh cycle (default 24; 0: skip)")
    bench.add_argument("--disk-levels", default="2,4,8,16,32",
                       help="Hertz-case ladder: elements across b, comma-separated (>= 2)")
    bench.add_argument("--pair-levels", default="coarse,fast,standard,fine",
                       help="tooth-pair ladder: quality levels, comma-separated (>= 2)")
    bench.add_argument("--torque", type=float, default=200.0,
                       help="tooth-pair torque on gear 1 [N·m] (default 200)")
    bench.add_argument("--no-peer", action="store_true",
                       help="do not run CalculiX beside the ladders even if ccx is installed")
    bench.add_argument("--study-cases", type=int, default=6,
                       help="solves in the study-runner overhead benchmark (default 6; 0: skip)")
    bench.add_argument("--study-only", action="store_true",
                       help="run only the study-runner overhead benchmark")
    bench.add_argument("--out", default="out/bench",
                       help="directory for bench.json and bench.png (default out/bench)")
    return parser


def cmd_profile(a: argparse.Namespace) -> int:
    from .output import prepare_dir, write_json, write_points_csv
    from .pair import build_pair
    from .plot import pair_png

    params = pair_params(a)
    chord = require_range("chord_error", a.chord_error, 1e-7, 0.1, unit="mm")
    positions = int(require_range("positions", a.positions, 4, 360))
    out = prepare_dir(a.out)
    geo = build_pair(params, chord, positions)
    summary = geo.summary()
    files = {
        "gear1_csv": write_points_csv(out / "gear1.csv", geo.gear1),
        "gear2_csv": write_points_csv(out / "gear2.csv", geo.gear2),
        "png": pair_png(out / "pair.png", geo.gear1, geo.gear2, params.e, params.r0,
                        f"compound-cycloid pair: {params.describe()}",
                        zoom_half_width=4.0 * params.m),
    }
    summary["files"] = {k: str(v) for k, v in files.items()}
    write_json(out / "summary.json", summary)
    if a.json:
        print(json.dumps(summary, indent=2))
    else:
        print(_profile_table(geo))
        for k, v in files.items():
            print(f"{k:10s} {v}")
    return 0


def _profile_table(geo) -> str:
    rows = sorted(geo.contact.teeth, key=lambda t: abs(t.position_deg))[:7]
    rows.sort(key=lambda t: t.position_deg)

    def f(v):
        return "   none" if v is None else f"{v:8.3f}"

    lines = [f"gear 1 tip radius {geo.tip_radius:.6f} mm, root radius {geo.root_radius:.6f} mm",
             "", "clearance at β = 0 (µm of arc at r0; + = gear 1 turning counter-clockwise)",
             "| tooth | position [deg] |     + µm |     − µm |",
             "|------:|---------------:|---------:|---------:|"]
    for t in rows:
        lines.append(f"| {t.tooth:5d} | {t.position_deg:14.3f} | {f(t.plus_um)} | "
                     f"{f(t.minus_um)} |")
    if geo.backlash is not None:
        b = geo.backlash
        lines += ["", f"backlash over one mesh cycle: + {b.plus_um:.3f} µm, − {b.minus_um:.3f} µm"]
    if geo.contact.interference:
        worst = max(geo.contact.interference, key=lambda i: i.depth_um)
        lines += [f"INTERFERENCE: {len(geo.contact.interference)} teeth, worst tooth "
                  f"{worst.tooth} by {worst.depth_um:.3f} µm at ({worst.point[0]:.4f}, "
                  f"{worst.point[1]:.4f}) mm"]
    return "\n".join(lines)


def cmd_hertz(a: argparse.Namespace) -> int:
    import time

    from .disks import QUALITY, DiskCase, solve_disks, write_disk_outputs
    from .output import prepare_dir

    quality = a.quality if a.quality in QUALITY else _number(
        "quality", a.quality)
    kw = {} if a.penalty_factor is None else {"penalty_factor": a.penalty_factor}
    case = DiskCase(r1=a.r1, r2=a.r2, load=a.load, thickness=a.thickness, E=a.E, nu=a.nu,
                    plane=a.plane, quality=quality, **kw)
    out = prepare_dir(a.out) if a.out else None
    result = solve_disks(case)
    summary = result.summary()
    if out is not None:
        t0 = time.perf_counter()
        files = write_disk_outputs(result, out)
        result.timings_s["output"] = time.perf_counter() - t0
        summary = result.summary()
        summary["files"] = {k: str(v) for k, v in files.items()}
    if a.json:
        print(json.dumps(summary, indent=2))
    else:
        print(_hertz_table(result))
        if out is not None:
            for k, v in summary["files"].items():
                print(f"{k:10s} {v}")
    return 0


def _number(name: str, text: str) -> float:
    from .errors import ParameterError

    try:
        return float(text)
    except ValueError:
        raise ParameterError(name, text, "coarse / standard / fine or a number") from None


def _hertz_table(r) -> str:
    c, h = r.case, r.hertz
    kind = "disk in bore" if c.r2 < 0 else "two disks"
    lines = [f"{kind}: r1 {c.r1:g} mm, r2 {c.r2:g} mm, P {c.load:g} N, t {c.thickness:g} mm, "
             f"E {c.E:g} MPa, nu {c.nu:g}, plane {c.plane}, quality {c.quality}",
             "",
             "| quantity           |          FE |       Hertz |  FE − Hertz |",
             "|--------------------|------------:|------------:|------------:|",
             f"| p_max [MPa]        | {r.p_max:11.3f} | {h.p0:11.3f} | {r.p_error_pct:+10.3f}% |",
             f"| half-width b [mm]  | {r.half_width:11.6f} | {h.b:11.6f} | "
             f"{r.b_error_pct:+10.3f}% |",
             "",
             f"b/R* = {h.b_over_R:.4f} (R* = {h.R_star:.4g} mm; Hertz assumes b/R* << 1); "
             f"contact half-angle on disk 1 {math.degrees(r.half_width / c.r1):.1f}°",
             f"recovered surface normal stress at the contact: {r.surface_stress:.3f} MPa "
             f"({100 * (r.surface_stress / r.p_max - 1):+.2f}% vs FE p_max)",
             f"DOFs {r.dofs}, contact points {r.contact_points}, active-set iterations "
             f"{r.iterations}, max penetration {r.max_penetration * 1e3:.3g} µm "
             f"({r.max_penetration / r.half_width:.1e} b)",
             "",
             "| stage | time [s] |", "|-------|---------:|"]
    lines += [f"| {k} | {v:.3f} |" for k, v in r.timings_s.items()]
    lines.append(f"| total | {sum(r.timings_s.values()):.3f} |")
    return "\n".join(lines)


def cmd_solve(a: argparse.Namespace) -> int:
    from .output import prepare_dir
    from .pairout import cycle_table, pair_table

    job = prepare(a)
    result = run(job, prepare_dir(a.out))
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


def cmd_study(a: argparse.Namespace) -> int:
    import os

    from .study import StudyInterrupted, run_study
    from .studyfile import load_study

    if a.workers is not None:
        if a.scheduler:
            raise FegearError("--workers sets the local pool; with --scheduler the cluster's "
                              "workers run the cases (leave --workers out)")
        require_range("workers", a.workers, 1, 4 * (os.cpu_count() or 1))
    study = load_study(a.file)
    out = a.out or f"out/study/{study.name}"

    def started(found: int, todo: int) -> None:
        varied = f", varying {', '.join(study.varied)}" if study.varied else ""
        print(f"{study.name}: {len(study.cases)} cases{varied} ({found} finished before, "
              f"{todo} to compute); results in {out}", file=sys.stderr, flush=True)

    try:
        report = run_study(study, out, workers=a.workers, scheduler=a.scheduler,
                           retry_failed=a.retry_failed, progress=not a.no_progress,
                           on_start=started)
    except StudyInterrupted as exc:
        print(f"fegear: {exc}", file=sys.stderr)
        return 128 + exc.signum
    md = report.files.get("md")
    if md is not None:
        print(md.read_text(), end="")
    print(f"\n{report.cases} cases: {report.found} found finished, {report.computed} computed "
          f"({report.failed} failed) in {report.wall_s:.1f} s")
    for k, v in report.files.items():
        print(f"{k:12s} {v}")
    return 0


def cmd_bench(a: argparse.Namespace) -> int:
    from .bench import (
        PEER_TARGET,
        disk_ladder,
        geometry_bench,
        ladder_json,
        ladder_table,
        ladder_targets,
        pair_bench,
        pair_ladder,
        peer_speedups,
    )
    from .errors import ParameterError
    from .output import prepare_dir, write_json
    from .plot import ladder_png
    from .scene import QUALITY

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
    disk_levels = [_number("disk_levels", x) for x in a.disk_levels.split(",")]
    if len(disk_levels) < 2 or not all(1 <= n <= 200 for n in disk_levels):
        raise ParameterError("disk_levels", a.disk_levels,
                             "two or more numbers 1 <= elements across b <= 200")
    study_cases = int(a.study_cases)
    if study_cases != 0 or a.study_only:
        require_range("study_cases", study_cases, 2, 1000)
    params = pair_params(a)
    if a.study_only:
        return _study_bench(params, study_cases)
    out = prepare_dir(a.out)
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
    from .bench_study import overhead_table, study_overhead

    print(overhead_table(study_overhead(params, cases, workers=1), workers=1))
    return 0


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    a = parser.parse_args(argv)
    logging.basicConfig(level=logging.INFO if a.verbose else logging.WARNING,
                        format="%(levelname)s %(name)s: %(message)s")
    try:
        return {"profile": cmd_profile, "hertz": cmd_hertz, "solve": cmd_solve,
                "study": cmd_study, "drive": cmd_drive, "bench": cmd_bench}[a.command](a)
    except FegearError as exc:
        print(f"fegear: error: {exc}", file=sys.stderr)
        return EXIT_USAGE


if __name__ == "__main__":
    sys.exit(main())

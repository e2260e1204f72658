"""Command line: ``fegear profile``, ``fegear hertz``, ``fegear solve`` and ``fegear bench``.

User errors (bad parameters, unwritable output) print one line ``fegear: error: …`` on stderr
and exit with code 2, without a traceback.
"""

from __future__ import annotations

import argparse
import json
import logging
import math
import sys

from .errors import FegearError
from .params import PairParameters, require_range

EXIT_USAGE = 2


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> None:  # one line, no usage dump
        self.exit(EXIT_USAGE, f"fegear: error: {message}\n")


def _add_pair_args(p: argparse.ArgumentParser) -> None:
    g = p.add_argument_group("pair")
    g.add_argument("--m", type=float, default=2.0, help="module [mm] (default 2)")
    g.add_argument("--z2", type=int, default=45, help="internal gear teeth (default 45)")
    g.add_argument("--z1", type=int, default=44, help="external gear teeth (default 44)")
    g.add_argument("--h1", type=float, default=0.30, help="tooth-height coefficient (0.30)")
    g.add_argument("--f1", type=float, default=0.15, help="tooth-shape coefficient (0.15)")
    g.add_argument("--shift", type=float, default=0.0,
                   help="Δ1 negative shift [mm]: gear 1 generated at e + shift (default 0)")
    g.add_argument("--rotation", type=float, default=0.0,
                   help="Δ2 rotation modification of the generating tool [mm] (default 0)")
    g.add_argument("--tip-relief", type=float, default=None,
                   help="gear-1 radial tip clearance to the far side [mm] (default: = shift)")


def _add_material_args(p: argparse.ArgumentParser, thickness: str) -> None:
    p.add_argument("--thickness", type=float, default=5.0, help=f"{thickness} [mm] (default 5)")
    p.add_argument("--E", type=float, default=206000.0, help="Young's modulus [MPa] (206000)")
    p.add_argument("--nu", type=float, default=0.29, help="Poisson ratio (default 0.29)")


def _params(a: argparse.Namespace) -> PairParameters:
    """The pair, checked for an admissible geometry before any work or output starts."""
    from .admissible import check

    p = PairParameters(m=a.m, z2=a.z2, z1=a.z1, h1=a.h1, f1=a.f1, shift=a.shift,
                       rotation=a.rotation, tip_relief=a.tip_relief)
    check(p)
    return p


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="fegear", description=__doc__.splitlines()[0])
    parser.add_argument("-v", "--verbose", action="store_true", help="log progress")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)

    prof = sub.add_parser("profile", help="generate both tooth profiles and the clearance table")
    _add_pair_args(prof)
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
    _add_material_args(hz, "thickness")
    hz.add_argument("--plane", choices=("stress", "strain"), default="stress",
                    help="plane assumption (default stress)")
    hz.add_argument("--quality", default="standard",
                    help="coarse / standard / fine = 4 / 8 / 16 elements across b, or a number")
    hz.add_argument("--penalty-factor", type=float, default=None,
                    help="penalty κ = factor·E*/h (default 300)")
    hz.add_argument("--out", default=None, help="write VTU files and summary.json here")
    hz.add_argument("--json", action="store_true", help="print the summary as JSON")

    sv = sub.add_parser("solve", help="tooth-pair FE solve: stresses, load sharing, stiffness")
    _add_pair_args(sv)
    sv.add_argument("--torque", type=float, default=200.0, help="torque on gear 1 [N·m] (200)")
    sv.add_argument("--position", type=float, default=0.0,
                    help="rolling angle β of gear 2 [deg] (default 0)")
    sv.add_argument("--positions", type=int, default=None,
                    help="solve N rolling angles across one tooth pitch from --position on one "
                         "mesh; writes cycle.csv and cycle.png")
    _add_material_args(sv, "face width")
    sv.add_argument("--quality", default="standard", help="coarse / fast / standard / fine")
    sv.add_argument("--tip-round", type=float, default=None,
                    help="gear-1 tip-edge round radius [mm] (default 0.125 m)")
    sv.add_argument("--rim1", type=float, default=None,
                    help="gear-1 rim below the roots, to the bore [mm] (default 3 m)")
    sv.add_argument("--rim2", type=float, default=None,
                    help="gear-2 rim beyond the roots, to the fixed rim [mm] (default 3 m)")
    sv.add_argument("--extra-teeth", type=int, default=2,
                    help="unloaded teeth meshed beyond the paired ones on each side (default 2)")
    sv.add_argument("--extra-pairs", type=int, default=0,
                    help="pair this many more teeth on each side than the closure needs "
                         "(default 0; a safety check)")
    sv.add_argument("--penalty-factor", type=float, default=None,
                    help="penalty κ = factor·E*/h (default 1000; h the local facet length)")
    sv.add_argument("--no-estimate", action="store_true",
                    help="skip the second mesh level (no discretisation-error estimate)")
    sv.add_argument("--out", required=True, help="output directory (VTU, PNG, summary.json)")
    sv.add_argument("--json", action="store_true", help="print the summary as JSON")

    bench = sub.add_parser("bench", help="time the pipeline stages and print a table")
    _add_pair_args(bench)
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
    bench.add_argument("--out", default="out/bench",
                       help="directory for bench.json and bench.png (default out/bench)")
    return parser


def cmd_profile(a: argparse.Namespace) -> int:
    from .output import prepare_dir, write_json, write_points_csv
    from .pair import build_pair
    from .plot import pair_png

    params = _params(a)
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
    import time

    from .output import prepare_dir
    from .pairout import (
        cycle_rows,
        cycle_summary,
        cycle_table,
        pair_summary,
        pair_table,
        second_level_estimate,
        write_cycle_outputs,
        write_pair_outputs,
    )
    from .profile import Gear1Profile
    from .toothpair import SolveCase, cycle_positions, solve_positions

    t0 = time.perf_counter()
    kw = {} if a.penalty_factor is None else {"penalty_factor": a.penalty_factor}
    position = require_range("position", a.position, -180.0, 180.0, unit="deg")
    n = 1 if a.positions is None else int(require_range("positions", a.positions, 2, 360))
    case = SolveCase(_params(a), torque=a.torque, beta=math.radians(position),
                     thickness=a.thickness, E=a.E, nu=a.nu, quality=a.quality,
                     rim1=a.rim1, rim2=a.rim2, extra_teeth=a.extra_teeth,
                     extra_pairs=a.extra_pairs, tip_round=a.tip_round, **kw)
    out = prepare_dir(a.out)
    profile = Gear1Profile(case.params)
    betas = (case.beta,) if n == 1 else cycle_positions(case.beta, n, case.params.z2)
    sols = solve_positions(case, betas, profile)
    cycle_s = time.perf_counter() - t0
    # pictures, VTUs and the error estimate at the position of the largest gear-1 root stress
    sol = max(sols, key=lambda s: s.root_stress[0])
    estimate, other = (None, None) if a.no_estimate else second_level_estimate(sol, profile)
    summary = pair_summary(sol, estimate, time.perf_counter() - t0, other)
    files, rows = {}, None
    if n > 1:
        rows = cycle_rows(sols)
        summary["cycle"] = {"positions": n, "solve_s": cycle_s, **cycle_summary(rows),
                            "rows": rows}
        i = summary["inputs"]
        files.update(write_cycle_outputs(
            rows, out, f"m {i['m']:g}, h1 {i['h1']:g}, f1 {i['f1']:g}, T {i['torque_Nm']:g} "
                       f"N·m, {n} positions, quality {i['quality']}"))
    files.update(write_pair_outputs(sol, out, {**summary, "files": {
        k: str(v) for k, v in files.items()}}))
    if a.json:
        print(json.dumps({**summary, "files": {k: str(v) for k, v in files.items()}}, indent=2))
    else:
        if rows:
            print(cycle_table(rows))
            print(f"\n{n} positions on one mesh in {cycle_s:.1f} s; the details below are at "
                  f"the position of the largest gear-1 root stress\n")
        print(pair_table(summary))
        for k, v in files.items():
            print(f"{k:10s} {v}")
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
    params = _params(a)
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
    return 0


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    a = parser.parse_args(argv)
    logging.basicConfig(level=logging.INFO if a.verbose else logging.WARNING,
                        format="%(levelname)s %(name)s: %(message)s")
    try:
        return {"profile": cmd_profile, "hertz": cmd_hertz, "solve": cmd_solve,
                "bench": cmd_bench}[a.command](a)
    except FegearError as exc:
        print(f"fegear: error: {exc}", file=sys.stderr)
        return EXIT_USAGE


if __name__ == "__main__":
    sys.exit(main())

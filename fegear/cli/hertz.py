"""``fegear hertz``: the FE core on two disks (or a disk in a bore) against Hertz."""

from __future__ import annotations

import argparse
import json
import math

from ..fe.material import MATERIAL_INPUTS, PLANE_MODES
from ..verify.disk_inputs import DISK_INPUTS
from .args import add_inputs


def add_parser(sub) -> None:
    p = sub.add_parser("hertz", help="FE line contact of two disks (or disk in bore) vs Hertz")
    add_inputs(p, DISK_INPUTS[:3])
    add_inputs(p, MATERIAL_INPUTS)
    p.add_argument("--plane", choices=PLANE_MODES, default="stress",
                   help="plane assumption (default stress)")
    add_inputs(p, DISK_INPUTS[3:])
    p.add_argument("--out", default=None, help="write VTU files and summary.json here")
    p.add_argument("--json", action="store_true", help="print the summary as JSON")


def run(a: argparse.Namespace) -> int:
    from ..files import check_dir, prepare_dir
    from ..timing import Stopwatch
    from ..verify import DISK_QUALITY, DiskCase

    quality = a.quality if a.quality in DISK_QUALITY else _number(a.quality)
    case = DiskCase(r1=a.r1, r2=a.r2, load=a.load, thickness=a.face_width, E=a.E, nu=a.nu,
                    plane=a.plane, quality=quality, penalty_factor=a.penalty_factor)
    out = None if a.out is None else check_dir(a.out)
    from ..verify import solve_disks, write_disk_outputs  # the FE stack, once the case is sound
    result = solve_disks(case)
    summary = result.summary()
    if out is not None:
        out = prepare_dir(out)
        watch = Stopwatch()
        files = write_disk_outputs(result, out)
        result.timings_s["output"] = watch.s
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


def _number(text: str) -> float | str:
    """A number of elements as typed, read as a number where it is one (else the text, for
    the case to refuse with the range)."""
    try:
        return float(text)
    except ValueError:
        return text


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

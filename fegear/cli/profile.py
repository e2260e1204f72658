"""``fegear profile``: both tooth profiles, the clearance table and the backlash."""

from __future__ import annotations

import argparse
import json

from ..checks import require_range
from ..geometry.parameters import PAIR_INPUTS
from .args import add_inputs, given_values


def add_parser(sub) -> None:
    p = sub.add_parser("profile", help="generate both tooth profiles and the clearance table")
    add_inputs(p, PAIR_INPUTS, "pair")
    p.add_argument("--chord-error", type=float, default=1e-4,
                   help="max chord error of the written polylines [mm] (default 1e-4)")
    p.add_argument("--positions", type=int, default=16,
                   help="rolling positions scanned for the backlash (default 16)")
    p.add_argument("--out", default=None, help="output directory for gear1.csv, gear2.csv, "
                   "pair.png and summary.json (default: none, the table only)")
    p.add_argument("--json", action="store_true", help="print the summary as JSON")


def run(a: argparse.Namespace) -> int:
    from ..files import check_dir, prepare_dir, write_json, write_points_csv
    from ..geometry import admissible_pair

    params = admissible_pair(given_values(a, PAIR_INPUTS))
    from ..geometry import gear1_profile  # the envelope needs scipy

    gear1_profile(params)   # a relief that does not fit is refused before any output
    chord = require_range("chord_error", a.chord_error, 1e-7, 0.1, unit="mm")
    positions = int(require_range("positions", a.positions, 4, 360))
    out = None if a.out is None else check_dir(a.out)
    from ..geometry import build_geometry, pair_png  # the envelope needs scipy
    geo = build_geometry(params, chord, positions)
    summary = geo.summary()
    if out is None:
        print(json.dumps(summary, indent=2) if a.json else _profile_table(geo))
        return 0
    out = prepare_dir(out)
    files = {
        "gear1_csv": write_points_csv(out / "gear1.csv", geo.gear1, None if geo.relief_depth
                                      is None else {"relief_um": geo.relief_depth * 1e3}),
        "gear2_csv": write_points_csv(out / "gear2.csv", geo.gear2),
        "png": pair_png(out / "pair.png", geo.gear1, geo.gear2, params.e, params.r0,
                        f"compound-cycloid pair: {params.describe()}",
                        zoom_half_width=6.5 * params.m, relief=geo.relief_chart,
                        teeth=[(t.tooth, t.position_deg) for t in geo.contact.teeth],
                        tip_radius=geo.tip_radius),
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

    lines = [f"gear 1 tip radius {geo.tip_radius:.6f} mm, root radius {geo.root_radius:.6f} mm"]
    for side, c in zip(("first", "second"), geo.relief_chart):
        lines.append(f"tip relief, {side} flank: {c['corner_depth_um']:.3f} µm at the tip corner "
                     f"(r {c['corner_radius_mm']:.4f} mm), from r {c['start_radius_mm']:.4f} mm, "
                     f"{c['extent_mm']:.4f} mm along the flank before the conjugate tip end, "
                     f"{geo.params.relief_shape}")
    lines += ["", "clearance at β = 0 (µm of arc at r0; + = gear 1 turning counter-clockwise)",
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

"""``fegear profile``: both tooth profiles, the clearance table and the backlash."""

from __future__ import annotations

import argparse
import json

from ..checks import Input
from ..geometry.parameters import PAIR_INPUTS
from ..toothpair.inputs import DEVIATION_INPUTS, SOLVE_INPUTS
from .args import add_inputs, checked, given_values

#: the command's own inputs (the pair's are :data:`~fegear.geometry.PAIR_INPUTS`)
PROFILE_INPUTS = (
    Input("chord-error", float, 1e-4, "max chord error of the written polylines and drawings",
          "mm", low=1e-7, high=0.1),
    Input("positions", int, 16, "rolling positions scanned for the backlash", low=4,
          high=360),
    Input("map-size", int, 21, "designs along each axis of --map", low=5, high=101),
    Input("step", bool, False, "with --out, also write gear1.step and gear2.step: each gear "
          "extruded by --face-width as a solid of gmsh's OpenCASCADE kernel (about 2 s)"),
)
#: the drawn parts' bodies, as a solve takes them (docs/geometry.md, "Drawings for manufacture")
BODY_INPUTS = tuple(SOLVE_INPUTS[name] for name in ("face-width", "tip-round", "rim1", "rim2"))


def add_parser(sub) -> None:
    p = sub.add_parser("profile", help="generate both tooth profiles and the clearance table")
    add_inputs(p, PAIR_INPUTS, "pair")
    add_inputs(p, PROFILE_INPUTS[:2])
    p.add_argument("--out", default=None, help="output directory for gear1.csv, gear2.csv, "
                   "the drawings gear1.dxf and gear2.dxf, pair.png and summary.json "
                   "(default: none, the table only)")
    p.add_argument("--json", action="store_true", help="print the summary as JSON")
    p.add_argument("--map", default=None, metavar="X,Y",
                   help="instead, map where the design is admissible over two inputs (the "
                        "others as given) and what bounds it, e.g. h1,f1; spans may be given "
                        "as h1=0.1:0.8,f1=0:0.4 (default spans: h1 0.05-1, f1 0-0.6, the "
                        "input's range for the others); with --out writes map.png, "
                        "map_grid.csv and map_edges.csv")
    add_inputs(p, PROFILE_INPUTS[2:3])
    add_inputs(p, (*PROFILE_INPUTS[3:], *BODY_INPUTS), "drawings (with --out: gear1.dxf, "
               "gear2.dxf, the bodies a solve takes)")
    add_inputs(p, DEVIATION_INPUTS, "deviations (with --out: deviations.png draws them, "
                                    "gear1_deviated.dxf and gear2_deviated.dxf carry them)")


def run(a: argparse.Namespace) -> int:
    from ..errors import FegearError
    from ..files import check_dir, prepare_dir, write_json, write_points_csv
    from ..geometry import admissible_pair

    own = checked(a, PROFILE_INPUTS)
    if a.map is not None:
        drawn = [row.name for row in (*PROFILE_INPUTS[3:], *BODY_INPUTS)
                 if row.dest in getattr(a, "typed", ())]
        if drawn:
            raise FegearError(f"--{drawn[0]}: not with --map (a map draws no part; the "
                              "drawings are written without --map)")
        return _map(a, own["map_size"])
    params = admissible_pair(given_values(a, PAIR_INPUTS))
    chord, positions = own["chord_error"], own["positions"]
    deviations = _deviations(a, params)
    body = _body(a, params)
    if own["step"] and a.out is None:
        raise FegearError("--step: with --out DIR (the files are written there)")
    out = None if a.out is None else check_dir(a.out)
    from ..geometry import build_geometry, pair_png  # the envelope needs scipy
    geo = build_geometry(params, chord, positions)
    summary = geo.summary()
    if out is None:
        print(json.dumps(summary, indent=2) if a.json else _profile_table(geo))
        return 0
    outlines = _outlines(params, chord, body, deviations)
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
    if deviations:
        from ..geometry import gear1_profile
        from ..geometry.deviation_plot import deviations_png
        from ..toothpair.present.tables import deviations_words

        summary["deviations"] = deviations.summary()
        files["deviations_png"] = deviations_png(
            out / "deviations.png", geo.gear1, geo.gear2, params, gear1_profile(params),
            deviations,
            f"deviations: {deviations_words(deviations.summary())}")
    files.update(_drawings(out, outlines, body, own["step"], params.describe()))
    summary["drawings"] = _drawings_summary(outlines, body, own["step"])
    summary["files"] = {k: str(v) for k, v in files.items()}
    write_json(out / "summary.json", summary)
    if a.json:
        print(json.dumps(summary, indent=2))
    else:
        print(_profile_table(geo))
        for k, v in files.items():
            print(f"{k:10s} {v}")
    return 0


def _deviations(a: argparse.Namespace, params):
    """The deviations the options give, checked against the pair's teeth."""
    from ..geometry import deviations_of

    values = given_values(a, DEVIATION_INPUTS)
    for row in DEVIATION_INPUTS:    # the numbers' ranges; the texts are read by deviations_of
        if row.kind is not str and row.name in values:
            values[row.name] = row.check(values[row.name])
    return deviations_of(values, params.z1, params.z2)


def _body(a: argparse.Namespace, params) -> dict:
    """The drawn parts' face width, gear 1's tip round and the bore and rim radii (mm),
    checked and defaulted as ``fegear solve`` takes them (a round that does not fit is refused
    with the largest that does; the rims by :class:`~fegear.toothpair.SolveCase`)."""
    from ..toothpair import SolveCase, tip_round_of
    from ..toothpair.inputs import torque_limit

    for row in BODY_INPUTS:              # the static ranges first: they answer at once
        if not row.limits:
            row.check(getattr(a, row.dest), row.name)
    width = a.face_width
    # a drawing carries no load: the case's torque at its limit passes its check
    case = SolveCase(params, torque=torque_limit(SOLVE_INPUTS["E"].default, params.m, width,
                                                 params.r1),
                     thickness=width, rim1=a.rim1, rim2=a.rim2,
                     tip_round=tip_round_of(params, a.tip_round))
    rim1, rim2 = case.rims
    return {"face_width": width, "tip_round": case.edge_radius,
            "bore": case.root_radius1 - rim1, "rim": params.r0 + 2 * params.e1 + rim2}


def _outlines(params, chord: float, body: dict, deviations) -> dict:
    """The drawn outlines (name → :class:`~fegear.geometry.Outline`): each gear's exact one,
    and with deviations those of the gears they move."""
    from ..geometry import NO_DEVIATIONS, gear1_outline, gear2_outline

    def both(devs, suffix):
        out = {}
        if not suffix or devs.teeth(1) or devs.runout1.fr:
            out[f"gear1{suffix}"] = gear1_outline(params, chord, body["tip_round"],
                                                  body["bore"], devs)
        if not suffix or devs.teeth(2) or devs.runout2.fr:
            out[f"gear2{suffix}"] = gear2_outline(params, chord, body["rim"], devs)
        return out

    return {**both(NO_DEVIATIONS, ""), **(both(deviations, "_deviated") if deviations else {})}


def _drawings(out, outlines: dict, body: dict, step: bool, title: str) -> dict:
    """Write each outline as DXF and, with ``step``, as a STEP solid of the face width."""
    from ..geometry import write_dxf

    files = {}
    for name, outline in outlines.items():
        files[f"{name}_dxf"] = write_dxf(out / f"{name}.dxf", outline, title)
    if step:
        from ..fe import Circle, Segment, write_step

        for name, outline in outlines.items():
            teeth = [Segment(f"run {k}", run) for k, run in enumerate(outline.runs())]
            circle = Circle(outline.circle)
            files[f"{name}_step"] = (
                write_step(out / f"{name}.step", teeth, body["face_width"], holes=[circle])
                if outline.gear == 1 else
                write_step(out / f"{name}.step", circle, body["face_width"], holes=[teeth]))
    return files


def _drawings_summary(outlines: dict, body: dict, step: bool) -> dict:
    """What the drawings are: their tolerance, frame, bodies and the deviations they carry."""
    out = {"chord_error_um": next(iter(outlines.values())).chord_error * 1e3,
           "frame": "each gear about its own axis at the origin, as at β = 0 (mm)",
           "tip_round_mm": body["tip_round"], "gear1_bore_radius_mm": body["bore"],
           "gear2_rim_radius_mm": body["rim"], "deviated": sorted(
               name.split("_")[0] for name in outlines if name.endswith("_deviated"))}
    if step:
        out["face_width_mm"] = body["face_width"]
    return out


def _profile_table(geo) -> str:
    rows = sorted(geo.contact.teeth, key=lambda t: abs(t.position_deg))[:7]
    rows.sort(key=lambda t: t.position_deg)

    def f(v):
        return "   none" if v is None else f"{v:z8.3f}"

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
        lines += ["", f"backlash over one mesh cycle: + {b.plus_um:z.3f} µm, "
                      f"− {b.minus_um:z.3f} µm"]
    if geo.contact.interference:
        worst = max(geo.contact.interference, key=lambda i: i.depth_um)
        lines += [f"INTERFERENCE: {len(geo.contact.interference)} teeth, worst tooth "
                  f"{worst.tooth} by {worst.depth_um:.3f} µm at ({worst.point[0]:.4f}, "
                  f"{worst.point[1]:.4f}) mm"]
    return "\n".join(lines)


#: the seed paper's study ranges (its Tables 5 and 6), outlined on an h1-f1 map
PAPER_BOX = ((0.2, 0.4), (0.1, 0.2), "the seed paper's ranges")
#: the inputs a map can span
MAPPED = ("h1", "f1", "shift", "rotation", "tip-clearance", "relief", "relief-extent")


def _map(a: argparse.Namespace, size: int) -> int:
    """``fegear profile --map X,Y``: the design-space map and its tables."""
    import os

    from .. import progress
    from ..files import check_dir, prepare_dir, write_csv
    from ..geometry.plot import map_png
    from ..geometry.space import design_map, map_span, map_tables
    from ..running import pool_or_serial

    (x, x_span), (y, y_span) = _map_axes(a.map)
    values = given_values(a, PAIR_INPUTS)
    x_span, y_span = x_span or map_span(x, values), y_span or map_span(y, values)
    out = None if a.out is None else check_dir(a.out)
    progress.plan(size)

    def rows(fn, args):
        # the rows on two spawned workers (where there are two cores), said as each arrives
        with pool_or_serial(min(2, os.cpu_count() or 1)) as executor:
            for k, task in enumerate([executor.submit(fn, x) for x in args]):
                row = task.result()
                progress.stage(f"{y} = {row.y:.4g} ({k + 1} of {size})")
                yield row

    dm = design_map(values, x, y, size, x_span, y_span, rows=rows)
    head, grid, edge_head, edges = map_tables(dm)
    table = _edges_table(dm)
    if out is None:
        print(table)
        print("(no files written: --out DIR writes map.png, map_grid.csv, map_edges.csv)")
        return 0
    out = prepare_dir(out)
    others = ", ".join(f"{k} {v:g}" for k, v in values.items() if k not in (x, y))
    here = (values.get(x, _default(x, values)), values.get(y, _default(y, values)))
    files = {
        "png": map_png(out / "map.png", dm, f"admissible designs over {x} and {y}"
                       + (f" at {others}" if others else " (the seed paper's pair otherwise)"),
                       here=here, here_label="this design" if values else
                       "the seed paper's pair", box=PAPER_BOX if (x, y) == ("h1", "f1") else
                       None),
        "grid_csv": write_csv(out / "map_grid.csv", head, grid),
        "edges_csv": write_csv(out / "map_edges.csv", edge_head, edges),
    }
    print(table)
    for k, v in files.items():
        print(f"{k:10s} {v}")
    return 0


def _map_axes(text: str) -> list[tuple[str, tuple[float, float] | None]]:
    """--map's two inputs, each with its span (lo, hi) where given, else None."""
    from ..errors import ParameterError

    axes = []
    for part in text.split(","):
        name, _, span = part.partition("=")
        name = name.strip()
        if name not in MAPPED:
            raise ParameterError("map", text, "two of " + ", ".join(MAPPED) + ", as X,Y or "
                                 "X=lo:hi,Y=lo:hi")
        try:
            bounds = tuple(float(v) for v in span.split(":")) if span else None
        except ValueError:
            bounds = ()
        if bounds is not None and (len(bounds) != 2 or not bounds[0] < bounds[1]):
            raise ParameterError("map", text, f"a span {name}=lo:hi with lo < hi")
        axes.append((name, bounds))
    if len(axes) != 2 or axes[0][0] == axes[1][0]:
        raise ParameterError("map", text, "two different inputs, as X,Y (e.g. h1,f1)")
    return axes


def _default(name: str, values: dict) -> float:
    """The value input ``name`` takes at ``values`` (its default, or its default rule)."""
    from dataclasses import asdict

    from ..geometry.admissible import resolve

    p = resolve(values)
    return p.radial_tip_clearance if name == "tip-clearance" else asdict(p)[name.replace(
        "-", "_")]


def _edges_table(dm) -> str:
    lines = [f"admissible {dm.x} at each {dm.y} (the edges a refusal states, the reason past "
             "each)", f"| {dm.y:>8s} | {dm.x + ' from':>12s} | {'reason below':>14s} | "
             f"{dm.x + ' to':>12s} | {'reason above':>14s} |",
             "|---------:|-------------:|---------------:|-------------:|---------------:|"]
    for r in reversed(dm.rows):
        lo = "none" if r.lower is None else f"{r.lower:.4f}"
        hi = "none" if r.upper is None else f"{r.upper:.4f}"
        lines.append(f"| {r.y:8.4f} | {lo:>12s} | {r.lower_reason or '-':>14s} | {hi:>12s} | "
                     f"{r.upper_reason or '-':>14s} |")
    return "\n".join(lines)

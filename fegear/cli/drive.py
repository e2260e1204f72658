"""``fegear drive``: ratios and efficiencies, seed 000's bearing forces, the lumped model."""

from __future__ import annotations

import argparse
import json
import math

from ..checks import Input, require_range
from ..drive.inputs import BEARING_INPUTS, DYNAMICS_INPUTS, RATIO_INPUTS
from ..drive.reducer_inputs import REDUCER_INPUTS
from ..errors import ParameterError
from ..toothpair.inputs import QUALITY
from .args import Parser, add_inputs, checked

#: trains of ``fegear drive ratio`` and the order of their --teeth
TRAINS = {"ngw": ("za", "zb"), "nn": ("zb", "zc", "zd", "ze"), "khv": ("zb", "zc"),
          "internal": ("z1", "z2")}


def add_parser(sub) -> None:
    drive = sub.add_parser("drive", help="drive level: ratios and efficiencies, bearing forces "
                                          "(seed 000), torsional dynamics from the mesh stiffness, "
                                          "seed 003's reducer")
    sub = drive.add_subparsers(dest="drive_command", required=True, parser_class=Parser,
                               metavar="{ratio,bearings,dynamics,reducer}")
    r = sub.add_parser("ratio", help="ratio and mesh efficiency of a planetary train")
    r.add_argument("--train", required=True, choices=[*TRAINS, "2kh"],
                   help="ngw (teeth za,zb), nn (zb,zc,zd,ze), khv (zb,zc), internal (z1,z2), "
                        "2kh (give --i-ab-h)")
    r.add_argument("--teeth", default=None, help="tooth numbers, comma-separated (see --train)")
    add_inputs(r, RATIO_INPUTS)
    r.add_argument("--json", action="store_true", help="print JSON")

    b = sub.add_parser("bearings", help="seed 000: eccentric-bearing forces and support "
                                        "reactions of the three-ring reducer")
    add_inputs(b, BEARING_INPUTS, "the reducer (the paper's example)")
    add_inputs(b, [STEP])
    b.add_argument("--json", action="store_true", help="print the summary as JSON")
    b.add_argument("--out", default=None, help="write bearings.json, .csv and .png here")

    d = sub.add_parser("dynamics", help="torsional two-inertia model driven by the mesh "
                                        "stiffness of `fegear solve --positions N`")
    d.add_argument("--stiffness", required=True, help="mesh_stiffness.json of a solve cycle")
    add_inputs(d, DYNAMICS_INPUTS[:2])
    d.add_argument("--spring", choices=("tangent", "secant"), default="tangent",
                   help="the mesh spring of the vibration about the static state: tangent "
                        "dT/dθ at the load (the linearised model's; default) or secant T/δ "
                        "(the static state is the secant's either way)")
    add_inputs(d, DYNAMICS_INPUTS[2:])
    d.add_argument("--speeds", default=None,
                   help="gear-1 speeds [r/min]: a list 500,1000 or a range lo:hi:count "
                        "(default: 60 speeds up to a mesh frequency of 1.5 f_n)")
    d.add_argument("--json", action="store_true", help="print the summary as JSON")
    d.add_argument("--out", default=None, help="write dynamics.json, .csv and .png here")


    _add_reducer(sub)


#: the crank-angle grid of ``fegear drive bearings``
STEP = Input("step", float, 1.0, "crank-angle grid (the paper used 1)", "deg", low=0.001,
             high=30.0)
#: ``fegear drive reducer``'s own inputs beside the model's (:data:`~fegear.drive.
#: reducer_inputs.REDUCER_INPUTS`)
REDUCER_RUN = (
    Input("plates", int, 3, "the build whose mode shapes are drawn and whose Campbell "
          "crossings are printed: 1, 2 or 3 plates (all three are solved)", low=1, high=3),
    Input("modes", int, 10, "natural frequencies per build", low=1, high=60),
    Input("mesh-stiffness", str, "table", "table (Table 1's constant, 4.97e8 N/m), fe "
          "(fegear's mean tangent stiffness of the compound-cycloid pair of the same teeth, "
          "module, plate width and output torque), a mesh_stiffness.json, or N/m",
          limits="table / fe / a mesh_stiffness.json / 0 < mesh-stiffness N/m"),
    Input("fe-quality", str, "coarse", "mesh quality of --mesh-stiffness fe", choices=QUALITY),
    Input("fe-positions", int, 12, "positions of --mesh-stiffness fe's mesh cycle", low=2,
          high=96),
)


def _add_reducer(sub) -> None:
    r = sub.add_parser("reducer", help="seed 003: natural frequencies and unbalance response "
                                       "of the three-axis internal-gear reducer (1, 2, 3 plates)")
    add_inputs(r, REDUCER_RUN)
    r.add_argument("--speeds", default=None,
                   help="crank speeds of the response [r/min]: 500,1000 or lo:hi:count "
                        "(default: 60 up to 1.5× the working speed)")
    add_inputs(r, REDUCER_INPUTS, "the reducer (seed 003's Table 1)")
    r.add_argument("--json", action="store_true", help="print the summary as JSON")
    r.add_argument("--out", default=None, help="write reducer.json, frequencies.csv, "
                                               "response.csv and the pictures here")


def run(a: argparse.Namespace) -> int:
    return {"ratio": _ratio, "bearings": _bearings, "dynamics": _dynamics,
            "reducer": _reducer}[a.drive_command](a)


def _reducer(a: argparse.Namespace) -> int:
    from ..drive.reducer_inputs import ReducerInputs
    from ..drive.reducer_report import (
        mesh_source,
        public,
        reducer_summary,
        reducer_table,
        write_reducer,
    )
    from ..files import check_dir, prepare_dir

    own = checked(a, REDUCER_RUN)
    inputs = ReducerInputs(**{row.dest: getattr(a, row.dest) for row in REDUCER_INPUTS})
    speeds = None if a.speeds is None else _speeds(a.speeds)
    if speeds is not None and len(speeds) > 2000:
        raise ParameterError("speeds", a.speeds, "at most 2000 speeds")
    out = None if a.out is None else check_dir(a.out)
    from ..fe import blas_threads

    with blas_threads():   # its eigenproblems as the FE solves: OpenBLAS's threads cost more
        mesh = mesh_source(a.mesh_stiffness, inputs, a.fe_quality, own["fe_positions"])
        summary = reducer_summary(inputs, mesh, own["modes"], speeds)
    files = write_reducer(prepare_dir(out), summary, own["plates"]) if out is not None else {}
    if a.json:
        print(json.dumps({**public(summary), "files": {k: str(v) for k, v in files.items()}},
                         indent=2))
    else:
        print(reducer_table(summary, own["plates"]))
        for k, v in files.items():
            print(f"{k:15s} {v}")
    return 0


def _ratio(a: argparse.Namespace) -> int:
    from .. import drive
    from ..drive import ratio_table

    checked(a, RATIO_INPUTS[1:])      # the ratio: by the train it gives (two_kh)
    if a.train == "2kh":
        if a.i_ab_h is None:
            raise ParameterError("i_ab_h", None, "a carrier-fixed ratio (--i-ab-h) for 2kh")
        if a.teeth is not None:
            raise ParameterError("teeth", a.teeth, "not with --train 2kh (give --i-ab-h)")
        r = drive.two_kh(a.i_ab_h)
    else:
        if a.i_ab_h is not None:
            raise ParameterError("i_ab_h", a.i_ab_h, "only with --train 2kh (the other trains "
                                                     "take --teeth)")
        names = TRAINS[a.train]
        teeth = _teeth(a.teeth, names)
        r = {"ngw": drive.ngw, "nn": drive.nn, "khv": drive.khv,
             "internal": drive.internal_teeth}[a.train](*teeth)
    if a.json:
        from dataclasses import asdict

        out = asdict(r)
        if a.eta_h is not None:
            out["eta_H"], out["efficiency"] = a.eta_h, r.efficiency(a.eta_h)
        print(json.dumps(out, indent=2))
    else:
        print(ratio_table(r, a.eta_h))
    return 0


def _teeth(text: str | None, names: tuple[str, ...]) -> list[int]:
    want = ",".join(names)
    if text is None:
        raise ParameterError("teeth", None, f"--teeth {want}")
    try:
        teeth = [int(t) for t in text.split(",")]
    except ValueError:
        raise ParameterError("teeth", text, f"{len(names)} integers {want}") from None
    if len(teeth) != len(names):
        raise ParameterError("teeth", text, f"{len(names)} integers {want}")
    return teeth


def _bearings(a: argparse.Namespace) -> int:
    from ..drive import RingDrive, bearings_summary, bearings_table, write_bearings
    from ..files import check_dir, prepare_dir

    v = {row.dest: getattr(a, row.dest) for row in BEARING_INPUTS}
    if v["inertia_force"] == 0:           # 0: from eq. (2)
        v["inertia_force"] = None
    drive = RingDrive(**v)
    step = STEP.check(a.step)
    out = None if a.out is None else check_dir(a.out)
    summary = bearings_summary(drive, step)
    files = {}
    if out is not None:
        files = write_bearings(prepare_dir(out), drive, summary, step)
    return _report(summary, bearings_table, files, a.json)


def _speeds(text: str) -> list[float]:
    try:
        if ":" in text:
            lo, hi, n = text.split(":")
            lo, hi, count = float(lo), float(hi), int(n)
            if count < 1 or not 0 < lo <= hi:
                raise ValueError
            return [lo + (hi - lo) * j / max(count - 1, 1) for j in range(count)]
        values = [float(s) for s in text.split(",")]
    except ValueError:
        raise ParameterError("speeds", text, "speeds > 0 [r/min]: 500,1000 or lo:hi:count "
                                             "with 0 < lo <= hi, count >= 1") from None
    for v in values:
        require_range("speeds", v, 0.0, 1e6, lo_open=True, unit="r/min")
    return values


def _dynamics(a: argparse.Namespace) -> int:
    from ..drive import (
        TorsionalPair,
        default_inertias,
        dynamics_summary,
        dynamics_table,
        steady_response,
        write_dynamics,
    )
    from ..files import check_dir, prepare_dir
    from ..toothpair import read_mesh_stiffness

    own = checked(a, DYNAMICS_INPUTS)
    speeds = None if a.speeds is None else _speeds(a.speeds)
    if speeds is not None and len(speeds) > 2000:
        raise ParameterError("speeds", a.speeds, "at most 2000 speeds")
    out = None if a.out is None else check_dir(a.out)
    mesh = read_mesh_stiffness(a.stiffness)
    j1, j2 = default_inertias(mesh)
    torque = mesh.torque if own["torque"] is None else own["torque"]
    pair = TorsionalPair(own["J1"] or j1, own["J2"] or j2, mesh.z2 / mesh.z1,
                         mesh.kind(a.spring).mean, own["zeta"])
    if speeds is None:  # through f_n/2 and f_n: mesh frequency z1 n/60 up to 1.5 f_n
        top = 1.5 * pair.natural_frequency / (2 * math.pi) * 60.0 / mesh.z1
        speeds = [top * j / 60 for j in range(1, 61)]
    DYNAMICS_INPUTS[3].check(torque)       # the file's too
    out = prepare_dir(out) if out is not None else None
    summary = dynamics_summary(pair, mesh, torque,
                               [steady_response(pair, mesh, torque, s, spring=a.spring)
                                for s in speeds], a.spring)
    files = write_dynamics(out, summary) if out is not None else {}
    return _report(summary, dynamics_table, files, a.json)


def _report(summary: dict, table, files: dict, as_json: bool) -> int:
    """Print the summary as JSON (with the files written), or its table and the files."""
    if as_json:
        print(json.dumps({**summary, "files": {k: str(v) for k, v in files.items()}},
                         indent=2))
    else:
        print(table(summary))
        for k, v in files.items():
            print(f"{k:6s} {v}")
    return 0

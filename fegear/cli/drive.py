"""``fegear drive``: ratios and efficiencies, seed 000's bearing forces, the lumped model."""

from __future__ import annotations

import argparse
import json
import math

from ..checks import require_range
from ..errors import ParameterError
from .args import Parser

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
    r.add_argument("--i-ab-h", type=float, default=None,
                   help="2kh: the carrier-fixed ratio i_ab^H with its sign")
    r.add_argument("--eta-h", type=float, default=None,
                   help="efficiency of the carrier-fixed mechanism (product of its meshes)")
    r.add_argument("--json", action="store_true", help="print JSON")

    b = sub.add_parser("bearings", help="seed 000: eccentric-bearing forces and support "
                                        "reactions of the three-ring reducer")
    for name, default, text in (
            ("--z1", 78, "external (output) gear teeth"), ("--z2", 81, "internal ring teeth"),
            ("--m", 4.5, "module [mm]"), ("--torque", 1117.0, "output torque [N·m]"),
            ("--rings", 3, "planet rings"), ("--speed", 1500.0, "crank speed [r/min]"),
            ("--pressure-angle", 20.0, "standard pressure angle [deg]"),
            ("--working-angle", 35.286, "working pressure angle α' [deg]"),
            ("--base-radius", 171.26, "base radius r_b of the ring [mm]"),
            ("--ring-weight", 420.6, "ring weight G_2 [N]"),
            ("--inertia-force", 8050.2, "ring inertia force P_i2 [N] (0: from eq. 2)"),
            ("--load-factor", 1.2, "F_n = factor · T / (rings r_b)"),
            ("--half-span", 338.0, "half distance l of bearings A, B [mm]"),
            ("--spacing", 40.0, "axial spacing B of the eccentrics [mm]"),
            ("--support-span", 180.0, "span L' of a crank shaft's supports [mm]"),
            ("--bearing-weight", 20.0, "eccentric-bearing weight G_H [N]"),
            ("--step", 1.0, "crank-angle grid [deg] (the paper used 1)")):
        b.add_argument(name, type=type(default), default=default,
                       help=f"{text} (default {default:g}: the paper's example)")
    b.add_argument("--json", action="store_true", help="print the summary as JSON")
    b.add_argument("--out", default=None, help="write bearings.json, .csv and .png here")

    d = sub.add_parser("dynamics", help="torsional two-inertia model driven by the mesh "
                                        "stiffness of `fegear solve --positions N`")
    d.add_argument("--stiffness", required=True, help="mesh_stiffness.json of a solve cycle")
    d.add_argument("--J1", type=float, default=None,
                   help="gear-1 inertia [kg·m²] (default: steel disk of its pitch radius)")
    d.add_argument("--J2", type=float, default=None,
                   help="gear-2 inertia [kg·m²] (default: steel ring, pitch radius + 3 m)")
    d.add_argument("--spring", choices=("tangent", "secant"), default="tangent",
                   help="the mesh spring of the vibration about the static state: tangent "
                        "dT/dθ at the load (the linearised model's; default) or secant T/δ "
                        "(the static state is the secant's either way)")
    d.add_argument("--zeta", type=float, default=0.05, help="mesh damping ratio (0.05)")
    d.add_argument("--torque", type=float, default=None,
                   help="gear-1 torque [N·m] (default: the stiffness file's)")
    d.add_argument("--speeds", default=None,
                   help="gear-1 speeds [r/min]: a list 500,1000 or a range lo:hi:count "
                        "(default: 60 speeds up to a mesh frequency of 1.5 f_n)")
    d.add_argument("--json", action="store_true", help="print the summary as JSON")
    d.add_argument("--out", default=None, help="write dynamics.json, .csv and .png here")


    _add_reducer(sub)


#: ``fegear drive reducer``'s model inputs: option, help (the defaults are seed 003's Table 1
#: and ReducerInputs' choices for what it leaves unsaid; docs/drive.md)
REDUCER_OPTIONS = (
    ("power-kW", "power [kW]"), ("speed-rpm", "working crank (input) speed [r/min]"),
    ("module-mm", "module [mm]"), ("z-plate", "internal-gear plate teeth"),
    ("z-gear", "external (output) gear teeth"), ("eccentricity-mm", "eccentricity [mm]"),
    ("mesh-angle-deg", "working pressure angle [deg]"),
    ("bearing-stiffness", "support and planet bearing stiffness [N/m]"),
    ("mesh-damping", "mesh damping ratio ζ"),
    ("plate-mass", "plate mass [kg], a single plate of the whole thickness"),
    ("plate-inertia", "plate polar moment of inertia [kg·m²] (Table 1: 21.02, unit lost; "
                      "docs/drive.md)"),
    ("eccentric-mass", "mass of each crank's eccentric [kg] (Table 1's 0.29 kg, label lost)"),
    ("motor-inertia", "the motor rotor's inertia at the input's drive end [kg·m²] (not in "
                      "Table 1)"),
    ("input-diameter-mm", "crank shafts' mean diameter [mm]"),
    ("input-length-mm", "crank shafts' length = support span [mm]"),
    ("output-diameter-mm", "output shaft's mean diameter [mm]"),
    ("output-length-mm", "output shaft's length (the span and an overhang) [mm]"),
    ("plate-thickness-mm", "total plate thickness [mm] (not in Table 1)"),
    ("plate-gap-mm", "axial gap between plates [mm] (not in Table 1)"),
    ("crank-radius-mm", "distance of the crank shafts from the output axis [mm] (not in "
                        "Table 1)"),
    ("crank-angle-deg", "crank angle the model's geometry is frozen at [deg]"),
    ("elements", "beam elements over the crank shafts' span"))


def _add_reducer(sub) -> None:
    from ..drive.reducer_inputs import ReducerInputs

    r = sub.add_parser("reducer", help="seed 003: natural frequencies and unbalance response "
                                       "of the three-axis internal-gear reducer (1, 2, 3 plates)")
    r.add_argument("--plates", type=int, default=3,
                   help="the build whose mode shapes are drawn and whose Campbell crossings "
                        "are printed: 1, 2 or 3 plates (all three are solved) (default 3)")
    r.add_argument("--modes", type=int, default=10, help="natural frequencies per build (10)")
    r.add_argument("--mesh-stiffness", default="table",
                   help="table (Table 1's constant, 4.97e8 N/m), fe (fegear's mean tangent "
                        "stiffness of the compound-cycloid pair of the same teeth, module, "
                        "plate width and output torque), a mesh_stiffness.json, or N/m")
    r.add_argument("--fe-quality", default="coarse",
                   help="mesh quality of --mesh-stiffness fe (coarse)")
    r.add_argument("--fe-positions", type=int, default=12,
                   help="positions of --mesh-stiffness fe's mesh cycle (12)")
    r.add_argument("--speeds", default=None,
                   help="crank speeds of the response [r/min]: 500,1000 or lo:hi:count "
                        "(default: 60 up to 1.5× the working speed)")
    defaults = ReducerInputs()
    for name, text in REDUCER_OPTIONS:
        value = getattr(defaults, name.replace("-", "_"))
        r.add_argument(f"--{name}", type=type(value), default=value,
                       help=f"{text} (default {value:g})")
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
    from ..files import prepare_dir
    from ..toothpair import QUALITY

    if a.plates not in (1, 2, 3):
        raise ParameterError("plates", a.plates, "1, 2 or 3")
    require_range("modes", a.modes, 1, 60)
    require_range("fe_positions", a.fe_positions, 2, 96)
    if a.fe_quality not in QUALITY:
        raise ParameterError("fe_quality", a.fe_quality, " / ".join(QUALITY))
    inputs = ReducerInputs(**{name.replace("-", "_"): getattr(a, name.replace("-", "_"))
                              for name, _ in REDUCER_OPTIONS})
    speeds = None if a.speeds is None else _speeds(a.speeds)
    if speeds is not None and len(speeds) > 2000:
        raise ParameterError("speeds", a.speeds, "at most 2000 speeds")
    mesh = mesh_source(a.mesh_stiffness, inputs, a.fe_quality, a.fe_positions)
    summary = reducer_summary(inputs, mesh, a.modes, speeds)
    files = write_reducer(prepare_dir(a.out), summary, a.plates) if a.out is not None else {}
    if a.json:
        print(json.dumps({**public(summary), "files": {k: str(v) for k, v in files.items()}},
                         indent=2))
    else:
        print(reducer_table(summary, a.plates))
        for k, v in files.items():
            print(f"{k:15s} {v}")
    return 0


def _ratio(a: argparse.Namespace) -> int:
    from .. import drive
    from ..drive import ratio_table

    if a.eta_h is not None:
        require_range("eta_h", a.eta_h, 0.0, 1.0, lo_open=True)
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
    from ..files import prepare_dir

    drive = RingDrive(z1=a.z1, z2=a.z2, m=a.m, torque=a.torque, rings=a.rings, speed=a.speed,
                      pressure_angle=a.pressure_angle, working_angle=a.working_angle,
                      base_radius=a.base_radius, ring_weight=a.ring_weight,
                      inertia_force=None if a.inertia_force == 0 else a.inertia_force,
                      load_factor=a.load_factor, half_span=a.half_span,
                      eccentric_spacing=a.spacing, support_span=a.support_span,
                      bearing_weight=a.bearing_weight)
    step = require_range("step", a.step, 0.001, 30.0, unit="deg")
    summary = bearings_summary(drive, step)
    files = {}
    if a.out is not None:
        files = write_bearings(prepare_dir(a.out), drive, summary, step)
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
    from ..files import prepare_dir
    from ..toothpair import read_mesh_stiffness

    speeds = None if a.speeds is None else _speeds(a.speeds)
    if speeds is not None and len(speeds) > 2000:
        raise ParameterError("speeds", a.speeds, "at most 2000 speeds")
    mesh = read_mesh_stiffness(a.stiffness)
    j1, j2 = default_inertias(mesh)
    torque = mesh.torque if a.torque is None else a.torque
    pair = TorsionalPair(j1 if a.J1 is None else a.J1, j2 if a.J2 is None else a.J2,
                         mesh.z2 / mesh.z1, mesh.kind(a.spring).mean, a.zeta)
    if speeds is None:  # through f_n/2 and f_n: mesh frequency z1 n/60 up to 1.5 f_n
        top = 1.5 * pair.natural_frequency / (2 * math.pi) * 60.0 / mesh.z1
        speeds = [top * j / 60 for j in range(1, 61)]
    require_range("torque", torque, 0.0, 1e5, lo_open=True, unit="N·m")
    out = prepare_dir(a.out) if a.out is not None else None
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

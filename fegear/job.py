"""One ``fegear solve`` job: its inputs, their checks, the solve and its outputs.

The command line and the study runner share this module, so a study case is exactly a
``fegear solve`` call: the same inputs under the same names (the long option without ``--``),
the same checks, the same JSON summary.
"""

from __future__ import annotations

import argparse
import functools
import math
import time
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from types import MappingProxyType

from .params import PairParameters, require_range


def add_pair_args(p: argparse.ArgumentParser) -> None:
    """The pair's inputs (every command that builds a pair takes them)."""
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


def add_material_args(p: argparse.ArgumentParser, thickness: str) -> None:
    p.add_argument("--thickness", type=float, default=5.0, help=f"{thickness} [mm] (default 5)")
    p.add_argument("--E", type=float, default=206000.0, help="Young's modulus [MPa] (206000)")
    p.add_argument("--nu", type=float, default=0.29, help="Poisson ratio (default 0.29)")


def add_solve_args(p: argparse.ArgumentParser) -> None:
    """Every input of a tooth-pair solve (not where its outputs go)."""
    add_pair_args(p)
    p.add_argument("--torque", type=float, default=200.0, help="torque on gear 1 [N·m] (200)")
    p.add_argument("--position", type=float, default=0.0,
                   help="rolling angle β of gear 2 [deg] (default 0)")
    p.add_argument("--positions", type=int, default=None,
                   help="solve N rolling angles across one tooth pitch from --position on one "
                        "mesh; writes cycle.csv, cycle.png and mesh_stiffness.json/.csv")
    add_material_args(p, "face width")
    p.add_argument("--quality", default="standard", help="coarse / fast / standard / fine")
    p.add_argument("--tip-round", type=float, default=None,
                   help="gear-1 tip-edge round radius [mm] (default 0.125 m)")
    p.add_argument("--rim1", type=float, default=None,
                   help="gear-1 rim below the roots, to the bore [mm] (default 3 m)")
    p.add_argument("--rim2", type=float, default=None,
                   help="gear-2 rim beyond the roots, to the fixed rim [mm] (default 3 m)")
    p.add_argument("--extra-teeth", type=int, default=2,
                   help="unloaded teeth meshed beyond the paired ones on each side (default 2)")
    p.add_argument("--extra-pairs", type=int, default=0,
                   help="pair this many more teeth on each side than the closure needs "
                        "(default 0; a safety check)")
    p.add_argument("--penalty-factor", type=float, default=None,
                   help="penalty κ = factor·E*/h (default 1000; h the local facet length)")
    p.add_argument("--no-estimate", action="store_true",
                   help="skip the second mesh level (no discretisation-error estimate)")


@dataclass(frozen=True)
class SolveInput:
    """One input of ``fegear solve``: its name (the long option without ``--``), the
    attribute it sets, its kind (``float``, ``int``, ``bool`` or ``str``) and its default."""

    name: str
    dest: str
    kind: str
    default: object


@functools.cache
def solve_inputs() -> Mapping[str, SolveInput]:
    """Every input of ``fegear solve`` by name, read off the parser so the two never drift
    (built once: a study asks for every case)."""
    p = argparse.ArgumentParser(add_help=False)
    add_solve_args(p)
    out = {}
    for act in p._actions:  # argparse offers no public iterator over its arguments
        name = act.option_strings[-1].removeprefix("--")
        if act.const is True:
            kind = "bool"
        else:
            kind = {float: "float", int: "int", None: "str"}[act.type]
        out[name] = SolveInput(name, act.dest, kind, act.default)
    return MappingProxyType(out)


def namespace(values: dict[str, object]) -> argparse.Namespace:
    """A solve's inputs by name (missing ones at their defaults) as the CLI would parse them."""
    inputs = solve_inputs()
    ns = argparse.Namespace(**{i.dest: i.default for i in inputs.values()})
    for name, v in values.items():
        setattr(ns, inputs[name].dest, v)
    return ns


def pair_params(a: argparse.Namespace) -> PairParameters:
    """The pair, checked for an admissible geometry before any work or output starts."""
    from .admissible import check

    p = PairParameters(m=a.m, z2=a.z2, z1=a.z1, h1=a.h1, f1=a.f1, shift=a.shift,
                       rotation=a.rotation, tip_relief=a.tip_relief)
    check(p)
    return p


@dataclass(frozen=True)
class Job:
    """A checked solve: the case and the rolling angles (rad) to solve it at."""

    case: object  # toothpair.SolveCase (imported lazily: it pulls in the FE stack)
    betas: tuple[float, ...]
    estimate: bool


def prepare(a: argparse.Namespace) -> Job:
    """Check every input of a solve (raises :class:`~fegear.errors.ParameterError` or
    :class:`~fegear.errors.GeometryError`); no meshing, no output."""
    from .toothpair import SolveCase, cycle_positions

    kw = {} if a.penalty_factor is None else {"penalty_factor": a.penalty_factor}
    position = require_range("position", a.position, -180.0, 180.0, unit="deg")
    n = 1 if a.positions is None else int(require_range("positions", a.positions, 2, 360))
    case = SolveCase(pair_params(a), torque=a.torque, beta=math.radians(position),
                     thickness=a.thickness, E=a.E, nu=a.nu, quality=a.quality,
                     rim1=a.rim1, rim2=a.rim2, extra_teeth=a.extra_teeth,
                     extra_pairs=a.extra_pairs, tip_round=a.tip_round, **kw)
    betas = (case.beta,) if n == 1 else cycle_positions(case.beta, n, case.params.z2)
    return Job(case, tuple(betas), not a.no_estimate)


@dataclass(frozen=True)
class JobResult:
    """What a solve produced: the JSON summary (``fegear solve --json``), the files written
    (name → path), the cycle rows (``--positions``; else None) and the time of the solve
    itself (s, without writing files)."""

    summary: dict
    files: dict[str, Path]
    rows: list[dict] | None
    solve_s: float


def run(job: Job, out: Path | None, fields: bool = True, pictures: bool = True) -> JobResult:
    """Solve ``job``; write summary.json, and the VTUs (``fields``) and pictures
    (``pictures``) into ``out`` unless it is None."""
    from .pairout import (
        cycle_rows,
        cycle_summary,
        pair_summary,
        second_level_estimate,
        write_cycle_outputs,
        write_pair_outputs,
    )
    from .profile import Gear1Profile
    from .toothpair import solve_positions

    t0 = time.perf_counter()
    profile = Gear1Profile(job.case.params)
    sols = solve_positions(job.case, job.betas, profile)
    cycle_s = time.perf_counter() - t0
    # pictures, VTUs and the error estimate at the position of the largest gear-1 root stress
    sol = max(sols, key=lambda s: s.root_stress[0])
    estimate, other = second_level_estimate(sol, profile) if job.estimate else (None, None)
    summary = pair_summary(sol, estimate, time.perf_counter() - t0, other)
    rows = None
    if len(sols) > 1:
        rows = cycle_rows(sols)
        summary["cycle"] = {"positions": len(sols), "solve_s": cycle_s,
                            **cycle_summary(rows), "rows": rows}
    solve_s = time.perf_counter() - t0
    files: dict[str, Path] = {}
    if out is not None:
        if rows:
            files.update(write_mesh_stiffness(out, rows, job.case))
        if rows and pictures:
            i = summary["inputs"]
            files.update(write_cycle_outputs(
                rows, out, f"m {i['m']:g}, h1 {i['h1']:g}, f1 {i['f1']:g}, T "
                           f"{i['torque_Nm']:g} N·m, {len(rows)} positions, quality "
                           f"{i['quality']}"))
        files.update(write_pair_outputs(sol, out, {**summary, "files": {
            k: str(v) for k, v in files.items()}}, fields=fields, pictures=pictures))
    return JobResult(summary, files, rows, solve_s)


def write_mesh_stiffness(out: Path, rows: list[dict], case) -> dict[str, Path]:
    """mesh_stiffness.json (for ``fegear drive dynamics``) and mesh_stiffness.csv: stiffness
    and unloaded transmission error over one mesh period, by mesh phase."""
    from .dynamics import from_cycle
    from .output import write_csv, write_json

    p = case.params
    mesh = from_cycle(rows, p.z1, p.z2, p.m, case.thickness, case.torque)
    beta0 = rows[0]["position_deg"]
    table = ((ph, beta0 + ph * 360.0 / p.z2, k, e)
             for ph, k, e in zip(mesh.phase, mesh.stiffness, mesh.error))
    return {"mesh_stiffness": write_json(out / "mesh_stiffness.json", mesh.to_json()),
            "mesh_stiffness_csv": write_csv(
                out / "mesh_stiffness.csv",
                ("phase", "position_deg", "stiffness_Nm_per_rad", "error_rad"), table)}

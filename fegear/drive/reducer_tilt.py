"""The misalignment at each mesh of seed 003's reducer (:mod:`.reducer`) under the rated
torque, in fegear's terms: per build and plate, how far the output shaft's gear (fegear's gear
1) turns out of square with the plate's internal gear (gear 2) across the plate's face width,
split into ``fegear solve``'s ``--misalignment`` (across the line of centres) and ``--tilt``
(along it), and the ``fegear solve`` line that solves that mesh.

The load case is the model's own: the input torque T_out / i at the input shaft's drive end,
reacted by the held output end through the planet bearings, the plates and the mesh springs
(the model's kinematics carry the ratio i = z_gear / (z_plate − z_gear) exactly: the held end's
reaction is T_out), in the sense that loads the mesh springs' line of action in compression.
Statics on the model's stiffness, linear.

What the model can say: the gear is a disk at one node of the output shaft, so it turns with
that node's section rotation (dx/dz, dy/dz in the xz and yz planes). The plates are rigid and
plane, with x, y and Θ only, and the planet bearings and the mesh are point springs on the
shafts' x, y and torsion: nothing in the model tilts a plate, so it stays square to the axis and
the gear's rotation is the whole relative slope. The three eccentrics' own slopes at the plate
are reported beside it (a plate held by its planet bearings' tilt stiffness would follow some
mix of them; the model has no such stiffness, so no number for the plate's tilt).

Frames: at a plate's mesh u is the plate's offset from the output axis (the crank's direction),
the pitch point lies at −r_w1 u from the gear's centre and t = ẑ × u. The misalignment's
direction is where the gear's loaded flanks push the plate's at the pitch point (its mesh
force's component across the line of centres, ± t); the tilt's is −u (the gear away from the
plate's centre: the centre distance grows). The face's first end is its end nearer the model's
z = 0 (the shafts' first support bearing, the input's drive end); the other choice flips both
signs, the mirror image of the same pair. SI inside; µm, mm, N·m out, as ``fegear solve``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..toothpair import solve_command
from .beams import SX, SY, TZ
from .reducer import ReducerModel, _directions, build_reducer
from .reducer_inputs import BUILDS, ReducerInputs

DECIMALS = 3     # µm in the command line: a nanometre, far below anything the solve resolves
TURN_ANGLES = 24  # crank angles a turn, 15° apart: the two-plate build's answer is a wave of
                  # half a turn, its peak read within 1 − cos 15° = 3.4 % of its swing


@dataclass(frozen=True)
class MeshTilt:
    """One plate's mesh under the rated torque. ``plate`` counts from 0 along z; ``fraction``
    of the plate thickness; ``face_width_mm``; ``torque_Nm``, the plate's share of the output
    torque (its mesh force times r_b); ``mesh_force_N`` along the line of action; ``slope``,
    the gear's section rotation (dx/dz, dy/dz, rad); ``misalignment_um`` and ``tilt_um`` over
    the face width, the plate square (the model's answer); ``eccentrics_um``: each crank's
    eccentric's slope at the plate, as (misalignment, tilt) in µm over the face width of the
    same frame, for what the plates' tilt might add (not modelled)."""

    plates: int
    plate: int
    fraction: float
    face_width_mm: float
    torque_Nm: float
    mesh_force_N: float
    slope: tuple[float, float]
    misalignment_um: float
    tilt_um: float
    eccentrics_um: tuple[tuple[float, float], ...]

    @property
    def label(self) -> str:
        return "single plate" if self.plates == 1 else f"plate {self.plate + 1} of {self.plates}"


def rated_torque_load(model: ReducerModel) -> tuple[np.ndarray, np.ndarray]:
    """The load of the rated torque and the model's static answer to it: |T_out / i| (N·m) on
    the input's drive-end torsion, the held output end reacting T_out. Its sense is the one
    that compresses the mesh springs: a spring is one line of action, the loaded flank's
    (the gear's flanks push the plate's along n, whose radial part separates the two); the
    other sense would have the flanks pull, which the linear spring cannot tell apart."""
    force = np.zeros(model.ndofs)
    ip = model.inputs
    force[model.dof(0, 0, TZ)] = ip.output_torque / ip.ratio
    x = _static_sparse(model, force)
    if sum(k * float(g @ x) for g, k in model.meshes) < 0:
        force, x = -force, -x
    return force, x


def _static_sparse(model: ReducerModel, force: np.ndarray) -> np.ndarray:
    """:func:`~.reducer._static` by a sparse LU: the stiffness is banded along each shaft
    (5-dof beam blocks, a few spring rows across), and the crank turn asks for dozens of
    solves, each about ten times faster than a dense one."""
    from scipy.sparse import csc_matrix
    from scipy.sparse.linalg import spsolve

    x = np.zeros(model.ndofs)
    x[model.free] = spsolve(csc_matrix(model.reduced[0]), force[model.free])
    return x


def face_components(slope: np.ndarray, u: np.ndarray, push: np.ndarray,
                    width_m: float) -> tuple[float, float]:
    """A relative slope (gear minus plate, rad, as (dx/dz, dy/dz)) over a face ``width_m``
    wide as ``fegear solve``'s (misalignment, tilt) in µm: its component along ``push`` (the
    unit direction across the line of centres the gear's loaded flanks push the plate's at the
    pitch point) and along −``u`` (``u`` the unit direction from the gear's centre to the
    plate's)."""
    d = 1e6 * width_m * np.asarray(slope, float)
    return float(d @ push), float(-(d @ u))


def mesh_tilts(model: ReducerModel) -> tuple[MeshTilt, ...]:
    """Every plate's mesh of ``model`` under the rated torque (:func:`rated_torque_load`)."""
    ip = model.inputs
    _, x = rated_torque_load(model)
    phi0 = math.radians(ip.crank_angle_deg)
    out = []
    for i, (s, (g, k)) in enumerate(zip(model.stations, model.meshes)):
        u, t = _directions(phi0 + s.phase)
        force = k * float(g @ x)    # on the plate along the line of action n = cos α' t +
        push = math.copysign(1.0, force) * t   # sin α' u: its across part (+ t, compressed)
        width = s.fraction * 1e-3 * ip.plate_thickness_mm
        node = model.node(3, s.z)
        slope = np.array([x[model.dof(3, node, SX)], x[model.dof(3, node, SY)]])
        mis, tilt = face_components(slope, u, push, width)
        cranks = tuple(face_components(
            np.array([x[model.dof(j, model.node(j, s.z), c)] for c in (SX, SY)]), u, push,
            width) for j in range(3))
        out.append(MeshTilt(model.plates, i, s.fraction, 1e3 * width,
                            abs(force) * ip.base_radius, abs(force),
                            (float(slope[0]), float(slope[1])), mis, tilt, cranks))
    return tuple(out)


def solve_values(inputs: ReducerInputs, mesh: MeshTilt) -> dict[str, object]:
    """``fegear solve``'s inputs by name for ``mesh``: fegear's compound-cycloid pair of the
    reducer's teeth and module (gear 1 the output gear, gear 2 the plate; fegear's own tooth
    form and centre distance m (z2 − z1)/2, not the reducer's involute one), the plate's face
    width, its share of the torque, and the misalignment and tilt, rounded as printed."""
    return {"z1": inputs.z_gear, "z2": inputs.z_plate, "m": inputs.module_mm,
            "face-width": round(mesh.face_width_mm, 4), "torque": round(mesh.torque_Nm, 1),
            "misalignment": round(mesh.misalignment_um, DECIMALS) + 0.0,
            "tilt": round(mesh.tilt_um, DECIMALS) + 0.0}


def over_the_turn(inputs: ReducerInputs, plates: int, mesh_stiffness: float | None = None,
                  angles: int = TURN_ANGLES) -> tuple[tuple[MeshTilt, ...], ...]:
    """:func:`mesh_tilts` of the build frozen at ``angles`` crank angles over a turn:
    (angles, plates). The answer moves with the crank angle: the input crank alone carries
    the torque into the plates, and its lever turns against each mesh's line of action."""
    return tuple(mesh_tilts(build_reducer(replace(inputs, crank_angle_deg=float(a)), plates,
                                          mesh_stiffness))
                 for a in inputs.crank_angle_deg + np.arange(angles) * 360.0 / angles)


def rated_misalignment(inputs: ReducerInputs, mesh_stiffness: float | None = None,
                       angles: int = TURN_ANGLES) -> dict:
    """The section "misalignment at each mesh under the rated torque" of ``fegear drive
    reducer``: every build's plates over the crank turn (:func:`over_the_turn`), each at
    the crank angle of its largest |(misalignment, tilt)| with its ``fegear solve`` line and
    the range over the turn, and the worst mesh of all."""
    rows = []
    for plates in BUILDS:
        turn = over_the_turn(inputs, plates, mesh_stiffness, angles)
        steps = inputs.crank_angle_deg + np.arange(angles) * 360.0 / angles
        for i in range(plates):
            each = [step[i] for step in turn]
            k = max(range(angles), key=lambda j: _size(each[j]))   # the first of equals
            m = each[k]
            values = solve_values(inputs, m)
            rows.append({"plates": plates, "plate": m.plate + 1, "label": m.label,
                         "crank_angle_deg": float(steps[k] % 360.0), "fraction": m.fraction,
                         "face_width_mm": m.face_width_mm, "torque_Nm": m.torque_Nm,
                         "mesh_force_N": m.mesh_force_N, "slope_rad": list(m.slope),
                         "misalignment_um": m.misalignment_um, "tilt_um": m.tilt_um,
                         "eccentrics_um": [list(e) for e in m.eccentrics_um],
                         "over_the_turn": {
                             "misalignment_um": _range(e.misalignment_um for e in each),
                             "tilt_um": _range(e.tilt_um for e in each),
                             "torque_Nm": _range(e.torque_Nm for e in each)},
                         "solve_values": values, "command": solve_command(values)})
    worst = max(range(len(rows)), key=lambda k: round(math.hypot(
        rows[k]["misalignment_um"], rows[k]["tilt_um"]), 9))
    return {"torque_Nm": inputs.output_torque, "input_torque_Nm":
            inputs.output_torque / inputs.ratio, "crank_angles": angles, "meshes": rows,
            "worst": worst,
            "plate_tilt": "not modelled: the plates are rigid and plane (x, y, Θ) and the "
                          "planet bearings carry no moment, so a plate stays square; the "
                          "misalignment is the output gear's own rotation"}


def _size(mesh: MeshTilt) -> float:
    """|(misalignment, tilt)| in µm to 1e-9 µm: a build that leaves the gear square (one
    plate) keeps its first crank angle rather than its rounding noise's largest."""
    return round(math.hypot(mesh.misalignment_um, mesh.tilt_um), 9)


def _range(values) -> list[float]:
    values = list(values)
    return [float(min(values)), float(max(values))]


def misalignment_table(section: dict) -> str:
    """The section as text: a row per build and plate at its worst crank angle with the range
    over the turn, the eccentrics' slopes beside it, and the ``fegear solve`` lines."""
    lines = [f"Misalignment at each mesh under the rated torque ({section['torque_Nm']:.0f} "
             f"N·m at the output, {section['input_torque_Nm']:.2f} N·m in), over "
             f"{section['crank_angles']} crank angles a turn: µm over the plate's face width "
             "from its end nearer z = 0, the output gear against its plate held square (the "
             "plates' tilt is not modelled; the eccentrics' slopes at the plate beside it):",
             "", "| build | plate | face width [mm] | worst at crank [°] | torque [N·m] | "
             "misalignment [µm] | tilt [µm] | over the turn: misalignment, tilt [µm] | "
             "the eccentrics (input, support 1, support 2): misalignment/tilt [µm] |",
             "|---:|:---|---:|---:|---:|---:|---:|:---|:---|"]
    for r in section["meshes"]:
        turn = r["over_the_turn"]
        spans = ", ".join(f"{_um(lo)} … {_um(hi)}" for lo, hi in
                          (turn["misalignment_um"], turn["tilt_um"]))
        ecc = ", ".join(f"{_um(a)}/{_um(b)}" for a, b in r["eccentrics_um"])
        lines.append(f"| {r['plates']} | {r['label']} | {r['face_width_mm']:g} | "
                     f"{r['crank_angle_deg']:g} | {r['torque_Nm']:.1f} | "
                     f"{_um(r['misalignment_um'])} | {_um(r['tilt_um'])} | {spans} | {ecc} |")
    lines += ["", "each mesh at its worst crank angle in fegear (its compound-cycloid pair of "
              "the reducer's teeth and module, centre distance m (z2 − z1)/2 where the "
              "reducer's involute one is the eccentricity; the plate's torque share):"]
    lines += [f"  {r['label']}: {r['command']}" for r in section["meshes"]]
    return "\n".join(lines)


def _um(value: float) -> str:
    """µm to the command line's nanometre, signed, without a negative zero."""
    return f"{round(value, DECIMALS) + 0.0:+.{DECIMALS}f}"

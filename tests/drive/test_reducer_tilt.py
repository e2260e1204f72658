"""The misalignment at each mesh of seed 003's reducer under the rated torque: the output
shaft's rotation at the gear against the beam's closed form under the model's own mesh forces,
the load case's equilibrium, the frame's signs and units, the worst crank angle over the turn,
and the printed ``fegear solve`` line parsed by ``fegear solve`` itself."""

import math
import shlex
from dataclasses import replace

import numpy as np
import pytest

from fegear.cli import build_parser
from fegear.cli.args import typed_values
from fegear.drive.beams import TZ, Section, X, Y
from fegear.drive.reducer import build_reducer
from fegear.drive.reducer_inputs import ReducerInputs
from fegear.drive.reducer_tilt import (
    face_components,
    mesh_tilts,
    misalignment_table,
    rated_misalignment,
    rated_torque_load,
    solve_values,
)
from fegear.toothpair import JOB_INPUTS, prepare_job


def simply_supported_rotation(z, a, P, L, EI, k):
    """The section rotation at ``z`` of a shaft on two radial springs ``k`` at 0 and ``L``
    under a point load ``P`` at ``a``: the pinned beam's slope P b (L² − b² − 3z²)/(6 EI L)
    left of the load (mirrored right of it) and the rigid rotation (R_B − R_A)/(k L) of the
    springs' give. Timoshenko's section rotation is the same: the shear angle integrates to
    zero over the span (V's integral is the end moments' difference, both zero)."""
    b = L - a
    if z <= a:
        bend = P * b * (L ** 2 - b ** 2 - 3 * z ** 2) / (6 * EI * L)
    else:
        bend = -P * a * (L ** 2 - a ** 2 - 3 * (L - z) ** 2) / (6 * EI * L)
    return bend + P * (a - b) / (k * L ** 2)


@pytest.mark.parametrize("plates", [1, 2, 3])
def test_the_gears_rotation_is_the_beams_closed_form_under_the_mesh_forces(plates):
    """The mesh forces as the model carries them (k δ along each spring's line, read from the
    static answer) put on the output shaft's span as point loads: the reported rotation at each
    plate is their superposition's, in both planes, to 1e-8 (the interdependent Timoshenko
    element is exact at its nodes under point loads)."""
    ip = ReducerInputs()
    model = build_reducer(ip, plates)
    _, x = rated_torque_load(model)
    span = 1e-3 * ip.input_length_mm
    shaft = Section(1e-3 * ip.output_diameter_mm)
    EI = shaft.material.E * shaft.I
    loads = []   # (z, force on the gear in x, in y)
    for s, (g, k) in zip(model.stations, model.meshes):
        node = model.node(3, s.z)
        f = -k * float(g @ x)
        loads.append((s.z, f * g[model.dof(3, node, X)], f * g[model.dof(3, node, Y)]))
    for s, tilt in zip(model.stations, mesh_tilts(model)):
        want = [sum(simply_supported_rotation(s.z, a, P[c], span, EI, ip.bearing_stiffness)
                    for a, *P in loads) for c in (0, 1)]
        scale = max(abs(v) for v in want) or 1.0
        assert np.allclose(tilt.slope, want, rtol=0, atol=1e-8 * max(scale, 1e-6)), \
            (tilt.slope, want)


@pytest.mark.parametrize("plates", [1, 2, 3])
def test_the_rated_torque_is_reacted_at_the_output_and_compresses_the_meshes(plates):
    """The input's |T_out / i| comes out as T_out at the held end (the model's kinematics carry
    the ratio), the plates' shares (mesh force × r_b) add up to it, and every mesh spring is
    in compression."""
    ip = ReducerInputs()
    model = build_reducer(ip, plates)
    force, x = rated_torque_load(model)
    held = model.dof(3, len(model.z[3]) - 1, TZ)
    assert abs(force[model.dof(0, 0, TZ)]) == pytest.approx(ip.output_torque / ip.ratio)
    assert abs((model.K @ x)[held]) == pytest.approx(ip.output_torque, rel=1e-8)
    assert all(k * float(g @ x) > 0 for g, k in model.meshes)
    tilts = mesh_tilts(model)
    assert sum(t.torque_Nm for t in tilts) == pytest.approx(ip.output_torque, rel=1e-8)
    assert [t.face_width_mm for t in tilts] == pytest.approx(
        [f * ip.plate_thickness_mm for f in (t.fraction for t in tilts)])


def test_the_frame_across_and_along_the_line_of_centres_in_micrometres():
    """A slope of 1e-4 rad over a 10 mm face is 1 µm: along the push it is the misalignment,
    against the plate's offset u (the centres moving apart) the tilt."""
    u, push = np.array([0.0, 1.0]), np.array([1.0, 0.0])
    assert face_components(np.array([1e-4, 0.0]), u, push, 0.010) == pytest.approx((1.0, 0.0))
    assert face_components(np.array([0.0, -1e-4]), u, push, 0.010) == pytest.approx((0.0, 1.0))
    assert face_components(np.array([-2e-4, 3e-4]), u, -push, 0.025) == \
        pytest.approx((5.0, -7.5))


def test_two_plates_load_their_inner_ends_and_lean_along_the_line_of_action():
    """Two half plates at 180° put opposed mesh forces on the gear, a couple: the shaft turns
    so that each plate's inner end closes first (plate 1's second end, plate 2's first: the
    misalignment + then −), and it bends along the line of action, whose radial part pushes
    the gear away from the plate: tilt / misalignment = −tan α'. One plate at the span's middle
    leaves the gear square (the symmetric shaft's slope there is zero)."""
    ip = ReducerInputs()
    one, = mesh_tilts(build_reducer(ip, 1))
    assert abs(one.misalignment_um) < 1e-9 and abs(one.tilt_um) < 1e-9
    first, second = mesh_tilts(build_reducer(ip, 2))
    assert first.misalignment_um > 0.1 and second.misalignment_um < -0.1
    for t in (first, second):
        assert t.tilt_um / t.misalignment_um == pytest.approx(
            -math.tan(math.radians(ip.mesh_angle_deg)), rel=1e-6)


def test_the_turn_keeps_each_plates_worst_crank_angle():
    """The input crank alone carries the torque into the plates, so the answer moves with the
    crank angle the model is frozen at: each row is its plate's largest over the turn, the
    model's own angle's answer within the row's range, and the same turn started a step later
    gives the same rows."""
    ip = ReducerInputs()
    section = rated_misalignment(ip, angles=8)
    again = rated_misalignment(replace(ip, crank_angle_deg=45.0), angles=8)
    own = {2: mesh_tilts(build_reducer(ip, 2)), 3: mesh_tilts(build_reducer(ip, 3))}
    for row, other in zip(section["meshes"], again["meshes"]):
        assert (other["misalignment_um"], other["tilt_um"]) == pytest.approx(
            (row["misalignment_um"], row["tilt_um"]), abs=1e-9)
        if row["plates"] == 1:   # square at every angle (the test above)
            continue
        lo, hi = row["over_the_turn"]["misalignment_um"]
        assert row["misalignment_um"] in (lo, hi)   # the tilt is −tan α' times it throughout
        assert abs(row["misalignment_um"]) == max(abs(lo), abs(hi))
        at_own = own[row["plates"]][row["plate"] - 1].misalignment_um
        assert lo <= at_own <= hi
    spread = section["meshes"][1]["over_the_turn"]["misalignment_um"]
    assert spread[1] - spread[0] > 0.05   # plate 1 of 2: 0.27 … 0.34 µm


def test_the_printed_command_is_a_fegear_solve_of_that_mesh():
    """The worst mesh's line, parsed by ``fegear solve``'s own parser and checked into a job:
    the plate's face width and torque, the misalignment and tilt as the table prints them."""
    ip = ReducerInputs()
    section = rated_misalignment(ip, angles=4)
    row = section["meshes"][section["worst"]]
    assert (row["plates"], row["plate"]) == (2, 1)
    words = shlex.split(row["command"])
    assert words[:2] == ["fegear", "solve"]
    a = build_parser().parse_args(words[1:])
    values = typed_values(a, JOB_INPUTS.values())
    assert values == row["solve_values"]
    job = prepare_job({**values, "quality": "coarse"})
    assert job.case.thickness == pytest.approx(0.5 * ip.plate_thickness_mm)
    assert job.case.torque == pytest.approx(row["torque_Nm"], abs=0.05)
    assert (job.face.misalignment, job.face.tilt) == pytest.approx(
        (row["misalignment_um"], row["tilt_um"]), abs=5e-4)
    text = misalignment_table(section)
    assert row["command"] in text and "not modelled" in text


def test_the_values_are_rounded_as_printed():
    ip = ReducerInputs()
    t = mesh_tilts(build_reducer(ip, 3))[0]
    v = solve_values(ip, t)
    assert (v["z1"], v["z2"], v["m"]) == (120, 122, 2.0)
    assert v["misalignment"] == round(t.misalignment_um, 3)
    assert v["face-width"] == pytest.approx(6.25)

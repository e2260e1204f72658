"""The torsional lumped model against closed forms and linear theory, and the mesh-stiffness
export of a real FE mesh cycle."""

import json
import math

import numpy as np
import pytest

from fegear.drive.dynamics import TorsionalPair, default_inertias, steady_response
from fegear.errors import FegearError, ParameterError
from fegear.toothpair.stiffness import MeshStiffness, mesh_stiffness_of_cycle, read_mesh_stiffness

N = 512  # samples per mesh period of the synthetic stiffness (linear interpolation between)


def mesh(k=5e5, eps=0.0, err=0.0, harmonic=1, z1=44, z2=45):
    ph = np.arange(N) / N
    return MeshStiffness(ph, k * (1 + eps * np.cos(2 * np.pi * harmonic * ph)),
                         err * np.sin(2 * np.pi * ph), 200.0, z1, z2, 2.0, 5.0)


def first_harmonic(r, values):
    """Complex amplitude of the mesh-order-1 component (e^{iωt} convention) of one period."""
    v = values[:-1]
    return 2 * np.mean(v * np.exp(-2j * np.pi * np.arange(len(v)) / len(v)))


def test_natural_frequency_matches_the_closed_form():
    p = TorsionalPair(J1=2.3e-4, J2=1.1e-3, ratio=45 / 44, stiffness=5.65e5, zeta=0.05)
    w, v = p.modes()
    assert w[0] == pytest.approx(0.0, abs=1e-6 * w[1])  # the rigid rotation
    closed = math.sqrt(5.65e5 * (1 / 2.3e-4 + (45 / 44) ** 2 / 1.1e-3))
    assert w[1] == pytest.approx(closed, rel=1e-12)
    assert p.natural_frequency == pytest.approx(closed, rel=1e-14)
    rigid = v[:, 0] / v[0, 0]
    assert rigid[1] == pytest.approx(44 / 45, rel=1e-12)  # θ2 = θ1/i: the mesh does not strain
    # the same frequency from the line-of-action form k_lin = k_θ / r1², masses J/r²
    r1, r2 = 0.044, 0.045
    k_lin = 5.65e5 / r1 ** 2
    assert math.sqrt(k_lin * (r1 ** 2 / 2.3e-4 + r2 ** 2 / 1.1e-3)) == pytest.approx(closed)


def test_damping_ratio_of_the_mode_is_zeta():
    p = TorsionalPair(J1=1e-3, J2=2e-3, ratio=1.1, stiffness=1e5, zeta=0.07)
    a = np.array([[0, 1], [-p.stiffness / p.equivalent_inertia,
                           -p.damping / p.equivalent_inertia]])
    lam = np.linalg.eigvals(a)[0]
    assert -lam.real / abs(lam) == pytest.approx(0.07, rel=1e-12)


def test_constant_mesh_gives_the_static_deflection():
    m = mesh(err=0.0)
    p = TorsionalPair(1e-3, 2e-3, 45 / 44, m.mean)
    r = steady_response(p, m, 200.0, 3000.0)
    assert np.allclose(r.q, 200.0 / 5e5, rtol=1e-9)
    assert r.dynamic_factor == pytest.approx(1.0, abs=1e-9) and r.multiplier < 1
    assert r.min_factor == pytest.approx(1.0, abs=1e-9)


def test_transmission_error_response_matches_linear_theory():
    m = mesh(err=1e-6)  # 1 µrad sinusoidal kinematic error, constant stiffness
    p = TorsionalPair(1e-3, 2e-3, 45 / 44, 5e5, zeta=0.05)
    for speed in (500.0, 2000.0, 6000.0):
        r = steady_response(p, m, 100.0, speed)
        w = r.mesh_frequency
        h = p.stiffness / (p.stiffness - p.equivalent_inertia * w ** 2 + 1j * p.damping * w)
        want = 1e-6 * h / 1j  # e = E sin = E e^{iωt}/i (first harmonic)
        assert abs(first_harmonic(r, r.q)) == pytest.approx(abs(want), rel=2e-4), speed


def test_small_stiffness_variation_matches_linear_theory_to_second_order():
    p = TorsionalPair(1e-3, 2e-3, 45 / 44, 5e5, zeta=0.05)
    errors = []
    for eps in (0.02, 0.01):
        m = mesh(eps=eps)
        r = steady_response(p, m, 100.0, 2500.0)
        rr = r.mesh_frequency / p.natural_frequency
        want = -eps * (100.0 / 5e5) / (1 - rr ** 2 + 2j * 0.05 * rr)
        errors.append(abs(first_harmonic(r, r.q) - want) / abs(want))
    assert errors[0] < 0.05 and errors[1] < errors[0] / 1.6  # O(ε): halving ε halves it


def test_parametric_resonance_needs_more_variation_than_four_zeta():
    p = TorsionalPair(1e-3, 2e-3, 45 / 44, 5e5, zeta=0.02)
    speed = 2 * p.natural_frequency / 44 * 30 / math.pi  # mesh frequency = 2 ω_n
    assert steady_response(p, mesh(eps=0.3), 100.0, speed).multiplier > 1  # 0.3 > 4ζ
    assert steady_response(p, mesh(eps=0.04), 100.0, speed).multiplier < 1  # 0.04 < 4ζ


def test_periodic_start_is_where_brute_force_integration_ends_up():
    from scipy.integrate import solve_ivp

    m = mesh(eps=0.1, err=2e-6)
    p = TorsionalPair(1e-3, 2e-3, 45 / 44, m.mean, zeta=0.2)
    speed = p.natural_frequency / 2 / 44 * 30 / math.pi  # two natural periods per mesh period
    r = steady_response(p, m, 100.0, speed)
    period = 2 * np.pi / r.mesh_frequency

    def rhs(t, x):  # the smooth functions the mesh samples (512 per period)
        k = 5e5 * (1 + 0.1 * np.cos(2 * np.pi * t / period))
        e = 2e-6 * np.sin(2 * np.pi * t / period)
        return [x[1], (100.0 - p.damping * x[1] - k * (x[0] - e)) / p.equivalent_inertia]

    # the start decays as exp(−ζ ω_n t): 30 periods leave e^{−150} of it
    end = solve_ivp(rhs, (0, 30 * period), [100.0 / m.mean, 0.0], method="DOP853",
                    rtol=1e-11, atol=1e-16).y[0, -1]
    assert end == pytest.approx(r.q[0], rel=1e-5)  # the samples' linear interpolation: ~2e-6
    assert r.q[-1] == pytest.approx(r.q[0], rel=1e-12)  # periodic


def test_bad_model_input_names_the_parameter():
    with pytest.raises(ParameterError, match="J2"):
        TorsionalPair(1e-3, 0.0, 1.0, 1e5)
    with pytest.raises(ParameterError, match="zeta"):
        TorsionalPair(1e-3, 1e-3, 1.0, 1e5, zeta=1.5)
    with pytest.raises(ParameterError, match="J1"):   # a bool is no number
        TorsionalPair(True, 1e-3, 1.0, 1e5)
    with pytest.raises(ParameterError, match="stiffness"):
        MeshStiffness(np.array([0.0, 0.5]), np.array([1.0, -1.0]), np.zeros(2), 1, 44, 45, 2, 5)


def test_fe_cycle_exports_a_stiffness_the_model_reproduces_statically(tmp_path):
    from fegear.cli import main

    out = tmp_path / "cycle"
    assert main(["solve", "--z2", "25", "--z1", "24", "--quality", "coarse",
                 "--shift", "0.016", "--rotation", "0.002", "--torque", "20",
                 "--positions", "4", "--no-estimate", "--out", str(out)]) == 0
    m = read_mesh_stiffness(out / "mesh_stiffness.json")
    rows = json.loads((out / "summary.json").read_text())["cycle"]["rows"]
    assert m.phase.tolist() == pytest.approx([0, 0.25, 0.5, 0.75])
    again = mesh_stiffness_of_cycle(rows, 24, 25, 2.0, 5.0, 20.0)
    assert np.array_equal(again.stiffness, m.stiffness)
    # secant mapping: static rotation = e + T/k, the FE rotation at every position
    rot = np.array([r["rotation_urad"] for r in rows]) * 1e-6
    assert m.error + 20.0 / m.stiffness == pytest.approx(rot, rel=1e-9)
    # quasi-static speed: the dynamic mesh torque stays at the static one
    j1, j2 = default_inertias(m)
    p = TorsionalPair(j1, j2, 25 / 24, m.mean)
    slow = steady_response(p, m, 20.0, 1.0)
    assert slow.dynamic_factor == pytest.approx(1.0, abs=1e-3)
    assert (out / "mesh_stiffness.csv").read_text().startswith("phase,position_deg,")
    table = np.loadtxt(out / "mesh_stiffness.csv", delimiter=",", skiprows=1)
    assert np.array_equal(table[:, 2], m.stiffness) and np.array_equal(table[:, 3], m.tangent)
    assert np.array_equal(table[:, 4], m.error)
    # the tangent (contact set kept) is stiffer than the secant: the contact grows with load
    assert np.all(m.tangent > m.stiffness)
    assert np.array_equal(again.tangent, m.tangent)
    # about the static state, a tangent spring leaves the slow response static too
    pt = TorsionalPair(j1, j2, 25 / 24, m.mean_tangent)
    assert steady_response(pt, m, 20.0, 1.0, spring="tangent").dynamic_factor == \
        pytest.approx(1.0, abs=1e-3)


def test_a_file_without_the_tangent_reads_and_says_so(tmp_path):
    """A mesh_stiffness.json written before the tangent was exported still reads; asking it
    for the tangent spring is one clear error."""
    m = MeshStiffness(np.array([0.0, 0.5]), np.array([1e5, 2e5]), np.zeros(2), 20, 24, 25, 2,
                      5)
    d = m.to_json()
    del d["tangent_stiffness_Nm_per_rad"], d["mean_tangent_Nm_per_rad"]
    path = tmp_path / "old.json"
    path.write_text(json.dumps(d))
    old = read_mesh_stiffness(path)
    assert old.tangent is None and old.kind("secant") is old
    with pytest.raises(FegearError, match="no tangent stiffness"):
        old.kind("tangent")


def test_tangent_and_secant_springs_differ_only_in_the_vibration():
    """With k_t = k_s the tangent form is the secant model to rounding; a stiffer tangent
    leaves the static state and raises the natural frequency by sqrt(k_t / k_s)."""
    phase = np.linspace(0, 1, 8, endpoint=False)
    ks = 1e5 * (1 + 0.1 * np.cos(2 * np.pi * phase))
    e = 1e-5 * np.sin(2 * np.pi * phase)
    same = MeshStiffness(phase, ks, e, 20, 24, 25, 2, 5, ks.copy())
    p = TorsionalPair(1e-3, 2e-3, 25 / 24, same.mean)
    a = steady_response(p, same, 20.0, 3000.0, steps=512)
    b = steady_response(p, same, 20.0, 3000.0, steps=512, spring="tangent")
    assert np.allclose(a.force, b.force, rtol=1e-9)
    stiff = MeshStiffness(phase, ks, e, 20, 24, 25, 2, 5, 1.5 * ks)
    pt = TorsionalPair(1e-3, 2e-3, 25 / 24, stiff.mean_tangent)
    assert pt.natural_frequency / p.natural_frequency == pytest.approx(np.sqrt(1.5), rel=1e-12)
    slow = steady_response(pt, stiff, 20.0, 1.0, spring="tangent")
    assert slow.dynamic_factor == pytest.approx(1.0, abs=1e-3)


def test_a_revolutions_mesh_stiffness_is_its_first_pitchs():
    # a revolution's rows repeat the same phases on every pitch (to rounding, or exactly):
    # the mesh period is its first pitch; a cycle across the wrap at ±180° keeps its order
    pitch, k = 360.0 / 45, [1.0e6, 1.2e6]
    rows = [{"position_deg": 3.0 + j * pitch / 2, "mesh_stiffness_Nm_per_rad": k[j % 2] + j,
             "first_touch_urad": 0.0, "tangent_stiffness_Nm_per_rad": None} for j in range(88)]
    m = mesh_stiffness_of_cycle(rows, 44, 45, 2.0, 5.0, 200.0)
    assert m.phase == pytest.approx([0.0, 0.5]) and m.stiffness.tolist() == [1.0e6, 1.2e6 + 1]
    wrapped = [{**r, "position_deg": (178.0 + j * pitch / 4 + 180.0) % 360.0 - 180.0}
               for j, r in enumerate(rows[:4])]
    m = mesh_stiffness_of_cycle(wrapped, 44, 45, 2.0, 5.0, 200.0)
    assert m.phase == pytest.approx([0.0, 0.25, 0.5, 0.75])
    assert m.stiffness.tolist() == [r["mesh_stiffness_Nm_per_rad"] for r in rows[:4]]

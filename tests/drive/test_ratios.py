"""Drive kinematics: ratios against hand-derived cases (signs included) and mesh efficiencies
against an independent torque and power balance of the transformed mechanism."""

import pytest

from fegear import drive
from fegear.errors import ParameterError


def balance_efficiency(i: float, eta_h: float, carrier_drives: bool) -> float:
    """Efficiency from first principles: ω_H = 1, ω_X = i, ω_b = 0 (b fixed). The member that
    puts power into the carrier-fixed train loses the fraction 1 − η^H of it; torques balance,
    T_X + T_b + T_H = 0."""
    t_x = (-1.0 if i > 0 else 1.0) if carrier_drives else (1.0 if i > 0 else -1.0)
    p_x_rel = t_x * (i - 1.0)  # X's power in the carrier-fixed train (ω_X − ω_H = i − 1)
    # b's relative speed is −1: b's relative power is −T_b
    t_b = eta_h * p_x_rel if p_x_rel > 0 else p_x_rel / eta_h
    t_h = -t_x - t_b
    if carrier_drives:
        return -(t_x * i) / (t_h * 1.0)
    return -(t_h * 1.0) / (t_x * i)


def test_ngw_by_hand():
    r = drive.ngw(20, 70)
    assert r.transformed == pytest.approx(-3.5)  # one external mesh: negative
    assert r.value == pytest.approx(4.5)         # 1 + 70/20, carrier turns with the sun
    # speeds: with ω_b = 0 and ω_H = 1 the sun turns at 4.5 (definition of i^H)
    assert (4.5 - 1.0) / (0.0 - 1.0) == pytest.approx(r.transformed)
    assert r.efficiency(0.9702) == pytest.approx(0.976822222, abs=1e-9)


def test_internal_teeth_drive_turns_against_the_crank():
    r = drive.internal_teeth(44, 45)  # the paper's pair
    assert r.value == pytest.approx(-44.0, rel=1e-12)  # i_H1 = −z1/(z2 − z1)
    assert r.transformed == pytest.approx(45 / 44)     # internal mesh: positive
    assert drive.internal_teeth(78, 81).value == pytest.approx(-26.0)  # seed 000's example
    # crank 44 turns, ring translating: gear 1 turns −1 (ω_1 = ω_H (1 − z2/z1))
    assert 44.0 * (1.0 - 45 / 44) == pytest.approx(44.0 / r.value)
    # the few-tooth-difference K-H-V drive has the same ratio (planet = gear 1, ring fixed)
    assert drive.khv(45, 44).value == pytest.approx(r.value)


def test_internal_teeth_efficiency_amplifies_the_mesh_loss():
    r = drive.internal_teeth(44, 45)
    for eta_h, want in ((0.99, 0.6875), (0.995, 0.815574), (0.999, 0.956897)):
        assert r.efficiency(eta_h) == pytest.approx(want, abs=1e-6)
        assert r.efficiency(eta_h) == pytest.approx(eta_h / (45 - 44 * eta_h), rel=1e-12)


def test_nn_by_hand():
    r = drive.nn(60, 20, 17, 57)  # c (20) in the fixed ring b (60), d (17) in ring e (57)
    assert r.transformed == pytest.approx(17 * 60 / (57 * 20))  # two internal meshes: +
    assert r.value == pytest.approx(9.5)
    assert r.efficiency(0.9801) == pytest.approx(balance_efficiency(1 / 9.5, 0.9801, True))


def test_two_kh_with_either_central_gear_fixed():
    assert drive.two_kh(-3.5).value == pytest.approx(4.5)
    b_in = drive.two_kh(-3.5, fixed="a")  # the ring drives, the sun is held
    assert b_in.value == pytest.approx(1 + 1 / 3.5)


@pytest.mark.parametrize("i", [4.5, 1.3, 0.7, 0.3, -0.5, -1 / 44, -44.0, 2.0, 10000.0])
@pytest.mark.parametrize("carrier_drives", [False, True])
def test_meshing_power_method_matches_the_power_balance(i, carrier_drives):
    for eta_h in (0.99, 0.9702, 0.9):
        got = drive.meshing_efficiency(i, eta_h, carrier_drives)
        assert got == pytest.approx(balance_efficiency(i, eta_h, carrier_drives), rel=1e-12)


def test_self_locking_shows_as_a_non_positive_efficiency():
    # WW-like positive train with a huge ratio, carrier driven: self-locks
    assert drive.meshing_efficiency(1e-4, 0.99, carrier_drives=False) < 0
    assert 0 < drive.meshing_efficiency(1e-4, 0.99, carrier_drives=True) < 0.01
    assert drive.meshing_efficiency(1.0, 0.9, carrier_drives=True) == 1.0  # turns as a block


def test_meshing_phase():
    assert drive.meshing_phase(3) == 120.0 and drive.meshing_phase(2) == 180.0


@pytest.mark.parametrize("call, name", [
    (lambda: drive.ngw(0, 70), "za"), (lambda: drive.internal_teeth(45, 44), "z2"),
    (lambda: drive.khv(44, 44), "zb"), (lambda: drive.meshing_efficiency(4.5, 1.2, True), "eta_h"),
    (lambda: drive.meshing_efficiency(0.0, 0.9, True), "ratio"),
    (lambda: drive.meshing_phase(0), "rings"), (lambda: drive.two_kh(1.0), "i_ab_h"),
])
def test_bad_input_names_the_parameter(call, name):
    with pytest.raises(ParameterError) as exc:
        call()
    assert exc.value.name == name.replace("_", "-")

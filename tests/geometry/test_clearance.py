"""Unloaded tooth contact: clearances checked by rotating gear 1 and measuring independently."""

import numpy as np
import pytest
from swept_reference import signed_distance

from fegear.geometry.clearance import ToothContact
from fegear.geometry.parameters import PairParameters

UM = 1e-3


@pytest.fixture(scope="module")
def tca_modified(baseline, baseline_profile):
    return ToothContact(baseline, baseline_profile)


def _min_gap_after_rotation(tca, tooth, delta, beta=0.0):
    """Rotate gear 1 by delta about O1 and return the smallest signed distance [mm] of the
    tooth to the nominal gear 2, measured with the independent eq.-11 reference."""
    g, p = tca.gear1, tca.params
    q = g.period_polyline(2e-5)
    ang = tooth * g.pitch + p.ratio * beta + delta
    c, s = np.cos(ang), np.sin(ang)
    x = np.stack([c * q[:, 0] - s * q[:, 1], s * q[:, 0] + c * q[:, 1] + p.e], -1)
    cb, sb = np.cos(beta), np.sin(beta)
    y = np.stack([cb * x[:, 0] + sb * x[:, 1], -sb * x[:, 0] + cb * x[:, 1]], -1)
    return signed_distance(y, p.r0, p.e1, p.e2, p.z2, 0.0).min()


def assert_closest_teeth_close_exactly(tca, direction, count=3) -> dict[int, float]:
    """Turning gear 1 by the reported clearance (µm) of each of the ``count`` closest teeth in
    ``direction`` makes it touch (to 0.05 µm), 0.1 µm less leaves a gap; their clearances."""
    st = tca.state(0.0)
    key = "plus_um" if direction > 0 else "minus_um"
    out = {}
    for t in sorted(st.teeth, key=lambda t: getattr(t, key) or np.inf)[:count]:
        c = getattr(t, key)
        delta = direction * c * UM / tca.params.r0
        assert abs(_min_gap_after_rotation(tca, t.tooth, delta)) < 0.05 * UM
        less = direction * (c - 0.1) * UM / tca.params.r0
        assert _min_gap_after_rotation(tca, t.tooth, less) > 0
        out[t.tooth] = c
    return out


@pytest.mark.parametrize("direction", [+1, -1])
def test_reported_clearance_closes_exactly(tca_modified, direction):
    """Turning gear 1 by the reported clearance makes the tooth touch (to 0.05 µm), and
    turning it 0.1 µm less leaves a gap."""
    assert_closest_teeth_close_exactly(tca_modified, direction)


# 3.4 s of golden-section search: the default run has the conjugate touching with zero
# clearance on the flanks that mesh (test_the_conjugate_touches_on_the_line_of_action) and
# overlapping nowhere (test_admissible.py's test_the_textbook_pair_is_admissible)
@pytest.mark.slow
def test_conjugate_pair_has_zero_backlash(conjugate, conjugate_profile):
    b = ToothContact(conjugate, conjugate_profile).backlash(8)
    assert abs(b.plus_um) < 1e-3 and abs(b.minus_um) < 1e-3


def test_paper_section2_backlash(baseline, baseline_profile):
    """Paper §2: Δ1 = 0.016 mm gives ≈ 8 µm single-side backlash; Δ2 = 0.002 mm changes it by
    2Δ2 = 4 µm. Definition: smallest rotation of gear 1 (µm of arc at r0) over one mesh cycle.
    A scan of 4 positions finds the smallest of each to 1e-8 µm as one of 8 does."""
    shift_only = ToothContact(PairParameters(shift=0.016)).backlash(4)
    both = ToothContact(baseline, baseline_profile).backlash(4)
    # measured: 8.959 µm each side (the paper reads ≈ 8 µm off its Fig. 6)
    assert shift_only.plus_um == pytest.approx(8.959, abs=0.01)
    assert shift_only.minus_um == pytest.approx(shift_only.plus_um, abs=0.01)
    change = shift_only.plus_um - both.plus_um
    assert change == pytest.approx(4.0, abs=0.4)
    assert shift_only.minus_um - both.minus_um == pytest.approx(4.0, abs=0.4)


def test_unrelieved_gear_interferes_by_about_shift_on_far_side():
    """Without tip clearance (tip_clearance = −shift: gear 1 exactly as generated at e + Δ1) the
    assembled pair interferes on the far side by ≈ Δ1 (docs/model.md, "Modifications")."""
    p = PairParameters(shift=0.016, tip_clearance=-0.016)
    st = ToothContact(p).state(0.0)
    assert st.interference
    worst = max(st.interference, key=lambda i: i.depth_um)
    assert worst.depth_um == pytest.approx(16.0, rel=0.05)  # measured 15.97 µm
    assert worst.point[1] < 0  # the far side (opposite the pitch point)
    # the default relief removes it
    assert not ToothContact(PairParameters(shift=0.016)).state(0.0).interference


def test_tooth_positions_and_counts(tca_modified):
    st = tca_modified.state(0.1)
    assert len(st.teeth) == tca_modified.params.z1
    pos = sorted(t.position_deg for t in st.teeth)
    assert np.allclose(np.diff(pos), 360 / tca_modified.params.z1, atol=1e-9)
    # the closest teeth are near the pitch point
    assert abs(st.closest(+1).position_deg) < 30 and abs(st.closest(-1).position_deg) < 30


def test_states_of_a_cycle_are_the_states_one_by_one(baseline, baseline_profile):
    # the cycle's one search gives every position exactly what its own search gives, also
    # for a subset of teeth and unrefined
    betas = np.linspace(0.0, 2 * np.pi / baseline.z2, 5, endpoint=False)
    tca = ToothContact(baseline, baseline_profile)
    assert tca.states(betas) == [tca.state(b) for b in betas]
    assert tca.states(betas[1:3], teeth=[9, 10, 30], refine=False) == [
        tca.state(b, teeth=[9, 10, 30], refine=False) for b in betas[1:3]]


@pytest.mark.parametrize("k", [22, 23, 24, 29])
def test_clearances_hold_where_gear_1s_centre_is_on_a_symmetry_line_of_gear_2(
        baseline, baseline_profile, k):
    # at β = π/2 − k π/z2 gear 1's centre lies on the middle of a gear-2 tooth or space,
    # where the distance to gear 2 is extreme exactly on a sample of the curve: every tooth's
    # clearance there is its clearance a hair away (a tooth was lost here, at 2 k π/z2 - 26°)
    beta = np.pi / 2 - k * np.pi / baseline.z2
    tca = ToothContact(baseline, baseline_profile)
    at, near = tca.states([beta, beta + 1e-9])
    for a, b in zip(at.teeth, near.teeth):
        for key in ("plus_um", "minus_um"):
            x, y = getattr(a, key), getattr(b, key)
            assert (x is None) == (y is None) and (x is None or abs(x - y) < 1e-3), (a.tooth,
                                                                                    key)


def test_angles_whole_pitches_apart_are_one_search_with_the_teeth_counted_on(baseline,
                                                                            baseline_profile):
    # gear 2 a pitch on, gear 1 a pitch on: the same pair, gear 1's teeth counted one on; the
    # states of a revolution's angles are those searched one by one: to 1e-6 µm on the teeth
    # that can touch, within the search's accuracy far out (1e-3 of the value: 0.05 µm at a
    # tooth 91 µm off)
    tca = ToothContact(baseline, baseline_profile)
    pitch = 2 * np.pi / baseline.z2
    betas = [0.3 * pitch + k * pitch for k in (0, 1, 7, 44, 45)] + [0.55 * pitch,
                                                                      3.55 * pitch]
    for got, beta in zip(tca.states(betas), betas):
        want = tca.state(beta)
        assert got.beta == beta and [t.tooth for t in got.teeth] == list(range(baseline.z1))
        for a, b in zip(got.teeth, want.teeth):
            for key in ("plus_um", "minus_um"):
                x, y = getattr(a, key), getattr(b, key)
                tol = 1e-6 if x is not None and x < 30.0 else 1e-3 * abs(x or 0.0)
                assert (x is None) == (y is None) and (x is None or abs(x - y) < tol), (
                    beta, a.tooth, key)
            assert a.position_deg == pytest.approx(b.position_deg, abs=1e-9)
            if a.plus_point is not None and a.plus_um < 30.0:
                assert np.allclose(a.plus_point, b.plus_point, atol=1e-9)
        assert [i.tooth for i in got.interference] == [i.tooth for i in want.interference]


def test_states_of_one_direction_are_that_direction_of_both(baseline, baseline_profile):
    # a tooth-pair solve under a + torque asks for the + side only: the same values, and no
    # contact point on the other side
    betas = np.linspace(0.0, 2 * np.pi / baseline.z2, 3, endpoint=False)
    tca = ToothContact(baseline, baseline_profile)
    for one, both in zip(tca.states(betas, directions=(+1,)), tca.states(betas)):
        assert [(t.tooth, t.plus_um, t.plus_point is None) for t in one.teeth] == \
            [(t.tooth, t.plus_um, t.plus_point is None) for t in both.teeth]
        assert all(t.minus_um is None for t in one.teeth)
        assert one.interference == both.interference


def _every_crossing(tca, beta, rho, phi, ang, valid, direction):
    """The signed angles by comparing every crossing of every point (the rule, written out)."""
    from fegear.geometry.clearance import ANGLE_TOL
    from fegear.planar import wrap

    x = tca._to_fixed(np.stack([rho * np.cos(phi), rho * np.sin(phi)], -1), beta)
    inside = tca.inside_gear2(x, beta)
    d = np.where(valid, wrap(direction * (ang - phi[:, None])), np.nan)
    ahead = np.where(d >= -ANGLE_TOL, d, np.inf)
    behind = np.where(d <= ANGLE_TOL, -d, np.inf)
    a, b = np.argmin(ahead, axis=1), np.argmin(behind, axis=1)
    rows = np.arange(len(rho))
    return (np.where(inside, -behind[rows, b], ahead[rows, a]), np.where(inside, b, a))


@pytest.mark.parametrize("params", [PairParameters(shift=0.016, rotation=0.002),
                                    PairParameters(h1=0.4, f1=0.1, shift=0.016),
                                    PairParameters(m=2, z2=25, z1=24, h1=0.35)],
                         ids=["baseline", "h1 0.4 f1 0.1", "25/24"])
def test_the_nearest_crossings_are_those_of_every_crossing_compared(params):
    """The clearance scan compares each flank point with the crossings next to its place among
    its circle's sorted crossings only; the values and crossing indices are, to the bit, those
    of comparing every crossing (0.9 s → 0.02 s at z2 180), over a pitch, both ways."""
    from fegear.geometry import gear1_profile

    tca = ToothContact(params, gear1_profile(params))
    teeth = np.arange(params.z1)
    for beta in np.linspace(0.0, 2 * np.pi / params.z2, 4):
        for direction in (+1, -1):
            _, _, pts = tca._flanks[direction]
            rho, phi0 = np.hypot(*pts.T), np.arctan2(pts[:, 1], pts[:, 0])
            phi = (phi0[None, :] + teeth[:, None] * tca.gear1.pitch).ravel()
            (ang, valid, _), = tca._crossings((beta,), tca._segments((beta,)), rho)
            n = len(teeth)
            want = _every_crossing(tca, beta, np.tile(rho, n), phi, np.tile(ang, (n, 1)),
                                   np.tile(valid, (n, 1)), direction)
            got = tca._signed_angles(beta, np.tile(rho, n), phi, ang, valid, direction,
                                     np.tile(np.arange(len(rho)), n))
            assert np.array_equal(got[0], want[0]) and np.array_equal(got[1], want[1])


def _meshing_points(g, beta: float) -> np.ndarray:
    """Where the exact conjugate touches gear 2 at rolling angle ``beta``, from the meshing
    equation alone: every point of gear 1's pieces whose generating angle is ``beta`` up to
    whole gear-2 pitches, carried into the fixed frame (gear 2 turned by its own angle)."""
    z2 = g.params.z2
    out = []
    for pc in g.pieces:
        b = g.branches[pc.run.branch]

        def f(x, b=b):
            return np.angle(np.exp(1j * z2 * (b.evaluate(np.atleast_1d(x)).beta - beta))) / z2

        xi = np.linspace(pc.xi0, pc.xi1, 2001)
        fx = f(xi)
        for i in np.nonzero((fx[:-1] * fx[1:] < 0) & (np.abs(np.diff(fx)) < np.pi / z2))[0]:
            lo, hi = xi[i], xi[i + 1]
            for _ in range(60):
                mid = 0.5 * (lo + hi)
                lo, hi = (mid, hi) if np.sign(f(mid)) == np.sign(f(lo)) else (lo, mid)
            a = b.evaluate(np.array([lo])).beta[0]
            x, y = b.tool.point(np.array([lo]))[0]
            out.append((np.cos(a) * x - np.sin(a) * y, np.sin(a) * x + np.cos(a) * y))
    return np.array(out)


@pytest.mark.parametrize("beta", [0.0, 0.05])
def test_the_conjugate_touches_on_the_line_of_action(conjugate, conjugate_profile, beta):
    """At zero load the exact conjugate touches gear 2 exactly where the meshing equation puts
    its contacts (near the pitch point and, by the far-side branch, on the tips of the teeth
    across the gear): the flanks with zero clearance and their contact points are those, and
    no others."""
    state = ToothContact(conjugate, conjugate_profile).state(beta)
    touching = np.array([getattr(t, f"{side}_point") for t in state.teeth
                         for side in ("plus", "minus")
                         if getattr(t, f"{side}_um") is not None
                         and abs(getattr(t, f"{side}_um")) < 0.01])
    theory = _meshing_points(conjugate_profile, beta)
    assert len(touching) >= 10
    far = np.linalg.norm(touching[:, None] - theory[None], axis=-1)
    # each touch is a meshing point and each meshing point touches (mm), but for one that
    # sits on a tip corner: at a kink the table finds the point to a µm, its clearance to a nm
    for nearest in (far.min(axis=1), far.min(axis=0)):
        assert np.sort(nearest)[-1] < 2e-3 and np.sort(nearest)[-2] < 1e-4

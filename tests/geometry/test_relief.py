"""Tip relief of gear 1 (fegear.geometry.relief): exact derivatives, joins, depth, extent, only
material removed, clearances closed by rotation, and the error lines of bad relief inputs."""

import numpy as np
import pytest
from test_clearance import assert_closest_teeth_close_exactly

from fegear.errors import ParameterError
from fegear.geometry import Gear1Profile, PairParameters, RoundedProfile
from fegear.geometry.clearance import ToothContact
from fegear.geometry.relief import RUN_IN, RelievedBranch

BASE = dict(shift=0.016, rotation=0.002)
AMOUNT_UM, EXTENT = 10.0, 0.5
UM = 1e-3


@pytest.fixture(scope="module", params=["parabolic", "arc", "linear"])
def relieved(request):
    return Gear1Profile(PairParameters(**BASE, relief=AMOUNT_UM, relief_extent=EXTENT,
                                       relief_shape=request.param))


@pytest.fixture(scope="module")
def plain(baseline_profile):
    return baseline_profile


def _zones(profile):
    branch = profile.branches[0]
    assert isinstance(branch, RelievedBranch)
    return branch, branch.zones


def test_points_tangents_and_curvature_are_exact(relieved):
    """On the relief the tangent is dq/dξ / σ and the curvature dθ/ds, checked by central
    differences of the points and tangents themselves."""
    branch, zones = _zones(relieved)
    for z in zones:
        xi = np.linspace(z.start, z.stop, 23)[1:-1]
        h = 1e-7
        ev, ep, em = (branch.evaluate(xi + d) for d in (0.0, h, -h))
        dq = (ep.q - em.q) / (2 * h)
        assert np.abs(dq - ev.speed[:, None] * ev.tangent).max() < 1e-6 * np.abs(ev.speed).max()
        angle = np.unwrap(np.arctan2(ep.tangent[:, 1], ep.tangent[:, 0])) - np.unwrap(
            np.arctan2(em.tangent[:, 1], em.tangent[:, 0]))
        turning = angle / (2 * h) / ev.speed           # dθ/ds: left turns positive
        # gear 1 is convex where its curve turns away from the outward normal
        sign = np.sign(ev.tangent[:, 0] * ev.normal[:, 1] - ev.tangent[:, 1] * ev.normal[:, 0])
        assert -sign * turning == pytest.approx(ev.kappa, rel=1e-6, abs=1e-6)
        assert np.abs(np.einsum("ij,ij->i", ev.tangent, ev.normal)).max() < 1e-14
        assert np.linalg.norm(ev.normal, axis=1) == pytest.approx(1.0, abs=1e-14)


def test_relief_depth_extent_and_joins(relieved, plain):
    """The depth is the amount at the conjugate tip end (also as the distance between the two
    curves' points there), the extent is the arc length from the start to that end, the
    relieved flank leaves the conjugate one with the same point and tangent, and its curvature
    jumps there by δ''(0)."""
    branch, zones = _zones(relieved)
    shape = relieved.params.relief_shape
    jump = {"parabolic": 2 * AMOUNT_UM * UM / EXTENT**2,
            "arc": 2 * AMOUNT_UM * UM / (EXTENT**2 + (AMOUNT_UM * UM) ** 2),
            "linear": AMOUNT_UM * UM / (1 - RUN_IN / 2) / (RUN_IN * EXTENT**2)}[shape]
    for z in zones:
        at_end = branch.evaluate(np.array([z.end])).q[0]
        conjugate = branch.branch.evaluate(np.array([z.end]))
        assert np.linalg.norm(at_end - conjugate.q[0]) == pytest.approx(AMOUNT_UM * UM, abs=1e-12)
        assert (at_end - conjugate.q[0]) @ conjugate.normal[0] == pytest.approx(-AMOUNT_UM * UM,
                                                                                 abs=1e-12)
        xi = np.linspace(z.start, z.end, 200001)
        q = branch.branch.evaluate(xi).q
        assert np.hypot(*np.diff(q, axis=0).T).sum() == pytest.approx(EXTENT, abs=1e-9)
        eps = 1e-10 * np.sign(z.end - z.start)      # 6 nm of arc
        xi = np.array([z.start - eps, z.start + eps])
        mine, theirs = branch.evaluate(xi), branch.branch.evaluate(xi)
        assert np.array_equal(mine.q[0], theirs.q[0])          # untouched before the start
        assert np.abs(mine.q[1] - theirs.q[1]).max() < 1e-15    # δ ~ w²: no step …
        assert np.abs(mine.tangent[1] - theirs.tangent[1]).max() < 1e-8   # … and no kink
        assert mine.kappa[1] - theirs.kappa[1] == pytest.approx(jump, rel=1e-4)


def test_relief_only_removes_material_and_moves_the_tip_corner(relieved, plain):
    """The relieved profile lies inside the conjugate one everywhere, equal to it from the tooth
    space to the start of the relief; the tip corner moves towards the tooth's middle."""
    phi = np.linspace(plain.phi_space, plain.phi_space + plain.pitch, 20001)
    r_plain, r_relieved = plain.radius(phi), relieved.radius(phi)
    assert (r_relieved - r_plain).max() <= 1e-12
    assert (r_plain - r_relieved).max() > 0.9 * AMOUNT_UM * UM
    untouched = np.abs(phi - plain.phi_space) < 0.5 * (plain.pieces[0].phi1 - plain.phi_space)
    assert np.abs(r_relieved - r_plain)[untouched].max() < 1e-12
    assert relieved.pieces[0].phi1 > plain.pieces[0].phi1
    assert relieved.pieces[-1].phi0 < plain.pieces[-1].phi0


def test_the_relieved_corner_is_rounded(relieved):
    """The tip round breaks the new corner. The relief turns the flank towards the tip trim,
    so the corner is blunter than the conjugate one, by less than the relief's slope there."""
    rounded = RoundedProfile(relieved, 0.25)
    conjugate = RoundedProfile(Gear1Profile(PairParameters(**BASE)), 0.25)
    assert len(rounded.fillets) == 2
    branch, zones = _zones(relieved)
    corner = relieved.tip_ends()[0][0]
    t = branch.evaluate(np.array([corner])).tangent[0]
    t0 = branch.branch.evaluate(np.array([corner])).tangent[0]
    slope = abs(np.arctan2(t0[0] * t[1] - t0[1] * t[0], t0 @ t))
    blunter = conjugate.fillets[0].kink - rounded.fillets[0].kink
    assert 0.5 * slope < blunter < slope


@pytest.mark.parametrize("direction", [+1, -1])
def test_relieved_clearance_closes_exactly(direction):
    """Turning gear 1 by the reported clearance makes the tooth touch (to 0.05 µm), 0.1 µm less
    leaves a gap; the first-touching tooth closes on its relief (its clearance grew)."""
    relieved = ToothContact(PairParameters(**BASE, relief=AMOUNT_UM))
    plain = ToothContact(PairParameters(**BASE)).state(0.0)
    key = "plus_um" if direction > 0 else "minus_um"
    closes = assert_closest_teeth_close_exactly(relieved, direction)
    assert any(c > getattr(plain.teeth[tooth], key) + 0.1 for tooth, c in closes.items())


@pytest.mark.parametrize("inputs, name, text", [
    (dict(relief=10, relief_extent=5.0), "relief-extent", "0 < relief-extent < 2.488 mm"),
    (dict(relief=10, relief_start=40.0), "relief-start", "< relief-start <"),
    (dict(relief=10, relief_extent=0.5, relief_start=44.0), "relief-start", "unset when"),
    (dict(relief=200), "relief", "0 <= relief <= 100 µm"),
    (dict(relief=64, relief_extent=0.5), "relief", "a smaller relief or a longer relief-extent"),
    (dict(relief=10, relief_shape="cubic"), "relief-shape", "parabolic / arc / linear"),
])
def test_bad_relief_inputs_name_the_parameter(inputs, name, text):
    with pytest.raises(ParameterError) as err:
        Gear1Profile(PairParameters(**BASE, **inputs))
    assert err.value.name == name and text in str(err.value)


def test_relief_start_radius_sets_the_extent():
    """A relief given by its start radius starts there."""
    p = Gear1Profile(PairParameters(**BASE, relief=10, relief_start=44.0))
    branch, zones = _zones(p)
    for z in zones:
        assert branch.evaluate(np.array([z.start])).radius[0] == pytest.approx(44.0, abs=1e-12)

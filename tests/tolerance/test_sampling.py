"""Monte-Carlo pairs of a class: every one passes inspection for its class, sample k is the same
pair in every run, and the deviations scatter as documented (σ a third of the tolerance)."""

import math

import numpy as np
import pytest

from fegear.errors import ParameterError
from fegear.geometry import PairParameters
from fegear.tolerance import SIGMAS, Draw, grade_of, sample_pair, tooth_positions

PAIR = PairParameters(shift=0.016, rotation=0.002)


@pytest.fixture(scope="module")
def class6():
    grade = grade_of(6, PAIR, centre_distance_tolerance=5.0)
    return grade, [sample_pair(grade, 3, k) for k in range(400)]


def _positions(dev, gear, z):
    """What a measuring machine reads: each tooth's indexing error and the eccentricity
    along its pitch circle (the runout's, in the gear's sign of a pitch deviation), by hand."""
    teeth, runout = dev.teeth(gear), getattr(dev, f"runout{gear}")
    theta = 2 * np.pi * np.arange(z) / z
    sign = 1.0 if gear == 1 else -1.0
    by_hand = (np.array([teeth[t].pitch for t in range(z)])
               + sign * 0.5 * runout.fr * np.sin(math.radians(runout.phase) - theta))
    assert np.allclose(tooth_positions(dev, gear, z), by_hand, rtol=0, atol=1e-12)
    return by_hand


def test_every_pair_drawn_passes_inspection_for_its_class(class6):
    grade, pairs = class6
    u = np.linspace(0, 1, 201)
    for dev in pairs:
        for gear, tol in ((1, grade.gear1), (2, grade.gear2)):
            p = _positions(dev, gear, tol.z)
            assert np.abs(p - np.roll(p, 1)).max() <= tol.f_pT + 1e-9
            assert np.ptp(p) <= tol.F_pT + 1e-9
            assert getattr(dev, f"runout{gear}").fr <= tol.F_rT
            for d in dev.teeth(gear).values():
                assert abs(d.slope) <= tol.f_HaT and abs(d.form) <= tol.f_faT
                assert np.ptp(d.normal_um(u)) <= tol.F_aT + 1e-6
            assert len(dev.teeth(gear)) == tol.z          # every tooth deviates
        assert abs(dev.centre_distance) <= 5.0


def test_sample_k_is_the_same_pair_whatever_else_is_drawn():
    grade = grade_of(5, PAIR)
    assert sample_pair(grade, 1, 17) == sample_pair(grade, 1, 17)
    assert sample_pair(grade, 1, 17) != sample_pair(grade, 2, 17)
    assert sample_pair(grade, 1, 17) != sample_pair(grade, 1, 18)


def test_the_deviations_scatter_a_third_of_their_tolerance(class6):
    grade, pairs = class6
    tol = grade.gear1
    single = np.concatenate([np.diff(_positions(d, 1, tol.z)) for d in pairs])
    slope = np.array([d.teeth(1)[0].slope for d in pairs])
    # normal with σ = T/3, the tails beyond T cut away by inspection: σ a little under T/3
    assert single.std() == pytest.approx(tol.f_pT / SIGMAS, rel=0.12)
    assert slope.std() == pytest.approx(tol.f_HaT / SIGMAS, rel=0.12)
    assert abs(single.mean()) < 0.05 * tol.f_pT
    # the eccentricity's two components normal with σ = F_rT / 6: the runout twice its
    # Rayleigh-distributed size, mean 2 σ √(π/2)
    fr = np.array([d.runout1.fr for d in pairs])
    assert fr.mean() == pytest.approx(2 * tol.F_rT / 6 * math.sqrt(math.pi / 2), rel=0.1)


def test_the_reach_bounds_every_pair_drawn(class6):
    grade, pairs = class6
    assert max(d.reach_um(t) for d in pairs for t in range(PAIR.z1)) <= grade.reach_um()


@pytest.mark.parametrize("tolerance", [-1.0, math.inf, 2000.0])
def test_a_bad_centre_distance_tolerance_is_refused_by_name(tolerance):
    with pytest.raises(ParameterError, match="centre-distance-tolerance"):
        grade_of(6, PAIR, tolerance)


@pytest.fixture(scope="module")
def across6():
    """Class 6 across a 5 mm face, drawn about a 4 µm misalignment within ±6 µm: 400 pairs."""
    grade = grade_of(6, PAIR, face_width=5.0)
    draw = Draw(grade, 400, 3, misalignment_um=4.0, band_um=6.0)
    return grade, [draw.face(k) for k in range(draw.count)]


def test_every_helix_drawn_passes_inspection_for_its_class(across6):
    grade, faces = across6
    zeta = np.linspace(-0.5, 0.5, 201)
    for face in faces:
        for helix, tol, z in ((face.helix.gear1, grade.helix1, PAIR.z1),
                              (face.helix.gear2, grade.helix2, PAIR.z2)):
            assert [t for t, _, _ in helix] == list(range(z))      # every tooth deviates
            slope, form = np.array([h[1:] for h in helix]).T
            assert np.abs(slope).max() <= tol.f_HbT and np.abs(form).max() <= tol.f_fbT
            trace = slope[:, None] * zeta + form[:, None] * (1 - 4 * zeta ** 2)
            assert np.ptp(trace, axis=1).max() <= tol.F_bT + 1e-9
        assert abs(face.misalignment - 4.0) <= 6.0


def test_the_helix_scatters_a_third_of_its_tolerance_half_of_it_the_gears(across6):
    grade, faces = across6
    tol = grade.helix1
    slope = np.array([[h[1] for h in f.helix.gear1] for f in faces])   # pairs × teeth
    form = np.array([[h[2] for h in f.helix.gear1] for f in faces])
    # normal with σ = T/3 (the tails cut by inspection), about zero
    assert slope.std() == pytest.approx(tol.f_HbT / SIGMAS, rel=0.12)
    assert form.std() == pytest.approx(tol.f_fbT / SIGMAS, rel=0.12)
    assert abs(slope.mean()) < 0.05 * tol.f_HbT
    # half the variance a gear-wide part (the machine's setting): two teeth of one gear
    # correlate by one half, and the gears' own parts are independent
    assert np.corrcoef(slope[:, 0], slope[:, 7])[0, 1] == pytest.approx(0.5, abs=0.1)
    assert np.corrcoef(form[:, 3], form[:, 20])[0, 1] == pytest.approx(0.5, abs=0.1)
    other = np.array([f.helix.gear2[0][1] for f in faces])
    assert abs(np.corrcoef(slope[:, 0], other)[0, 1]) < 0.15
    # the band: normal about the misalignment given, σ = B/3, within ±B
    mis = np.array([f.misalignment for f in faces])
    assert mis.std() == pytest.approx(6.0 / SIGMAS, rel=0.12)
    assert abs(mis.mean() - 4.0) < 3 * mis.std() / math.sqrt(len(mis))   # three errors


def test_a_sample_keeps_its_pair_in_the_plane_across_the_face_and_its_helix_with_a_band():
    plane = grade_of(5, PAIR)
    across = grade_of(5, PAIR, face_width=5.0)
    assert plane.helix1 is None and across.helix1.F_bT == 7.5
    for k in (0, 9, 31):   # common random numbers: the helix from a stream of its own
        assert Draw(across, 40, 2).pair(k) == Draw(plane, 40, 2).pair(k) == \
            sample_pair(plane, 2, k)
        fixed, banded = Draw(across, 40, 2, 3.0).face(k), Draw(across, 40, 2, 3.0, 5.0).face(k)
        assert fixed.helix == banded.helix and fixed.misalignment == 3.0
        assert banded.misalignment != 3.0
    assert Draw(across, 40, 2).face(5) != Draw(across, 40, 3).face(5)
    assert Draw(across, 40, 2).face(5) != Draw(across, 40, 2).face(6)
    with pytest.raises(ValueError, match="helix tolerances"):
        Draw(plane, 40, 2).face(0)

"""Monte-Carlo pairs of a class: every one passes inspection for its class, sample k is the same
pair in every run, and the deviations scatter as documented (σ a third of the tolerance)."""

import math

import numpy as np
import pytest

from fegear.errors import ParameterError
from fegear.geometry import PairParameters
from fegear.tolerance import SIGMAS, grade_of, sample_pair, tooth_positions

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

"""ISO 1328-1:2013's tolerances of a class: the standard's formulas and rounding, √2 a class,
and bad classes refused by name."""

import math

import pytest

from fegear.errors import ParameterError
from fegear.tolerance import class_tolerances, rounded


@pytest.mark.parametrize("um, expected", [(12.4, 12.0), (10.6, 11.0), (7.3, 7.5), (7.2, 7.0),
                                          (5.0, 5.0), (4.26, 4.3), (4.24, 4.2)])
def test_rounding_as_the_standard_rounds(um, expected):
    # above 10 µm to the whole µm, 5-10 µm to 0.5 µm, below 5 µm to 0.1 µm
    assert rounded(um) == expected


def test_class_5_for_gear_1_of_the_baseline_by_hand():
    t = class_tolerances(5, 2.0, 44)                  # d = 88 mm
    d, m = 88.0, 2.0
    assert t.f_pT == rounded(0.001 * d + 0.4 * m + 5) == 6.0                   # 5.888
    assert t.F_pT == rounded(0.002 * d + 0.55 * math.sqrt(d) + 0.7 * m + 12) == 19.0
    assert t.f_HaT == rounded(0.4 * m + 0.001 * d + 4) == 4.9                  # 4.888
    assert t.f_faT == rounded(0.55 * m + 5) == 6.0                             # 6.1
    assert t.F_aT == rounded(math.hypot(4.888, 6.1)) == 8.0                    # 7.817
    assert t.F_rT == rounded(0.9 * 18.736) == 17.0


def test_two_classes_coarser_doubles_every_tolerance_before_rounding():
    fine, coarse = class_tolerances(3, 5.0, 200), class_tolerances(7, 5.0, 200)
    for name in ("f_pT", "F_pT", "f_HaT", "f_faT", "F_aT", "F_rT"):
        # 4 × within the rounding of the two (≤ 0.5 µm each above 5 µm, the fine one ×4)
        assert getattr(coarse, name) == pytest.approx(4 * getattr(fine, name), abs=2.6)


@pytest.mark.parametrize("grade", [0, 12, 5.5, "six", True, math.nan])
def test_a_class_outside_1_to_11_is_refused_by_name(grade):
    with pytest.raises(ParameterError, match=r"grade = .* admissible: a whole number 1 \.\.\. 11"):
        class_tolerances(grade, 2.0, 44)


def test_a_gear_outside_the_formulas_range_is_refused_naming_the_class():
    with pytest.raises(ParameterError, match="0.5 <= m <= 70; this one's m is 0.3"):
        class_tolerances(6, 0.3, 44)


def test_helix_tolerances_follow_the_formulas_with_the_face_width():
    """f_HβT = (0.05 √d + 0.35 √b + 4) √2^(A−5), f_fβT = (0.07 √d + 0.45 √b + 4) √2^(A−5),
    rounded: the baseline's gear 1 (d 88, b 5 mm) at classes 5 and 7, and a wider face."""
    from fegear.tolerance.iso1328 import helix_tolerances

    assert helix_tolerances(5, 88.0, 5.0) == (5.5, 5.5)      # 5.25 and 5.66 µm
    assert helix_tolerances(7, 88.0, 5.0) == (11.0, 11.0)    # 10.50 and 11.33 µm
    assert helix_tolerances(5, 88.0, 100.0) == (8.0, 9.0)    # 7.97 and 9.16 µm
    with pytest.raises(ParameterError):
        helix_tolerances(12, 88.0, 5.0)


def test_the_total_helix_tolerance_is_the_two_together_as_the_profiles():
    """F_βT = √(f_HβT² + f_fβT²) from the unrounded two, each rounded as the others: 7.5 µm at
    class 5 on the baseline's gear 1 (d 88, b 5 mm; 7.72 unrounded), the √2 step a class."""
    from fegear.tolerance import helix_class

    h = helix_class(5, 88.0, 5.0)
    assert (h.f_HbT, h.f_fbT, h.F_bT) == (5.5, 5.5, 7.5)
    assert helix_class(7, 88.0, 5.0).F_bT == 15.0               # 15.45 µm
    assert h.summary()["F_bT_um"] == 7.5 and h.summary()["b_mm"] == 5.0

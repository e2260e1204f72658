"""A class's revolution screened (:mod:`fegear.toothpair.analyses.samples.screen`): the
scouts' places, the positions solved about the scouts that came near a pair's largest, and,
slow, a class screened against the same class solved at every position."""

import numpy as np
import pytest

from fegear.toothpair.analyses.samples.screen import (
    BEFORE,
    MARGINS,
    SCOUTS,
    STRIDE,
    about_scouts,
    beside_largest,
    scout_places,
    stride_of,
)
from fegear.toothpair.case import HEADLINE


def test_every_headline_has_a_margin():
    assert set(MARGINS) == set(HEADLINE)
    assert all(0.0 < m < 0.5 for m in MARGINS.values())


def test_the_scouts_are_evenly_apart_and_need_places_to_spare():
    assert scout_places(24) == [0, 12]
    assert scout_places(4) == [0, 2]
    assert scout_places(6) == [0, 3]
    assert scout_places(2 * SCOUTS - 1) is None
    assert scout_places(1) is None


def _scouted(values: dict[int, float], places: int, pitches: int, rest: float = 100.0):
    """Every scout position (scout_places) with every headline at ``rest``, and the
    root of gear 1 at ``values`` by position."""
    scouts = scout_places(places)
    return {r: {key: values.get(r, rest) if key == "root_stress_gear1_MPa" else rest
                for key in HEADLINE}
            for n in range(pitches) for r in (n * places + i for i in scouts)}


def test_a_pair_is_solved_about_its_scouts_within_the_margin_and_at_the_revolutions_end():
    places, pitches = 8, 5                     # scouts at places 0 and 4: 4 apart, stride 2
    end = places * pitches
    assert stride_of(places) == STRIDE == 2
    margin = MARGINS["root_stress_gear1_MPa"]
    # the largest at position 12 (pitch 1, place 4); position 20 just within the margin,
    # position 28 just without; everything else at 100
    scouted = _scouted({12: 200.0, 20: 200.0 * (1 - margin) + 1e-9,
                        28: 200.0 * (1 - margin) - 1e-3}, places, pitches)
    wanted = about_scouts(scouted, places, pitches)
    # every other headline is the same at every scout: all are its largest, so all are
    # solved about, at every other position: a pressure whose scouts do not differ is
    # screened by none; the revolution's last places at every one
    tail = set(range(end - 3, end))
    assert wanted == (set(range(0, end, 2)) | tail) - set(scouted)
    # the other headlines largest at the last scout alone: about 12 and 20 (the positions
    # of the stride nearer than the next scout either side), about the last scout, and the
    # last places
    flat = {r: {key: (v if key == "root_stress_gear1_MPa" else 150.0 if r == end - 4 else 100.0)
                for key, v in head.items()} for r, head in scouted.items()}
    others = {key: max(flat, key=lambda r: flat[r][key]) for key in HEADLINE}
    assert set(others.values()) == {12, end - 4}
    wanted = about_scouts(flat, places, pitches)
    assert wanted == {10, 14, 18, 22, end - 6} | tail
    assert not wanted & set(flat)
    assert 28 not in wanted and 26 not in wanted and 30 not in wanted


def test_where_the_scouts_stand_close_every_position_about_them_is_solved_at_once():
    places, pitches = 4, 3                     # scouts 2 apart: nothing between to leave
    assert stride_of(places) == 1
    values = {0: 500.0, 10: 500.0}             # the first scout and the last one largest
    scouted = _scouted(values, places, pitches)
    wanted = about_scouts(scouted, places, pitches)
    assert min(wanted) >= 0 and max(wanted) < places * pitches
    assert np.isin([1, 9, 11], sorted(wanted)).all()
    # nothing is left between the positions solved for the last round
    solved = {**{r: scouted[r] for r in scouted}, **{r: scouted[0] for r in wanted}}
    assert beside_largest(solved, places, pitches) == set()


def test_the_last_round_solves_beside_the_positions_within_half_the_margin():
    places, pitches = 8, 5                     # stride 2: solved every other position
    end = places * pitches
    margin = MARGINS["root_stress_gear1_MPa"]
    solved = {r: {key: 100.0 for key in HEADLINE} for r in range(0, end, 2)}
    for key in HEADLINE:                       # every headline largest at 20
        solved[20][key] = 200.0
    solved[8]["root_stress_gear1_MPa"] = 200.0 * (1 - margin / 2) + 1e-9   # within half
    solved[30]["root_stress_gear1_MPa"] = 200.0 * (1 - margin / 2) - 1e-3  # without
    wanted = beside_largest(solved, places, pitches)
    # either side of 20 and of 8 (the roots), before 20 alone for a flank's pressure: both
    # sides all the same for the others
    assert wanted == {7, 9, 19, 21}
    assert not wanted & set(solved)
    # the flank's pressure alone largest at 20: before it alone; the others at 36
    for key in HEADLINE:
        if key not in BEFORE:
            solved[20][key] = solved[8][key] = 100.0
            solved[36][key] = 200.0
    assert beside_largest(solved, places, pitches) == {19, 35, 37}
    # all the same everywhere: beside every position, nothing beyond the revolution
    solved = {r: {key: 100.0 for key in HEADLINE} for r in range(0, end, 2)}
    assert beside_largest(solved, places, pitches) == set(range(1, end, 2))


def test_a_flanks_pressure_is_solved_about_before_its_scout_alone():
    # a flank takes the load over from its tip round in a jump, which the scout after it sees
    # decaying: the positions after that scout are not asked for on its account
    places, pitches = 8, 5
    end = places * pitches
    scouted = {r: {key: 150.0 if (key in BEFORE and r == 12) else 100.0 for key in HEADLINE}
               for n in range(pitches) for r in (n * places, n * places + 4)}
    # the other headlines the same at every scout: each scout solved about on both sides
    assert about_scouts(scouted, places, pitches) == (set(range(0, end, 2))
                                                      | set(range(end - 3, end))) - set(scouted)
    for r, head in scouted.items():
        for key in HEADLINE:
            if key not in BEFORE:
                head[key] = 100.0 + (50.0 if r == end - 4 else 0.0)
    wanted = about_scouts(scouted, places, pitches)
    assert wanted == ({10, end - 6} | set(range(end - 3, end))) - set(scouted)


def test_a_screened_class_that_all_jams_still_has_the_exact_pair_at_every_place(baseline_ring):
    # no pair turns, so no place but the scouts asks for a solve: the exact pair is solved at
    # every place all the same (the class's nominal row), without a contact kept there
    from fegear.geometry import PairParameters
    from fegear.tolerance import Draw, grade_of
    from fegear.toothpair import SolveCase
    from fegear.toothpair.analyses.samples.solve import SampleCase, solve_samples
    from fegear.toothpair.case import revolution_positions
    from fegear.toothpair.ring.solver import RingSolver, SolverModes
    from fegear.toothpair.safety import DEFAULT_ALLOWABLES

    pair = PairParameters(shift=0.016, rotation=0.002)
    case = SolveCase(pair, torque=200.0, quality="coarse")
    places = revolution_positions(0.0, 4, pair.z1, pair.z2)[:4]
    sampled = solve_samples(SampleCase(case, places, Draw(grade_of(9, pair), 2, 0),
                                       DEFAULT_ALLOWABLES, pair.z1),
                            RingSolver(baseline_ring, SolverModes(keep_phases=True)))
    assert [r["status"] for r in sampled.rows] == ["jammed", "jammed"]
    assert [s.case.beta for s in sampled.nominal] == pytest.approx(list(places))


# slow (about 60 s: a class over a revolution solved twice); the default run checks the
# screen's choice of positions above, and test_samples.py a revolution's sample against the
# same pair turned alone
@pytest.mark.slow
def test_a_screened_revolution_gives_every_pairs_worst_as_the_whole_one(baseline_ring):
    # class 5 on the coarse baseline, 8 places a pitch (352 positions a pair): each pair's
    # worst over its revolution, screened, against every position solved. The screen's
    # acceptance (issue 70): 1 % on the roots and 2 % on the pressures; a screened row is one
    # of the whole one's positions, so never above it (the kept grids, widened for other
    # samples, stand a little differently: 1e-6)
    from fegear.geometry import PairParameters
    from fegear.tolerance import Draw, grade_of
    from fegear.toothpair import SolveCase
    from fegear.toothpair.analyses.samples.solve import SampleCase, solve_samples
    from fegear.toothpair.case import revolution_positions
    from fegear.toothpair.ring.solver import RingSolver, SolverModes
    from fegear.toothpair.safety import DEFAULT_ALLOWABLES

    pair = PairParameters(shift=0.016, rotation=0.002)
    case = SolveCase(pair, torque=200.0, quality="coarse")
    draw = Draw(grade_of(5, pair), 12, 2)
    places = revolution_positions(0.0, 8, pair.z1, pair.z2)[:8]

    def solved(screen: bool):
        return solve_samples(SampleCase(case, places, draw, DEFAULT_ALLOWABLES, pair.z1,
                                        screen=screen),
                             RingSolver(baseline_ring, SolverModes(keep_phases=True)))

    screened, whole = solved(True), solved(False)
    assert whole.solved_per_pair is None
    assert screened.solved_per_pair < 0.5 * 8 * pair.z1
    turning = 0
    for a, b in zip(screened.rows, whole.rows, strict=True):
        assert a["status"] == b["status"]
        if a["status"] != "solved":
            continue
        turning += 1
        for key in HEADLINE:
            short = 1e-2 if key.startswith("root") else 2e-2
            assert b[key] * (1 - short) <= a[key] <= b[key] * (1 + 1e-6), (a["sample"], key)
    assert turning >= 4


# slow (about 9 minutes on 2 cores: 2200 pairs over a revolution)
@pytest.mark.slow
def test_a_revolutions_quantile_falls_within_its_printed_error_of_2000_other_pairs():
    # issue 70: P95 over a revolution of 200 pairs against 2000 others (another seed:
    # disjoint draws), class 5 with backlash enough that few jam, `coarse`, 4 places a pitch,
    # screened: each headline's P95 of the pairs that turn within 2.5 of the combined printed
    # standard errors
    from class_quantiles import SHIFTED_CLASS_5, apart, turning_p95

    values = {**SHIFTED_CLASS_5, "positions": 4, "revolution": True}
    (s1, small), (s2, large) = turning_p95(values, 1, 200), turning_p95(values, 2, 2000)
    for s in (s1, s2):
        assert s["screened"] and s["jammed_share"] < 0.1 and s["failed"] == 0
    for key in HEADLINE:
        assert apart(small[key], large[key]) <= 2.5, key

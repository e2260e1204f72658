"""The relief search (fegear.optimize.relief_rule) on trials whose outcome is known, and once
on the baseline pair (slow)."""

from collections import Counter
from concurrent.futures import ThreadPoolExecutor

import pytest

from fegear.errors import FegearError
from fegear.optimize.relief_rule import (
    Ask,
    CycleResult,
    ReliefSearch,
    ReliefSizing,
    size_relief,
    sizing_table,
)

BASE = {"shift": 0.016, "rotation": 0.002, "torque": 200.0, "relief-extent": 0.5,
        "quality": "coarse"}


class Threads(ThreadPoolExecutor):
    """An executor (fegear.running's protocol) on threads, so that the fake solves below
    record their calls where the test reads them."""

    workers = 2


def _fake(needed_um: float, far_from_um: float | None = None, far_off_mm: float = 1.0,
          trimmed_um: float = 0.0):
    """Trials: the near-side rounds (tooth 11, 2° from the pitch point) carry load below
    ``needed_um`` (plus ``trimmed_um`` once the tip clearance exceeds the default 0.016 mm);
    a far-side round (tooth 23, 100°) from ``far_from_um`` on, while the tip clearance is
    below ``far_off_mm``."""
    calls = []

    def solve(values, amount, torque, positions, ask=None):
        tip = values.get("tip-clearance", 0.016)
        calls.append((amount, torque, positions, tip))
        edge = []
        if amount < needed_um + (trimmed_um if tip > 0.016 else 0.0):
            edge.append((11, 2.0))
        if far_from_um is not None and amount >= far_from_um and tip < far_off_mm:
            edge.append((23, 100.0))
        return CycleResult(amount, torque, 50.0 * len(edge), tuple(t for t, _ in edge),
                           tuple(a for _, a in edge), 600.0 + amount, 1000.0, 350.0 + amount,
                           5.0, {11: 0.43}, tip)

    return solve, calls


def test_the_search_finds_the_smallest_amount_within_its_tolerance_at_the_raised_torque():
    solve, calls = _fake(7.3)
    s = size_relief(BASE, ReliefSearch(positions=6, margin=0.2, tolerance_um=0.25), solve=solve)
    assert 7.3 <= s.amount_um < 7.3 + 0.25
    assert [t.amount_um for t in s.trials[:4]] == [0.0, 2.0, 4.0, 8.0]   # scan, then bisect
    assert all(torque == pytest.approx(240.0) for _, torque, _, _ in calls[:len(s.trials)])
    assert s.without.torque == s.with_relief.torque == 200.0           # reported at the design
    assert s.with_relief.amount_um == s.amount_um and s.without.amount_um == 0.0
    assert all(positions == 6 for _, _, positions, _ in calls)
    assert s.tip_clearance_mm == s.given_tip_clearance_mm == 0.016


def test_no_relief_is_needed_where_the_rounds_stay_unloaded():
    solve, _ = _fake(0.0)
    s = size_relief(BASE, solve=solve)
    assert s.amount_um == 0.0 and len(s.trials) == 1


def test_a_far_side_tip_on_its_round_raises_the_tip_clearance_in_steps_until_it_is_off():
    solve, calls = _fake(7.3, far_from_um=4.0, far_off_mm=0.021)
    s = size_relief(BASE, ReliefSearch(tolerance_um=0.25), solve=solve)
    assert 7.3 <= s.amount_um < 7.3 + 0.25
    assert s.given_tip_clearance_mm == 0.016
    assert s.tip_clearance_mm == pytest.approx(0.024)    # 16 µm + 2 steps of 4 µm (m = 2)
    assert [round(t.tip_clearance_mm, 4) for t in s.trials[-2:]] == [0.02, 0.024]
    assert s.with_relief.tip_clearance_mm == pytest.approx(0.024)
    assert s.without.tip_clearance_mm == 0.016 and s.without.amount_um == 0.0
    table = sizing_table(s)
    assert "tip clearance raised from 16.0 to 24.0 µm (--tip-clearance 0.024)" in table


def test_trimmed_tips_that_need_more_relief_send_the_search_on_from_the_amount_found():
    solve, _ = _fake(7.3, far_from_um=4.0, far_off_mm=0.021, trimmed_um=1.0)
    s = size_relief(BASE, ReliefSearch(tolerance_um=0.25), solve=solve)
    assert 8.3 <= s.amount_um < 8.3 + 0.25
    assert s.tip_clearance_mm == pytest.approx(0.024)
    assert s.with_relief.off_the_rounds


def test_a_relief_that_only_trades_near_for_far_side_edges_is_refused_when_told_to_keep_the_tip():
    solve, _ = _fake(7.3, far_from_um=4.0)
    with pytest.raises(FegearError) as err:
        size_relief(BASE, ReliefSearch(clearance=False), solve=solve)
    text = str(err.value)
    assert "far-side teeth [23]" in text and "without --keep-tip-clearance" in text
    assert "no tip relief over 0.5 mm" in text


def test_a_far_side_round_that_no_tip_clearance_frees_is_refused_naming_the_limit():
    solve, calls = _fake(7.3, far_from_um=4.0)   # tooth 23 stays on its round up to 1 mm
    with pytest.raises(FegearError) as err:
        size_relief(BASE, solve=solve)
    text = str(err.value)
    assert "far-side teeth [23]" in text
    assert "raised to 596 µm, the most this pair takes is 600 µm" in text  # m h1, 4 µm steps
    assert max(tip for *_, tip in calls) == pytest.approx(0.596, abs=1e-9)


def test_over_a_revolution_the_table_says_so_and_a_class_s_trials_give_the_share_on_a_round():
    """A search whose trials take a whole turn (``revolution`` among the inputs) reports its
    relief as over the turn and its trials' positions over it (8 a pitch, 44 pitches); a
    class's trial names the share of its pairs that load a round, a passing one's too."""
    from dataclasses import replace

    solve, _ = _fake(7.3)

    def graded(values, amount, torque, positions, ask=None):
        r = solve(values, amount, torque, positions)
        return replace(r, edge_share=0.3 if r.edge_teeth else 0.02)

    s = size_relief({**BASE, "revolution": True}, ReliefSearch(positions=8), solve=graded)
    assert s.pitches == 44 and s.summary()["pitches"] == 44
    table = sizing_table(s)
    assert "keeps every tip round unloaded over a whole turn of gear 1 at 240 N·m" in table
    assert "trials, each over 8 positions a pitch, 352 over the turn:" in table
    assert "carry 50.0 N (30 % of the pairs that turn load one)" in table
    assert "off the rounds (2 % of the pairs that turn load one)" in table
    one = size_relief(BASE, ReliefSearch(positions=8), solve=solve)
    assert one.pitches == 1
    assert "unloaded over the cycle at" in sizing_table(one) and "load one" not in \
        sizing_table(one)


def test_a_tooth_that_loads_its_round_on_both_sides_of_the_mesh_counts_on_both():
    """Over a whole turn every tooth passes the pitch point and the far side: a round loaded
    by the pitch point stays a near-side load whatever the same tooth does across the mesh
    (it hid behind the far-side load it was seen with last, and the search then took a
    failing amount for a passing one)."""
    from fegear.optimize.relief_rule import by_side, far, near

    teeth, angles = by_side([(7, 3.0), (7, 120.0), (2, -40.0), (7, -5.0)])
    assert teeth == (2, 7, 7) and angles == (-40.0, -5.0, 120.0)
    r = CycleResult(4.5, 240.0, 70.0, teeth, angles, 900.0, 900.0, 390.0, 26.0, {})
    assert near(r) == [2, 7] and far(r) == [7]
    assert "rounds of teeth [2, 7] carry" in sizing_table(ReliefSizing(
        0.5, "parabolic", 0.2, 8, (r,), 5.0, 0.03, 0.042, r, r))


def test_each_trial_is_asked_about_the_side_its_verdict_reads():
    """The scan and the bisection read the rounds by the pitch point, the tip clearance's
    steps the far side: a class's trial may end once that side has failed. The pair at the
    design torque, reported whole, is asked about nothing."""
    solve, _ = _fake(7.3, far_from_um=4.0, far_off_mm=0.021)
    asked = []

    def recording(values, amount, torque, positions, ask=None):
        asked.append((amount, torque, values.get("tip-clearance", 0.016), ask))
        return solve(values, amount, torque, positions)

    s = size_relief(BASE, ReliefSearch(tolerance_um=0.25), solve=recording)
    raised = [a for a in asked if a[1] == pytest.approx(240.0)]
    assert {a[3].side for a in raised if a[2] == 0.016} == {"near"}
    assert {a[3].side for a in raised if a[2] > 0.016} == {"far"}   # 0.024 mm: off from 0.021
    assert {a[3] for a in asked if a[1] == 200.0} == {None}
    assert s.tip_clearance_mm == pytest.approx(0.024)


def _class_fake(hits, pairs: int = 10):
    """A class's trials: pair k loads a round by the pitch point (tooth 11, 2°) at an amount
    where ``hits(k, amount)``; a trial asked of some pairs (``Ask.only``) solves those alone.
    At the 95th percentile of 10 pairs, one pair loading a round fails a trial."""
    calls = []

    def solve(values, amount, torque, positions, ask=None):
        solved = range(pairs) if ask is None or ask.only is None else sorted(ask.only)
        loading = tuple(k for k in solved if hits(k, amount))
        calls.append((amount, torque, ask))
        edge = [(11, 2.0)] if loading else []
        return CycleResult(amount, torque, 50.0 * len(edge), tuple(t for t, _ in edge),
                           tuple(a for _, a in edge), 600.0, 1000.0, 350.0, 5.0, {11: 0.4},
                           0.016, len(loading) / pairs, loading=(loading, ()),
                           left_out=pairs - len(solved))

    return solve, calls


def test_a_class_s_trials_by_the_pitch_point_solve_the_pairs_the_trial_below_loaded():
    """Above a trial solved whole, a trial solves only the pairs that loaded a round there (a
    larger relief keeps the others' off); the amount found is solved whole again, and is the
    one the search finds solving every pair."""
    def hits(k, amount):   # pair k needs 0.73 k µm, the largest 6.57
        return amount < 0.73 * k

    solve, calls = _class_fake(hits)
    s = size_relief(BASE, ReliefSearch(tolerance_um=0.25), solve=solve)
    every, _ = _class_fake(hits)
    whole = size_relief(BASE, ReliefSearch(tolerance_um=0.25),
                        solve=lambda *a: every(*a[:4]))
    assert s.amount_um == whole.amount_um and 6.57 <= s.amount_um < 6.57 + 0.25
    some = [ask.only for _, torque, ask in calls if ask is not None and ask.only is not None]
    assert some and all(len(only) < 10 for only in some)
    last = [ask for amount, torque, ask in calls
            if amount == s.amount_um and torque == pytest.approx(240.0)]
    assert last[-1].only is None                               # the amount found, whole
    assert len(s.trials) > len(whole.trials)                   # … solved again
    assert "pairs left out, off by the pitch point at a smaller relief" in sizing_table(s)


def test_a_pair_left_out_that_loads_a_round_after_all_sends_the_search_above_it():
    """A pair off its round at 2 µm but on it between 2.5 and 3 µm (not what a relief does,
    but what the search must survive): the bisection's trial at 2.5 µm leaves it out and
    passes, the whole trial there fails, and the search goes on above: the amount found is
    solved whole and within the tolerance of a trial that failed solving the pair."""
    def hits(k, amount):
        return amount < 2.4 if k < 9 else 2.5 <= amount < 3.0

    solve, calls = _class_fake(hits)
    s = size_relief(BASE, ReliefSearch(tolerance_um=0.5), solve=solve)
    raised = [(a, ask) for a, t, ask in calls if t == pytest.approx(240.0)]
    assert (2.5, Ask("near")) in raised                        # verified whole: it failed
    assert [ask.only for a, ask in raised if a == s.amount_um][-1] is None
    failed = [t.amount_um for t in s.trials if t.edge_teeth and t.amount_um < s.amount_um
              and (t.left_out == 0 or 9 in t.loading[0])]
    assert s.amount_um - max(failed) <= 0.5 and not hits(9, s.amount_um)


@pytest.mark.parametrize("kind", [dict(needed_um=7.3),
                                  dict(needed_um=7.3, far_from_um=4.0, far_off_mm=0.021),
                                  dict(needed_um=7.3, far_from_um=4.0, far_off_mm=0.021,
                                       trimmed_um=1.0),
                                  dict(needed_um=0.0)])
def test_solving_ahead_on_two_workers_finds_what_the_search_finds_alone(kind):
    """The guesses change nothing the search reports: the same amount, tip clearance, trials
    in the same order and the same pair at the design torque; they are solved in parallel with the
    trials it needs (more solves than trials, fewer rounds)."""
    alone, alone_calls = _fake(**kind)
    ahead, ahead_calls = _fake(**kind)
    s1 = size_relief(BASE, ReliefSearch(tolerance_um=0.25), solve=alone)
    with Threads(2) as threads:
        s2 = size_relief(BASE, ReliefSearch(tolerance_um=0.25), threads, solve=ahead)
    assert s2 == s1
    assert not Counter(alone_calls) - Counter(ahead_calls)   # every needed solve, …
    assert all(n == Counter(alone_calls)[c] for c, n in Counter(ahead_calls).items()
               if c in alone_calls)                           # … each as often as alone …
    if kind["needed_um"] > 0:                             # … and guesses beside them
        assert len(ahead_calls) > len(alone_calls)


@pytest.mark.slow
def test_the_baseline_gets_a_relief_and_tip_clearance_that_keep_it_off_its_rounds():
    """Over a 6-position cycle at `coarse`: the baseline pair needs a relief, and its far-side
    tooth 23 a larger tip clearance than the default 16 µm; with both no round carries load
    at 200 N·m, the flank pressure is the peak and the transmission error grows."""
    s = size_relief(BASE, ReliefSearch(positions=6))
    assert 0.0 < s.amount_um < 50.0
    assert s.tip_clearance_mm > s.given_tip_clearance_mm == 0.016
    assert s.with_relief.off_the_rounds and not s.without.off_the_rounds
    assert s.with_relief.contact_MPa == s.with_relief.flank_MPa
    assert s.with_relief.te_mean_urad > s.without.te_mean_urad


CLASSED = {"shift": 0.03, "rotation": 0.002, "torque": 240.0, "relief-extent": 0.5,
           "quality": "coarse"}


@pytest.fixture(scope="module")
def class4():
    from fegear.geometry import PairParameters
    from fegear.tolerance import Draw, grade_of

    return Draw(grade_of(4, PairParameters(shift=0.03, rotation=0.002)), 8, 0)


def test_a_class_s_trial_loads_a_round_where_more_of_its_pairs_do_than_the_quantile_leaves(
        class4):
    from fegear.optimize.relief_rule import Graded, cycle_result, graded_cycle_result, near

    # 2.5 µm keeps the exact pair off its rounds; some class-4 pairs still press a round by
    # the pitch point: at the 95th percentile of 8 pairs (any one of them) that fails, at the
    # median (more than four) it passes where no more than four do
    exact = cycle_result(CLASSED, 2.5, 240.0, 4)
    strict = graded_cycle_result(CLASSED, 2.5, 240.0, 4, Graded(class4, 0.95))
    lax = graded_cycle_result(CLASSED, 2.5, 240.0, 4, Graded(class4, 0.5))
    assert not near(exact) and near(strict)
    assert 0 < strict.edge_share <= 1 and strict.edge_share == lax.edge_share
    assert bool(near(lax)) == (strict.edge_share > 0.5)
    # the loads, pressures and transmission error reported are the exact pair's (solved in
    # the class's chain: 5e-6 apart, where its grids fall)
    assert strict.flank_MPa == pytest.approx(exact.flank_MPa, rel=1e-4)
    assert strict.te_mean_urad == pytest.approx(exact.te_mean_urad, rel=1e-4)


def test_a_class_whose_pairs_mostly_jam_has_no_relief_and_says_why():
    from fegear.errors import ParameterError
    from fegear.geometry import PairParameters
    from fegear.optimize.relief_rule import Graded, graded_cycle_result
    from fegear.tolerance import Draw, grade_of

    draw = Draw(grade_of(6, PairParameters(shift=0.016, rotation=0.002)), 6, 0)
    with pytest.raises(ParameterError, match="jam: no relief frees them") as err:
        graded_cycle_result({**CLASSED, "shift": 0.016}, 3.0, 240.0, 2, Graded(draw, 0.95))
    assert err.value.name == "grade"


def test_a_class_s_trial_asked_about_a_side_ends_once_that_side_fails_with_the_same_verdict(
        class4):
    """Asked about the far side (as the tip clearance's steps ask), a trial of 8 class-4 pairs
    stops solving pairs once more of them than the quantile leaves have loaded a far-side
    round (two do, from the first position on): the same verdict and the exact pair's same
    numbers, with the share it saw until then (at most the whole trial's); where that side
    passes (at the median), nothing stops and the trial is the whole one."""
    from fegear.optimize.relief_rule import Ask, Graded, far, graded_cycle_result

    whole = graded_cycle_result(CLASSED, 2.5, 240.0, 4, Graded(class4, 0.95))
    ended = graded_cycle_result(CLASSED, 2.5, 240.0, 4, Graded(class4, 0.95), Ask("far"))
    assert far(whole) and far(ended)
    assert ended.stopped and not whole.stopped
    assert 0 < ended.edge_share <= whole.edge_share
    assert (ended.flank_MPa, ended.te_mean_urad) == (whole.flank_MPa, whole.te_mean_urad)
    lax = graded_cycle_result(CLASSED, 2.5, 240.0, 4, Graded(class4, 0.5))
    lax_asked = graded_cycle_result(CLASSED, 2.5, 240.0, 4, Graded(class4, 0.5), Ask("far"))
    assert not far(lax) and not lax_asked.stopped
    assert lax_asked == lax

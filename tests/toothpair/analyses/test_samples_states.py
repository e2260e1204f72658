"""A class's check that a pair keeps its backlash over a turn (``samples.states``): the closing
points' clearances on their foot circles are the exact ones to far below the screen's margin,
so the states measured exactly are every state that closes, and the check finds where a pair
jams as the exact clearances of every state would."""

import numpy as np
import pytest

from fegear.geometry import (
    deviations,
    gear1_profile,
    least_clearances,
    least_of_states,
    point_clearances,
)
from fegear.tolerance import Draw, grade_of
from fegear.toothpair import SolveCase
from fegear.toothpair.analyses.samples import states as states_module
from fegear.toothpair.analyses.samples.states import States, jammed, screen_um
from fegear.toothpair.teeth import closure

from .test_samples import PAIR

CASE = SolveCase(PAIR, torque=200.0, quality="coarse")
#: class 6 on the seed paper's baseline: most pairs jam, a few turn
DRAW = Draw(grade_of(6, PAIR), 40, 3)


def states_of(draw):
    pairs = [draw.pair(k) for k in range(draw.count)]
    reach = max(d.widest_um() for d in pairs)
    return States(CASE, gear1_profile(PAIR), (0.0,), reach), pairs


@pytest.fixture(scope="module")
def states_and_pairs():
    return states_of(DRAW)


def _circles_error(states, pairs, monkeypatch) -> float:
    """The largest error of a pair's foot circles' clearances against the exact Newton steps
    on either side, as a share of its screen's margin. Where a closing point grazes gear 2
    and the deviations close it, the exact clearance follows its tooth's gap along the turn
    instead of the step (:func:`~fegear.geometry.deviations.grazes`), above the step: the
    circles' are never above the exact ones, so no state that closes escapes the screen."""
    worst = 0.0
    for dev in pairs:
        for side in (states.circles, states.coast):   # the loaded flanks, the coast flanks
            exact = point_clearances(dev, PAIR, side.closing)
            with monkeypatch.context() as m:
                m.setattr(deviations, "GRAZING", 0.0)
                newton = point_clearances(dev, PAIR, side.closing)
            assert np.abs(exact - side.closing.um).max() > 5.0   # the pairs move them by µm
            circles = side.clearances(dev)
            assert (circles - exact).max() < screen_um(dev) / 20
            worst = max(worst, np.abs(circles - newton).max() / screen_um(dev))
    return worst


def test_the_foot_circles_give_the_closing_points_clearances_to_a_fraction_of_the_margin(
        states_and_pairs, monkeypatch):
    assert _circles_error(*states_and_pairs, monkeypatch) < 1 / 20   # measured 1/60


def test_a_coarse_classs_margin_grows_with_the_cube_of_its_deviations(monkeypatch):
    # class 9's teeth move 2.5 times class 6's: the circles' error 15 times as large
    assert _circles_error(*states_of(Draw(grade_of(9, PAIR), 8, 1)), monkeypatch) < 1 / 10


def _jammed_exactly(states, dev):
    """Where ``dev`` jams by every state's exact clearances (the check without its screen)."""
    least, teeth = least_clearances(dev, PAIR, states.closing)
    behind = np.flatnonzero(least < 0)
    back = least_clearances(dev, PAIR, states.coast.closing.of_states(behind))[0]
    for i, b in zip(behind, back):
        where = closure(states.turn[i][0], int(teeth[i]), float(least[i]), float(b))
        if where is not None:
            return str(where)
    return None


@pytest.mark.parametrize("at_once", [1, 16])
def test_the_screened_check_finds_every_closing_state_and_the_same_jam(states_and_pairs,
                                                                        at_once, monkeypatch):
    # the near states measured a few at a time, in turn order: the same first closing state
    monkeypatch.setattr(states_module, "STATES_AT_ONCE", at_once)
    states, pairs = states_and_pairs
    verdicts, measured = [], []
    for dev in pairs:
        least = least_clearances(dev, PAIR, states.closing)[0]
        assert set(np.flatnonzero(least < 0)) <= set(states.near(dev))
        measured.append(len(states.near(dev)) / len(states.turn))
        verdicts.append(jammed(states, dev))
        assert verdicts[-1] == _jammed_exactly(states, dev)
    assert 0 < sum(v is None for v in verdicts) < len(verdicts)   # both kinds among them
    assert np.mean(measured) < 0.6, np.mean(measured)   # the screen spares most (0.42)


def test_a_states_least_is_its_points_least_with_the_first_tooth_holding_it():
    from fegear.geometry import Closing

    closing = Closing(+1, [["a", "b", "c"], [], ["d", "e"]], np.zeros(5), np.zeros(5),
                      np.zeros((5, 2)), np.array([7, 8, 9, 3, 4]), np.zeros(5))
    least, teeth = least_of_states(np.array([2.0, 1.0, 1.0, 5.0, -1.0]), closing)
    assert least.tolist() == [1.0, np.inf, -1.0]
    assert teeth.tolist() == [8, -1, 4]
    assert closing.of_states(np.array([2])).tooth.tolist() == [3, 4]

"""The contact's linear system at one linearisation (:mod:`fegear.toothpair.ring.contact_system`):
a step on an active set against the bordered system solved whole, a system on some of A's
points as the system of their block, and the blocks it keeps giving what fresh ones give."""

import numpy as np
import pytest

from fegear.toothpair.ring.contact_system import (
    BLOCKS,
    ContactSystem,
    active_set,
    gaps_at,
    primal_active_set,
    solve_active,
)

TORQUE = 5.0   # N·mm


def _active(system: ContactSystem, count: int) -> np.ndarray:
    """The ``count`` points of least rigid gap."""
    active = np.zeros(len(system.g0), bool)
    active[np.argsort(system.g0)[:count]] = True
    return active


@pytest.mark.parametrize("arm_rate", [0.0, 40.0])
@pytest.mark.parametrize("seed", range(3))
def test_a_step_closes_the_active_gaps_and_balances_the_torque(contact_problem, seed, arm_rate):
    system = contact_problem(40, seed)
    A, w, g0, a = system.A, system.w, system.g0, system.a
    active = _active(system, 12)
    pressure, step = solve_active(system, TORQUE, active, arm_rate)
    assert not pressure[~active].any()
    gap = gaps_at(system, pressure, step, active)
    np.testing.assert_allclose(gap, g0 + a * step + A @ pressure, rtol=0,
                               atol=1e-15 * np.abs(g0).max())
    assert np.abs(gap[active]).max() <= 1e-12 * np.abs(g0).max()
    assert (w * a) @ pressure + arm_rate * step == pytest.approx(-TORQUE, rel=1e-12)
    # the same step from the bordered system solved whole
    idx = np.flatnonzero(active)
    n = len(idx)
    M = np.block([[A[np.ix_(idx, idx)], a[idx, None]],
                  [(w * a)[None, idx], np.array([[arm_rate]])]])
    whole = np.linalg.solve(M, np.concatenate([-g0[idx], [-TORQUE]]))
    np.testing.assert_allclose(pressure[idx], whole[:n], rtol=1e-9)
    assert step == pytest.approx(whole[n], rel=1e-9)


def test_with_no_active_point_the_rotation_alone_carries_the_torque(contact_problem):
    # the torque's rate with the turn carries it where no point is active (a step of the
    # iterations can leave none); without that rate nothing can, and the step is refused
    from fegear.toothpair.ring.contact_system import RingContactError

    system = contact_problem(40, 0)
    none = np.zeros(len(system.g0), bool)
    pressure, step = solve_active(system, TORQUE, none, 40.0)
    assert not pressure.any()
    assert step == pytest.approx(-TORQUE / 40.0, rel=1e-15)
    np.testing.assert_array_equal(gaps_at(system, pressure, step, none),
                                  system.g0 + system.a * step)
    with pytest.raises(RingContactError, match="cannot carry"):
        solve_active(system, TORQUE, none, 0.0)


def test_a_system_on_some_of_As_points_is_the_system_of_their_block(contact_problem):
    every = contact_problem(60, 1)
    rows = np.flatnonzero(np.arange(60) % 3 != 1)
    some = ContactSystem(every.A, every.w[rows], every.g0[rows], every.a[rows], rows)
    block = ContactSystem(every.A[np.ix_(rows, rows)], some.w, some.g0, some.a)
    active = _active(block, 10)
    (p, step), (q, other) = (solve_active(s, TORQUE, active, 0.0) for s in (some, block))
    np.testing.assert_array_equal(p, q)
    assert step == other
    np.testing.assert_array_equal(gaps_at(some, p, step, active),
                                  gaps_at(block, q, other, active))


def test_the_blocks_a_system_keeps_give_what_fresh_ones_give(contact_problem):
    # more active sets than the system keeps, each one point wider, then the first ones again:
    # kept or formed again, a set's step is the same to the last bit
    system = contact_problem(40, 2)
    sets = [_active(system, k) for k in range(5, 5 + BLOCKS + 3)]
    for active in sets + sets[:3]:
        p, step = solve_active(system, TORQUE, active, 0.0)
        fresh = ContactSystem(system.A, system.w, system.g0, system.a)
        q, other = solve_active(fresh, TORQUE, active, 0.0)
        np.testing.assert_array_equal(p, q)
        assert step == other
    assert len(system.blocks) == BLOCKS + 1     # BLOCKS sets kept, and the columns gathered


@pytest.mark.parametrize("seed", range(4))
def test_joining_the_deepest_overlaps_first_settles_the_same_contact(contact_problem, seed):
    # from a set far from the one it settles on (the least gap's point, or a wide band), the
    # method joining only the points that overlap by more than half the largest overlap takes
    # its own steps to the same pressures and set as joining every overlapping point
    system = contact_problem(80, seed)
    for start in (_active(system, 1), _active(system, 60)):
        every = active_set(system, TORQUE, start.copy())
        deepest = active_set(ContactSystem(system.A, system.w, system.g0, system.a), TORQUE,
                             start.copy(), join=0.5)
        np.testing.assert_array_equal(deepest.active, every.active)
        np.testing.assert_allclose(deepest.pressure, every.pressure, rtol=1e-10,
                                   atol=1e-12 * every.pressure.max())
        assert deepest.step == pytest.approx(every.step, rel=1e-10)


def test_the_gaps_are_As_whichever_points_joined_and_left_before(contact_problem):
    # a solve's sets grow past the rows first gathered for them (64), then lose points and
    # gain others: every step's gaps are A's, on all points and on some of them
    every = contact_problem(150, 3)
    rows = np.flatnonzero(np.arange(150) % 5 != 2)
    some = ContactSystem(every.A, every.w[rows], every.g0[rows], every.a[rows], rows)
    block = every.A[np.ix_(rows, rows)]
    order = np.argsort(some.g0)
    sets = [order[:k] for k in (10, 40, 90)] + [order[20:100], order[::3]]
    for system, A in ((some, block), (every, every.A)):
        for chosen in sets:
            active = np.zeros(len(system.g0), bool)
            active[chosen] = True
            pressure, step = solve_active(system, TORQUE, active, 0.0)
            np.testing.assert_allclose(gaps_at(system, pressure, step, active),
                                       system.g0 + system.a * step + A @ pressure, rtol=0,
                                       atol=1e-14 * np.abs(system.g0).max())


@pytest.mark.parametrize("seed", range(5))
@pytest.mark.parametrize("warm", [False, True])
def test_the_primal_method_meets_the_contact_conditions_and_agrees_with_the_fast_one(
        contact_problem, seed, warm):
    system = contact_problem(60, seed)
    A, w, g0, a = system.A, system.w, system.g0, system.a
    torque = 5.0
    fast = active_set(system, torque, g0 <= g0.min())
    start = fast.pressure * (1.0 + np.random.default_rng(seed).uniform(-0.5, 0.5, len(g0))) - 1.0
    slow = primal_active_set(system, torque, start if warm else np.zeros(len(g0)))
    for found in (fast, slow):
        gap = g0 + a * found.step + A @ found.pressure
        assert found.pressure.min() >= 0.0
        assert gap.min() >= -1e-12 * np.abs(g0).max()
        assert np.abs(gap[found.active]).max() <= 1e-12 * np.abs(g0).max()
        assert -(w * found.pressure) @ a == pytest.approx(torque, rel=1e-12)
    np.testing.assert_allclose(slow.pressure, fast.pressure, rtol=1e-9,
                               atol=1e-12 * fast.pressure.max())
    assert slow.step == pytest.approx(fast.step, rel=1e-9)

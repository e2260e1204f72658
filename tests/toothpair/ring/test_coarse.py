"""A kept contact's coarse level (:mod:`fegear.toothpair.ring.coarse`): its hats interpolate
the fine pressures linearly, its compliance is the fine one's under them, it predicts a
deviated contact's rotation, and a solve that starts from its prediction settles the solution
it settles without, in fewer iterations."""

import numpy as np
import pytest

from fegear.geometry import Deviations, Placed, ToothDeviation
from fegear.toothpair.ring.circles import foot_circles
from fegear.toothpair.ring.coarse import AFTER, STRIDE, CoarseLevels, coarse_contact
from fegear.toothpair.ring.contact import Iterations, rigid_gap, solve_with
from fegear.toothpair.ring.phases import NEAR
from fegear.toothpair.ring.turning import turned

#: deviations of a few µm on the teeth in mesh at β = 0: each moves the loaded zones
SETS = (Deviations(gear1={10: ToothDeviation(pitch=4.0)}),
        Deviations(gear1={11: ToothDeviation(pitch=-3.0, slope=3.0)}),
        Deviations(gear2={10: ToothDeviation(form=3.0)}, centre_distance=5.0))


@pytest.fixture(scope="module")
def kept(kept_at_zero):
    solver, case = kept_at_zero(SETS)
    held = solver.phases.contact_at(solver.model, case)[1]
    return solver.model, case, held, coarse_contact(held.contact, case.thickness)


def test_the_coarse_hats_interpolate_the_fine_pressures_linearly(kept):
    _, _, held, level = kept
    contact, P = held.contact, level.P.toarray()
    assert contact.complete
    np.testing.assert_allclose(P.sum(axis=1), 1.0, atol=1e-14)   # a uniform pressure kept
    np.testing.assert_allclose(P[level.pick], np.eye(len(level.pick)), atol=1e-14)
    for k, grid in enumerate(contact.grids):   # a pressure linear in arc length kept exactly
        blk = contact.block(k)
        line = 3.0 + 2.0 * grid.s
        coarse = np.zeros(len(level.pick))
        mine = (level.pick >= blk.start) & (level.pick < blk.stop)
        coarse[mine] = line[level.pick[mine] - blk.start]
        np.testing.assert_allclose((P @ coarse)[blk], line, rtol=1e-12)
        assert mine.sum() == len(range(0, len(grid), STRIDE)) + ((len(grid) - 1) % STRIDE > 0)


def test_the_coarse_compliance_is_the_fine_one_under_the_coarse_hats(kept):
    _, case, held, level = kept
    assert level.form is not None   # a kept contact's: formed where it is read
    level.form(np.arange(len(level.pick)))   # every coarse column, and the fine under them
    dense = held.contact.A[level.pick] @ level.P.toarray()
    np.testing.assert_allclose(level.A, dense, rtol=1e-12, atol=1e-14 * np.abs(dense).max())
    np.testing.assert_allclose(level.w, level.P.T @ (held.contact.weight * case.thickness),
                               rtol=1e-14)
    assert level.w.sum() == pytest.approx(held.contact.weight.sum() * case.thickness,
                                          rel=1e-12)


def _solved(model, case, held, level, deviations):
    """The kept contact under ``deviations`` solved from the kept rotation and its loaded
    points, with the coarse level's prediction (``level``) or without (None)."""
    placed = Placed(deviations, case.params, case.beta)
    contact = turned(model, held.contact, 0, case.beta, placed)
    how = Iterations(start=held.active, within=NEAR * 1e-3 * max(held.elastic_um, 1.0),
                     circles=foot_circles(model, held.contact, held.rotation), coarse=level)
    return contact, solve_with(model, contact, case.torque_Nmm, held.rotation, how)


@pytest.mark.parametrize("k", range(len(SETS)))
def test_a_solve_from_the_coarse_prediction_settles_the_same_contact(kept, k):
    model, case, held, level = kept
    _, alone = _solved(model, case, held, None, SETS[k])
    contact, predicted = _solved(model, case, held, level, SETS[k])
    scale = alone.pressure.max()
    np.testing.assert_allclose(predicted.pressure, alone.pressure, atol=1e-9 * scale)
    assert predicted.rotation == pytest.approx(alone.rotation, rel=1e-11)
    assert predicted.iterations < alone.iterations
    # the coarse level is the same contact, coarser: its rotation within a few per cent of
    # the fine one's move from the kept rotation
    g0, a = _gaps_at(model, contact, held)
    from_coarse = level.predict(g0[level.pick], a[level.pick], case.torque_Nmm, held.active,
                                None)
    assert from_coarse is not None
    move = alone.rotation - held.rotation
    assert from_coarse[1] == pytest.approx(move, rel=0.05)
    # and the points it predicts loaded are mostly the fine solution's
    loaded = alone.pressure > 0
    assert (from_coarse[0] & loaded).sum() >= 0.8 * loaded.sum()


def _gaps_at(model, contact, held):
    """The rigid gaps and rates of every point of ``contact`` at the kept rotation."""
    p = model.case.params
    return rigid_gap(model, contact, p.ratio * contact.beta + held.rotation,
                     contact.feet.copy())


def test_a_kept_contact_forms_its_coarse_level_once_it_is_solved_again_and_again(kept):
    _, case, held, level = kept
    levels = CoarseLevels()
    assert [levels.level(3, held.contact, case.thickness) for _ in range(AFTER - 1)] == \
        [None] * (AFTER - 1)
    formed = levels.level(3, held.contact, case.thickness)
    for each in (formed, level):
        each.form(np.arange(len(each.pick)))
    np.testing.assert_array_equal(formed.A, level.A)
    assert levels.level(3, held.contact, case.thickness) is formed   # kept, not formed again
    assert levels.level(4, held.contact, case.thickness) is None     # each phase its own

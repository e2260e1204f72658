"""A kept contact's foot circles (:mod:`fegear.toothpair.ring.circles`): the exact pair's gaps
at the kept rotation, the deviated pair's exact gaps to the third order in the points' move
about it, and a contact solved on them that is the one solved on the exact gaps."""

import numpy as np
import pytest

from fegear.geometry import Deviations, Placed, Runout, ToothDeviation, gear2_tooth
from fegear.toothpair.ring import contact as ring_contact
from fegear.toothpair.ring.circles import (
    MARGIN,
    TOLERANCE,
    circle_gaps,
    foot_circles,
    moved,
    projected,
    unsure,
)
from fegear.toothpair.ring.contact import Iterations, rigid_gap, solve_ring_contact, solve_with
from fegear.toothpair.ring.influence import ColumnRule, assemble_contact
from fegear.toothpair.ring.turning import turned


@pytest.fixture(scope="module")
def settled(baseline_200):
    return baseline_200.detail


def _both(settled, dev: Deviations, theta: float, circles):
    """The exact and the circles' gaps and rates of the settled contact's points under
    ``dev`` with gear 1 turned ``theta`` beyond the kinematic angle."""
    model, contact = settled.model, settled.contact
    p = model.case.params
    placed = Placed(dev, p, contact.beta) if dev else None
    at = turned(model, contact, 0, contact.beta, placed)
    exact = rigid_gap(model, at, p.ratio * contact.beta + theta, at.feet.copy())
    return exact, circle_gaps(circles, moved(circles, model, at), theta)


def test_the_circles_give_the_exact_pairs_gaps_at_the_kept_rotation(settled):
    theta = settled.solution.rotation
    circles = foot_circles(settled.model, settled.contact, theta)
    (g, a), (gc, ac) = _both(settled, Deviations(), theta, circles)
    assert np.abs(gc - g).max() < 1e-12
    assert np.abs(ac - a).max() < 1e-9 * np.abs(a).max()


def _deviations(settled, um: float) -> dict[str, Deviations]:
    """One deviation of each kind, ``um`` large, on the most loaded tooth and its mate."""
    contact, pressure = settled.contact, settled.solution.pressure
    top = int(np.argmax(pressure))
    tooth = int(contact.teeth[top])
    mate = int(gear2_tooth(contact.feet[top:top + 1], settled.case.params.z2)[0])
    return {"pitch 1": Deviations({tooth: ToothDeviation(pitch=um)}),
            "slope 1": Deviations({tooth: ToothDeviation(slope=um)}),
            "form 1": Deviations({tooth: ToothDeviation(form=um)}),
            "pitch 2": Deviations(gear2={mate: ToothDeviation(pitch=um)}),
            "slope 2": Deviations(gear2={mate: ToothDeviation(slope=um)}),
            "form 2": Deviations(gear2={mate: ToothDeviation(form=um)}),
            "centre distance": Deviations(centre_distance=um),
            "runout 1": Deviations(runout1=Runout(2 * um, 30)),
            "runout 2": Deviations(runout2=Runout(2 * um, 200))}


KINDS = ("pitch 1", "slope 1", "form 1", "pitch 2", "slope 2", "form 2", "centre distance",
         "runout 1", "runout 2")


@pytest.mark.parametrize("kind", KINDS)
def test_the_circles_follow_the_deviated_gaps_to_the_third_order(settled, kind):
    # a class-6 move: 10 µm on a tooth and 2e-4 rad of rotation (9 µm of arc), then half;
    # on the points within 50 µm of closing
    theta = settled.solution.rotation
    circles = foot_circles(settled.model, settled.contact, theta)
    errors = []
    for scale in (1.0, 0.5):
        dev = _deviations(settled, 10.0 * scale)[kind]
        (g, a), (gc, ac) = _both(settled, dev, theta + 2e-4 * scale, circles)
        near = g < g.min() + 0.05
        errors.append(np.abs(gc - g)[near].max())
        assert np.abs(ac - a)[near].max() < 1e-4 * np.abs(a[near]).max()
    assert errors[0] < TOLERANCE
    assert errors[0] / errors[1] > 5.0    # third order: 8


def _every_kind(contact, p, um: float) -> Deviations:
    """Pitches of ±1.5 ``um`` alternating on the contact's teeth and their slopes −``um``,
    gear 2's forms ``um``, the centre distance ``um`` and gear 1's runout 2 ``um`` (µm)."""
    return Deviations({int(t): ToothDeviation(pitch=1.5 * um * (-1) ** int(t), slope=-um)
                       for t in set(contact.teeth)},
                      gear2={k: ToothDeviation(form=um) for k in range(p.z2)},
                      centre_distance=um, runout1=Runout(2.0 * um, 40))


def test_a_contact_solved_on_the_circles_is_the_one_solved_on_the_exact_gaps(settled):
    model, solved = settled.model, settled.contact
    p, torque = model.case.params, settled.case.torque * 1e3
    contact = assemble_contact(model, solved.grids, solved.beta, solved.turn,
                               ColumnRule(probes=False))
    theta = settled.solution.rotation
    circles = foot_circles(model, contact, theta)
    placed = Placed(_every_kind(contact, p, 1.0), p, contact.beta)
    on_circles = solve_with(model, turned(model, contact, 0, contact.beta, placed), torque,
                            theta, Iterations(start=settled.solution.pressure > 0,
                                              circles=circles))
    exact = solve_ring_contact(model, turned(model, contact, 0, contact.beta, placed),
                               torque, theta, start=settled.solution.pressure > 0)
    assert on_circles.rotation != pytest.approx(theta, rel=1e-3)   # the deviations tell
    assert on_circles.rotation == pytest.approx(exact.rotation, rel=1e-5)
    top = exact.pressure.max()
    assert np.abs(on_circles.pressure - exact.pressure).max() < 2e-3 * top


@pytest.mark.parametrize("kind", KINDS)
def test_the_points_the_circles_tell_open_are_open_on_the_exact_gaps(settled, kind):
    # a class-9 move (30 µm on a tooth, 6e-4 rad of rotation) under the settled pressures:
    # every point the circles settle is open on the exact gaps, the circles' error within a
    # twentieth of the margin they are read with
    model, contact, sol = settled.model, settled.contact, settled.solution
    theta = sol.rotation
    circles = foot_circles(model, contact, theta)
    dev = _deviations(settled, 30.0)[kind]
    placed = Placed(dev, model.case.params, contact.beta)
    at = turned(model, contact, 0, contact.beta, placed)
    elastic = sol.gap - rigid_gap(model, contact, contact.turn + theta, contact.feet.copy())[0]
    (g, _), (gc, _) = _both(settled, dev, theta + 6e-4, circles)
    points = projected(circles, moved(circles, model, at))
    gu, _, exact = unsure(model, points, theta + 6e-4, elastic, sol.pressure > 0)
    assert np.array_equal(gu, gc)
    assert np.abs(gc - g).max() < MARGIN / 20
    assert (g + elastic)[~exact].min() > 0
    # and it settles every point left open by more than twice the margin
    assert not (exact & (sol.pressure == 0) & (g + elastic > 2 * MARGIN)).any()


def test_a_brief_solve_measures_fewer_points_exactly_for_the_same_contact(settled,
                                                                          monkeypatch):
    model, solved = settled.model, settled.contact
    p, torque = model.case.params, settled.case.torque * 1e3
    contact = assemble_contact(model, solved.grids, solved.beta, solved.turn, ColumnRule())
    assert contact.complete    # as a kept contact: every column formed
    theta = settled.solution.rotation
    circles = foot_circles(model, contact, theta)
    placed = Placed(_every_kind(contact, p, 2.0), p, contact.beta)
    measured = []
    exact_gap = ring_contact.rigid_gap

    def counted(model, contact, turn, feet=None, idx=None):
        measured.append(contact.npoints if idx is None else len(idx))
        return exact_gap(model, contact, turn, feet, idx)

    monkeypatch.setattr(ring_contact, "rigid_gap", counted)
    solved = {}
    for brief in (False, True):
        measured.clear()
        solved[brief] = solve_with(
            model, turned(model, contact, 0, contact.beta, placed), torque, theta,
            Iterations(start=settled.solution.pressure > 0, circles=circles, brief=brief))
        solved[brief, "points"] = sum(measured)
    full, brief = solved[False], solved[True]
    loaded = full.pressure > 0
    assert np.array_equal(brief.pressure > 0, loaded)
    assert brief.rotation == pytest.approx(full.rotation, rel=1e-9)
    assert np.abs(brief.pressure - full.pressure).max() < 1e-6 * full.pressure.max()
    assert solved[True, "points"] < solved[False, "points"] / 2


def _direct(circles, moved_points, theta):
    """The gaps, rates and slides of the moved points measured to their circles as vectors:
    turned, offset, turned back with gear 2's tooth, then the foot's normal and tangent."""
    from fegear.planar import rotate, rotate_by

    lever = rotate(moved_points.x, theta) + moved_points.offset
    point = lever + moved_points.axis
    if moved_points.turn2 is not None:
        c, s = moved_points.turn2[0], -moved_points.turn2[1]
        point, lever = rotate_by(point, c, s), rotate_by(lever, c, s)
    u = point - circles.foot
    d = np.einsum("ij,ij->i", u, circles.normal)
    s = np.einsum("ij,ij->i", u, circles.tangent)
    k = circles.kappa
    bend = 1.0 - k * d
    q = np.hypot(bend, k * s)
    gap = (2.0 * d - k * (d * d + s * s)) / (1.0 + q) - moved_points.flank1
    placed, k2 = moved_points.gear2
    slid = circles.foot + (s[:, None] * circles.tangent
                           + (k * s * s / (q + bend))[:, None] * circles.normal) / q[:, None]
    gap -= placed.deviations.flank_offset(2, k2, placed.roll(2, slid))
    grad = (bend[:, None] * circles.normal - (k * s)[:, None] * circles.tangent) / q[:, None]
    return gap, grad[:, 1] * lever[:, 0] - grad[:, 0] * lever[:, 1], s


def test_the_projected_points_measure_what_the_moved_points_measure_at_any_turn(settled):
    model, contact = settled.model, settled.contact
    p = model.case.params
    theta = settled.solution.rotation
    circles = foot_circles(model, contact, theta)
    dev = Deviations({int(t): ToothDeviation(pitch=4.0, slope=-3.0, form=2.0)
                      for t in set(contact.teeth)},
                     gear2={k: ToothDeviation(pitch=-3.0, form=3.0) for k in range(p.z2)},
                     centre_distance=5.0, runout1=Runout(8.0, 40), runout2=Runout(6.0, 100))
    at = turned(model, contact, 0, contact.beta, Placed(dev, p, contact.beta))
    points = moved(circles, model, at)
    some = np.arange(3, contact.npoints, 7)
    for turn in (theta, theta + 3e-4, theta - 1e-3):
        gap, rate, slide = _direct(circles, points, turn)
        every = projected(circles, points).measured(turn)
        taken = projected(circles, points).take(some).measured(turn)
        for got in (every, tuple(v[some] for v in every), taken):
            sel = slice(None) if len(got[0]) == len(gap) else some
            assert np.abs(got[0] - gap[sel]).max() < 1e-12
            assert np.abs(got[1] - rate[sel]).max() < 1e-12 * np.abs(rate).max()
            assert np.abs(got[2] - slide[sel]).max() < 1e-12


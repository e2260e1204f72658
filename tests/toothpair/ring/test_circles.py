"""A kept contact's foot circles (:mod:`fegear.toothpair.ring.circles`): the exact pair's gaps
at the kept rotation, the deviated pair's exact gaps to the third order in the points' move
about it, and a contact solved on them that is the one solved on the exact gaps."""

import numpy as np
import pytest

from fegear.geometry import Deviations, Placed, Runout, ToothDeviation, gear2_tooth
from fegear.toothpair.ring.circles import TOLERANCE, circle_gaps, foot_circles, moved
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


def test_a_contact_solved_on_the_circles_is_the_one_solved_on_the_exact_gaps(settled):
    model, solved = settled.model, settled.contact
    p, torque = model.case.params, settled.case.torque * 1e3
    contact = assemble_contact(model, solved.grids, solved.beta, solved.turn,
                               ColumnRule(probes=False))
    theta = settled.solution.rotation
    circles = foot_circles(model, contact, theta)
    dev = Deviations({int(t): ToothDeviation(pitch=1.5 * (-1) ** int(t), slope=-1.0)
                      for t in set(contact.teeth)},
                     gear2={k: ToothDeviation(form=1.0) for k in range(p.z2)},
                     centre_distance=1.0, runout1=Runout(2.0, 40))
    placed = Placed(dev, p, contact.beta)
    on_circles = solve_with(model, turned(model, contact, 0, contact.beta, placed), torque,
                            theta, Iterations(start=settled.solution.pressure > 0,
                                              circles=circles))
    exact = solve_ring_contact(model, turned(model, contact, 0, contact.beta, placed),
                               torque, theta, start=settled.solution.pressure > 0)
    assert on_circles.rotation != pytest.approx(theta, rel=1e-3)   # the deviations tell
    assert on_circles.rotation == pytest.approx(exact.rotation, rel=1e-5)
    top = exact.pressure.max()
    assert np.abs(on_circles.pressure - exact.pressure).max() < 2e-3 * top

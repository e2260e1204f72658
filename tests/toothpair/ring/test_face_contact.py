"""The contact across the face (:mod:`fegear.toothpair.ring.face_contact`): an even face is
the 2D pair's solution in every section; the
iterative solve is the bordered system's exact solution on its active set, complementary and
in balance, its gaps those of the rigid teeth, the offsets and the face's approach formed
anew; neither the first linearisation's loose solves nor the preconditioner's rank change
the solution; a misalignment loads the end it closes; a helix slope on one tooth moves that
tooth's load alone towards the end it closes; a spread of its own between different teeth
(``across``) acts there alone: the same spread as the tooth's gives the same solution, an even
face stays the 2D pair's, and a misaligned one is the dense system with it solved."""

from dataclasses import replace

import numpy as np
import pytest

from fegear.fe import blas_threads
from fegear.running import SERIAL
from fegear.toothpair.face import Face
from fegear.toothpair.positions import positions_of
from fegear.toothpair.ring import face_contact
from fegear.toothpair.ring.contact import rigid_gap, solve_ring_contact
from fegear.toothpair.ring.face import exponential_kernel, face_coupling, tilted_across
from fegear.toothpair.ring.face_contact import FaceStart, solve_face_contact
from fegear.toothpair.ring.influence import near_field
from fegear.toothpair.ring.solver import RingSolver, SolverModes

SECTIONS = 7
COUPLING = face_coupling(SECTIONS, 5.0, exponential_kernel(1.5))


@pytest.fixture(scope="module")
def kept(baseline_ring):
    """The baseline at β = 0 under 200 N·m on its kept contact (coarse): the contact, what
    was kept and the case."""
    case = replace(baseline_ring.case, torque=200.0)
    solver = RingSolver(baseline_ring, SolverModes(keep_phases=True))
    positions_of(solver, False)(case, (0.0,), SERIAL)
    contact, kept = solver.phases.contact_at(baseline_ring, case)
    return baseline_ring, contact, kept, case


def _solve(kept, face: Face, coupling=COUPLING):
    model, contact, k, case = kept
    turn = case.params.ratio * contact.beta + k.rotation
    offsets = face.offsets(contact, turn, coupling.zeta, case.thickness, case.params.z2)
    with blas_threads():
        return solve_face_contact(model, contact, FaceStart(k.rotation, k.active,
                                                            1e-3 * k.elastic_um),
                                  case.torque_Nmm, offsets, coupling), offsets


def test_an_even_face_is_the_2d_pair_in_every_section(kept):
    model, contact, k, case = kept
    solved, _ = _solve(kept, Face(SECTIONS))
    alone = solve_ring_contact(model, contact, case.torque_Nmm, k.rotation, start=k.active)
    assert solved.rotation == pytest.approx(alone.rotation, rel=1e-12)
    for s in range(SECTIONS):
        np.testing.assert_allclose(solved.pressure[:, s], alone.pressure, rtol=0,
                                   atol=1e-9 * alone.pressure.max())


def test_the_solution_is_the_bordered_system_solved_directly_complementary_and_balanced(kept):
    model, contact, k, case = kept
    solved, offsets = _solve(kept, Face(SECTIONS, misalignment=8.0))
    p = solved.pressure
    assert (p >= 0).all()
    scale = 1e-9 * np.abs(solved.gap).max()
    assert solved.gap.min() >= -scale                        # no overlap anywhere
    assert np.abs(solved.gap[p > 0]).max() <= scale          # closed where it presses
    w = (contact.weight * case.thickness)[:, None] * COUPLING.share[None, :]
    alpha = case.params.ratio * contact.beta
    _, a = rigid_gap(model, contact, alpha + solved.rotation, contact.feet.copy())
    torque = -np.sum(w * p * a[:, None])
    assert torque == pytest.approx(case.torque_Nmm, rel=1e-9)
    # the same active set solved densely: A_hp ⊗ 1 + A_fe ⊗ S on its points
    near = near_field(model, contact)
    far = contact.A - near
    pts, sec = np.nonzero(p > 0)
    dense = far[np.ix_(pts, pts)] * COUPLING.spread[np.ix_(sec, sec)] \
        + near[np.ix_(pts, pts)] * (sec[:, None] == sec[None, :])
    g = solved.gap[pts, sec] - (dense @ p[pts, sec])        # the rigid part at the solution
    np.testing.assert_allclose(np.linalg.solve(dense, -g), p[pts, sec],
                               rtol=1e-8, atol=1e-8 * p.max())


def test_the_gaps_are_formed_anew_and_complementary_to_the_pressures(kept):
    """The KKT conditions on gaps formed from the solution's pressures and rotation alone
    (rigid gaps, offsets, near field in its section, finite-element part spread): p ≥ 0, no
    overlap, closed where it presses, the torque carried."""
    model, contact, k, case = kept
    solved, offsets = _solve(kept, Face(SECTIONS, misalignment=-8.0, crowning=4.0))
    p = solved.pressure
    alpha = case.params.ratio * contact.beta
    rigid, a = rigid_gap(model, contact, alpha + solved.rotation, contact.feet.copy())
    near = near_field(model, contact)
    gap = rigid[:, None] + offsets + (contact.A - near) @ p @ COUPLING.spread.T + near @ p
    scale = 1e-9 * np.abs(gap).max()
    np.testing.assert_allclose(solved.gap, gap, rtol=0, atol=scale)
    assert (p >= 0).all() and gap.min() >= -scale
    assert np.abs(gap * p).max() <= scale * p.max()
    assert (p > 0).sum(axis=0).min() > 0                       # every section carries
    w = (contact.weight * case.thickness)[:, None] * COUPLING.share[None, :]
    assert -np.sum(w * p * a[:, None]) == pytest.approx(case.torque_Nmm, rel=1e-9)


def test_neither_the_loose_first_solves_nor_the_rank_change_the_solution(kept, monkeypatch):
    face = Face(SECTIONS, misalignment=8.0)
    solved, _ = _solve(kept, face)
    monkeypatch.setattr(face_contact, "FIRST_TOL", face_contact.GMRES_TOL)
    monkeypatch.setattr(face_contact, "RANK", 2)
    tight, _ = _solve(kept, face)
    np.testing.assert_array_equal(tight.pressure > 0, solved.pressure > 0)
    np.testing.assert_allclose(tight.pressure, solved.pressure, rtol=0,
                               atol=1e-8 * solved.pressure.max())
    assert tight.rotation == pytest.approx(solved.rotation, rel=1e-11)


def test_a_misalignment_loads_the_end_it_closes_and_keeps_the_torque(kept):
    model, contact, k, case = kept
    ends = []
    for f in (6.0, -6.0):
        solved, _ = _solve(kept, Face(SECTIONS, misalignment=f))
        line = solved.line_loads(contact).sum(axis=0)        # N/mm, all teeth, by section
        ends.append(line[[0, -1]])
        assert (line * COUPLING.share).sum() * case.thickness > 0
    (first_pos, second_pos), (first_neg, second_neg) = ends
    assert second_pos > 1.3 * first_pos and first_neg > 1.3 * second_neg
    assert second_pos == pytest.approx(first_neg, rel=1e-6)  # the same pair mirrored


def test_a_helix_slope_moves_its_own_tooths_load_to_the_end_it_closes(kept):
    model, contact, k, case = kept
    even, _ = _solve(kept, Face(SECTIONS))
    loads = even.line_loads(contact)
    k_most = int(np.argmax(loads[:, 0]))
    tooth = contact.grids[k_most].tooth
    sloped, _ = _solve(kept, Face(SECTIONS, helix1=((tooth, 5.0, 0.0),)))
    line = sloped.line_loads(contact)
    assert line[k_most, -1] > 1.2 * line[k_most, 0]
    others = [i for i in range(len(contact.grids)) if i != k_most and loads[i, 0] > 0]
    for i in others:     # the others take what it sheds at its first end, there
        assert line[i, 0] >= loads[i, 0]


def test_a_spread_between_teeth_acts_between_them_alone(kept):
    model, contact, k, case = kept
    misaligned = Face(SECTIONS, misalignment=8.0)
    plain, _ = _solve(kept, misaligned)
    same, _ = _solve(kept, misaligned, replace(COUPLING, across=COUPLING.spread))
    np.testing.assert_allclose(same.pressure, plain.pressure, rtol=0,
                               atol=1e-9 * plain.pressure.max())
    alone = solve_ring_contact(model, contact, case.torque_Nmm, k.rotation, start=k.active)
    near = near_field(model, contact)
    far = contact.A - near
    tooth = np.array([g.tooth for g in contact.grids])[contact.grid_index]
    apart = np.abs(tooth[:, None] - tooth[None, :])
    apart = np.minimum(apart, case.params.z1 - apart)
    alpha = case.params.ratio * contact.beta
    for coupling in (tilted_across(COUPLING, 0.3), tilted_across(COUPLING, 0.3, -0.3)):
        even, _ = _solve(kept, Face(SECTIONS), coupling)        # their rows sum to one too
        for s in range(SECTIONS):
            np.testing.assert_allclose(even.pressure[:, s], alone.pressure, rtol=0,
                                       atol=1e-9 * alone.pressure.max())
        solved, offsets = _solve(kept, misaligned, coupling)
        p = solved.pressure
        assert not np.allclose(p, plain.pressure, rtol=0, atol=1e-3 * p.max())
        rigid, _ = rigid_gap(model, contact, alpha + solved.rotation, contact.feet.copy())
        approach = sum((far * (apart == d)) @ p @ coupling.between(d).T
                       for d in np.unique(apart))
        gap = rigid[:, None] + offsets + approach + near @ p
        scale = 1e-9 * np.abs(gap).max()
        np.testing.assert_allclose(solved.gap, gap, rtol=0, atol=scale)
        assert (p >= 0).all() and gap.min() >= -scale
        assert np.abs(gap * p).max() <= scale * p.max()

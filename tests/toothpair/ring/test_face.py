"""What varies across the face and the coupling of its sections
(:mod:`fegear.toothpair.ring.face`): the spread keeps an even load even and reads the same from
either end; each input moves the sections' rigid gaps as its definition says."""

import numpy as np
import pytest

from fegear.toothpair.face import Face
from fegear.toothpair.ring.face import (
    NEIGHBOUR_TILTS,
    TWIST_TABLE,
    exponential_kernel,
    face_coupling,
    measured_kernel,
    neighbour_tilts,
    product_coupling,
    twist_of,
)


class _Contact:
    """Three points: gear-1 teeth 4, 4 and 5, normals along −x, +y and −x (gear 1's frame),
    facing gear-2 teeth 0, 1 and 2."""

    normal = np.array([[-1.0, 0.0], [0.0, 1.0], [-1.0, 0.0]])
    teeth = np.array([4, 4, 5])
    feet = 2 * np.pi * np.array([0.0, 1.0, 2.0]) / 45


def test_the_spread_keeps_an_even_and_a_linear_load_and_reads_the_same_from_either_end():
    for sections, decay in ((2, 0.5), (9, 1.5), (17, 20.0)):
        c = face_coupling(sections, 5.0, exponential_kernel(decay))
        z = c.zeta * 5.0
        np.testing.assert_allclose(c.spread.sum(axis=1), 1.0, rtol=0, atol=1e-13)
        np.testing.assert_allclose(c.spread @ z, z, rtol=0, atol=1e-12)
        assert c.share.sum() == pytest.approx(1.0, abs=1e-15)
        np.testing.assert_allclose(c.spread[::-1, ::-1], c.spread, atol=1e-13)
    short = face_coupling(9, 5.0, exponential_kernel(0.05)).spread  # the tooth alone:
    assert np.diag(short).min() > 0.8                               # little reaches along
    # a load at mid-face spreads to its neighbours, less the farther
    mid = face_coupling(9, 5.0, exponential_kernel(1.5)).spread[4]
    assert mid[4] > mid[3] > mid[2] > mid[1] and mid[3] == pytest.approx(mid[5])


def test_each_input_moves_the_gaps_as_defined():
    zeta = np.array([-0.5, 0.0, 0.25, 0.5])
    c = _Contact()

    def um(**kw):
        return 1e3 * Face(**kw).offsets(c, 0.0, zeta, 5.0, 45)

    # a misalignment closes the second end on a flank whose normal faces −x, by ζ f
    np.testing.assert_allclose(um(misalignment=10.0)[0], -10.0 * zeta)
    np.testing.assert_allclose(um(misalignment=10.0)[1], 0.0, atol=1e-12)
    np.testing.assert_allclose(um(tilt=4.0)[1], -4.0 * zeta)      # the centre distance
    np.testing.assert_allclose(um(crowning=6.0)[2], [6.0, 0.0, 1.5, 6.0])
    # an end relief of 3 µm over 1 mm of a 5 mm face: from 1.5 mm off the middle
    np.testing.assert_allclose(um(end_relief=3.0, end_length=1.0)[0], [3.0, 0.0, 0.0, 3.0])
    helix = um(helix1=((5, 2.0, 1.0),))
    np.testing.assert_allclose(helix[:2], 0.0)
    np.testing.assert_allclose(helix[2], -2.0 * zeta - 1.0 * (1 - 4 * zeta ** 2))
    gear2 = um(helix2=((1, 2.0, 0.0),))
    np.testing.assert_allclose(gear2[1], -2.0 * zeta)
    assert not gear2[[0, 2]].any()


def test_a_mirrored_spread_keeps_an_even_load_and_lets_a_linear_one_level_off_at_the_ends():
    # the measured coupling's form: each load's images in the free ends, rows scaled to one
    kernel = measured_kernel(2.0, 0.2)
    for sections in (2, 9, 17):
        c = face_coupling(sections, 5.0, kernel, mirror=True, correction="scale")
        np.testing.assert_allclose(c.spread.sum(axis=1), 1.0, rtol=0, atol=1e-13)
        np.testing.assert_allclose(c.spread[::-1, ::-1], c.spread, atol=1e-13)
        assert (c.spread >= 0).all()
    c = face_coupling(9, 5.0, kernel, mirror=True, correction="scale")
    slope = (c.spread @ c.zeta) / np.where(c.zeta, c.zeta, 1.0)
    # a linear load's far-field answer: its slope is smaller than the load's, the more so at
    # the ends (the 3D tooth's: 0.80 of the even load's at mid-face, 0.76 at the end patch)
    assert 0.5 < slope[0] < slope[1] < slope[3] < 1.0


def test_the_twist_keeps_an_even_load_and_a_mid_face_one_and_tilts_an_end_one():
    """The tooth's twist (c P1 P1ᵀ diag(share)) leaves every row's sum and the mid-face
    column as they were, reads the same from either end, and under a load at one end takes
    from the far end what it adds at the loaded one, linearly across the face."""
    kernel = measured_kernel(2.0, 0.2)
    for sections in (2, 9, 17):
        plain = face_coupling(sections, 5.0, kernel, mirror=True, correction="slope")
        twisted = face_coupling(sections, 5.0, kernel, mirror=True, correction="slope",
                                twist=0.3)
        np.testing.assert_allclose(twisted.spread.sum(axis=1), 1.0, rtol=0, atol=1e-13)
        np.testing.assert_allclose(twisted.spread[::-1, ::-1], twisted.spread, atol=1e-13)
        added = twisted.spread - plain.spread
        if sections % 2:
            np.testing.assert_allclose(added[:, sections // 2], 0.0, atol=1e-15)
        # a load at the first end: +0.3 · share at that end, −0.3 · share at the far one
        np.testing.assert_allclose(added[:, 0], -0.3 * 2 * twisted.zeta * twisted.share[0],
                                   atol=1e-15)


def test_the_measured_twist_is_read_from_its_table_by_the_face_in_tooth_heights():
    (b0, c0), (b1, c1) = TWIST_TABLE[:2]
    assert twist_of(2.0 * b0, 2.0) == pytest.approx(c0, abs=1e-12)
    assert twist_of(1.0 * (b0 + b1), 2.0) == pytest.approx(0.5 * (c0 + c1), abs=1e-12)
    assert twist_of(0.1, 2.0) == pytest.approx(c0, abs=1e-12)      # held at the table's ends
    assert twist_of(1e3, 2.0) == pytest.approx(TWIST_TABLE[-1][1], abs=1e-12)
    # shorter faces twist more: the end's tilt matters less as the face grows
    assert all(a[1] >= b[1] for a, b in zip(TWIST_TABLE, TWIST_TABLE[1:]))


def test_the_products_coupling_carries_the_twist_and_the_neighbours_tilts_of_its_width():
    width, h = 5.0, 2.0
    c = product_coupling(9, width, h, 0.2)
    plain = face_coupling(9, width, measured_kernel(h, 0.2), mirror=True, correction="slope")
    p1 = 2.0 * c.zeta - c.share @ (2.0 * c.zeta)
    np.testing.assert_allclose(c.spread - plain.spread,
                               twist_of(width, h) * np.outer(p1, p1 * c.share), atol=1e-14)
    tilts = neighbour_tilts(width, h)
    assert len(tilts) == len(NEIGHBOUR_TILTS[0][1]) == len(c.across)
    for apart in range(1, len(tilts) + 2):       # the last spread for the teeth farther
        spread = c.between(apart)
        np.testing.assert_allclose(spread.sum(axis=1), 1.0, atol=1e-14)   # even stays even
        # a load at the first end moves a neighbour linearly, by its distance's tilt
        tilt = tilts[min(apart, len(tilts)) - 1]
        np.testing.assert_allclose(spread[:, 0] / c.share[0], 1.0 + tilt * p1 * p1[0],
                                   atol=1e-12)
    np.testing.assert_array_equal(c.between(0), c.spread)


def test_the_neighbours_tilts_are_read_from_their_table_by_the_face_in_tooth_heights():
    widths = [b for b, _ in NEIGHBOUR_TILTS]
    assert widths == sorted(widths)
    first, last = NEIGHBOUR_TILTS[0], NEIGHBOUR_TILTS[-1]
    assert neighbour_tilts(2.0 * first[0], 2.0) == pytest.approx(first[1], abs=1e-12)
    assert neighbour_tilts(0.1, 2.0) == pytest.approx(first[1], abs=1e-12)   # held
    assert neighbour_tilts(1e3, 2.0) == pytest.approx(last[1], abs=1e-12)
    (b0, t0), (b1, t1) = NEIGHBOUR_TILTS[:2]                  # linear between its widths
    np.testing.assert_allclose(neighbour_tilts(b0 + b1, 2.0),
                               0.5 * (np.array(t0) + np.array(t1)), atol=1e-12)


def test_the_measured_kernel_is_the_3d_tooths_less_the_near_field():
    h, share = 2.0, 0.25
    kernel, whole = measured_kernel(h, share), measured_kernel(h, 0.0)
    x = np.linspace(0.0, 5.0 * h, 20001)
    mass = 2.0 * np.trapezoid(whole(x), x)
    assert mass == pytest.approx(1.0, abs=0.03)        # the 3D answer per the even load's
    # the near field's share comes off the first hat: the rest is the finite-element part's
    np.testing.assert_allclose(2.0 * np.trapezoid(kernel(x), x), (mass - share) / (1 - share),
                               rtol=1e-3)
    assert kernel(np.array([3.0]))[0] == pytest.approx(whole(np.array([3.0]))[0] / (1 - share))
    assert np.all(np.diff(whole(x)) <= 1e-15)          # it never rises with the distance
    # in tooth heights: a tooth twice as high reaches twice as far
    assert measured_kernel(2 * h, 0.0)(np.array([2.0 * 3.0]))[0] == pytest.approx(
        0.5 * whole(np.array([3.0]))[0])

"""The sector model's scene: profile segments, the gear-1 sector, refinement zones, tooth choice and
the Hertz radii at the contact points."""

import math
from types import SimpleNamespace

import numpy as np
import pytest

from fegear.geometry.clearance import ToothContact
from fegear.geometry.gear1 import Gear1Profile
from fegear.geometry.gear2 import gear2_curve
from fegear.geometry.tip_edge import RoundedProfile
from fegear.planar import rotate
from fegear.toothpair.segments import (
    SHORT,
    SPLINE_CHORD,
    Layout,
    PolarCurve,
    profile_segments,
    sampled,
)
from fegear.toothpair.teeth import candidate_data, choose_teeth
from fegear.verify.sector import SectorCase
from fegear.verify.sector.scene import build_scene, tooth_run


def circle(phi):
    return 10.0 * np.column_stack([np.cos(phi), np.sin(phi)])


CIRCLE = PolarCurve(circle)


def test_profile_segments_are_contiguous_with_windows_over_roots():
    windows = [("w1", 0.30, 0.10), ("w2", 0.45, 0.10)]       # overlapping windows
    roots = [("r1", 0.20, 0.05), ("r2", 0.50, 0.02), ("r3", 0.40, 0.3)]  # r3 around all
    marks = [(0.05, 0.1, "edge")]
    segs, names = profile_segments("p", CIRCLE, 0.0, 1.0, Layout(windows, roots, marks))
    for s0, s1 in zip(segs, segs[1:]):
        assert np.allclose(s0.points[-1], s1.points[0], atol=1e-12)
    assert np.allclose(segs[0].points[0], circle(np.array([0.0]))[0])
    assert np.allclose(segs[-1].points[-1], circle(np.array([1.0]))[0])
    seg_names = [s.name for s in segs]
    assert seg_names.count("w1") == 1 and seg_names.count("w2") == 1
    w1 = segs[seg_names.index("w1")].points
    w2 = segs[seg_names.index("w2")].points
    ang = lambda p: np.arctan2(p[:, 1], p[:, 0])  # noqa: E731
    assert ang(w1)[-1] == pytest.approx(0.375) and ang(w2)[0] == pytest.approx(0.375)
    assert "r2" not in names  # wholly inside window w2
    seg_names = [s.name for s in segs]
    assert seg_names.count("r3") == 2  # split by the windows and r1, one name for both pieces
    zoned = [s for s in segs if s.zone == "edge"]
    ang0 = ang(np.vstack([z.points for z in zoned]))
    assert ang0.min() == pytest.approx(0.05) and ang0.max() == pytest.approx(0.1)
    assert sum(s.zone is None for s in segs) == len(segs) - len(zoned)


def test_profile_segments_with_many_zones_stay_contiguous():
    # a sector of 20 tooth spaces: every root is cut against every piece placed before it
    roots = [(f"r{k}", 0.05 * k + 0.025, 0.01) for k in range(20)]
    windows = [(f"w{k}", 0.05 * k + 0.04, 0.012) for k in range(0, 20, 2)]
    segs, names = profile_segments("p", CIRCLE, 0.0, 1.0, Layout(windows, roots))
    for s0, s1 in zip(segs, segs[1:]):
        assert np.allclose(s0.points[-1], s1.points[0], atol=1e-12)
    assert len([n for n in names if n.startswith("r")]) == 20


def test_profile_segments_with_nested_windows_stay_contiguous():
    # a long contact path (w8) around shorter ones, as for a conformal, unmodified pair
    windows = [("w8", 0.30, 0.28), ("w9", 0.32, 0.05), ("w10", 0.40, 0.15), ("w11", 0.45, 0.01)]
    segs, names = profile_segments("p", CIRCLE, 0.0, 1.0, Layout(windows))
    for s0, s1 in zip(segs, segs[1:]):
        assert np.allclose(s0.points[-1], s1.points[0], atol=1e-12)
    seg_names = [s.name for s in segs]
    assert all(seg_names.count(n) == 1 for n, _, _ in windows)  # each one connected piece
    ang = np.arctan2(*np.vstack([s.points for s in segs])[:, ::-1].T)
    assert np.all(np.diff(ang) >= -1e-12)


def test_gear2_is_refined_like_the_rounds_and_gear1_reaches_beyond(baseline):
    p = baseline
    profile = Gear1Profile(p)
    state = ToothContact(p, profile).state(0.0)
    teeth = choose_teeth(state, 15.0)
    case = SectorCase(p, torque=200.0, quality="fast", rim1=6.0, rim2=6.0, extra_teeth=2,
                     tip_round=0.25)
    scene = build_scene(case, profile, [(0.0, state)], teeth)
    size1 = {r.segments[0]: r.size for r in scene.gear1.refinements}
    size2 = {r.segments[0]: r.size for r in scene.gear2.refinements}
    assert size2["g2_round"] == size1["g1_round"] < size1[f"g1_contact_{scene.paired[0]}"]
    assert size1["g1_junction"] < size1["g1_round"]
    spans2 = [np.arctan2(s.points[:, 1], s.points[:, 0])
              for s in scene.gear2.outer if s.zone == "g2_round"]
    rounds1 = [s.points for s in scene.gear1.outer if s.zone in ("g1_round", "g1_junction")]
    spans1 = [np.arctan2(q[:, 1], q[:, 0]) for q in rounds1]
    # both tangent points of every refined round sit in a junction zone
    junctions = [np.arctan2(s.points[:, 1], s.points[:, 0])
                 for s in scene.gear1.outer if s.zone == "g1_junction"]
    refined = 0
    for c, h, _ in scene.shape.fillet_angles(range(-1, p.z1 + 1)):
        if any(a.min() <= c <= a.max() for a in spans1):
            refined += 1
            for t in (c - h, c + h):  # on both sides: the tangent point is also a cut
                assert any(a.min() < t - 1e-9 < a.max() for a in junctions)
                assert any(a.min() < t + 1e-9 < a.max() for a in junctions)
    assert refined >= 2
    # the tangent points of every round within a module of a window, refined or not, end a
    # segment: one spline through a curvature jump overshoots by µm (inverted elements at
    # 0.01 N·m); those further away do not (a sliver at `coarse` with f1 = 0)
    ends = np.concatenate([np.arctan2(s.points[[0, -1], 1], s.points[[0, -1], 0])
                           for s in scene.gear1.outer])
    windows = [np.arctan2(s.points[:, 1], s.points[:, 0]) for s in scene.gear1.outer
               if s.name.startswith("g1_contact_")]
    lo, hi = ends.min(), ends.max()
    reach = p.m / 45.0  # a module of arc at gear 1's tip radius
    cut = {True: 0, False: 0}
    for c, h, _ in scene.shape.fillet_angles(range(-1, p.z1 + 1)):
        for t in (c - h, c + h):
            t = lo + np.mod(t - lo, 2 * np.pi)
            if t < hi:
                near = min(min(abs(t - w.min()), abs(t - w.max())) for w in windows)
                if near < 0.8 * reach:
                    assert np.abs(ends - t).min() < 1e-12
                    cut[True] += 1
                elif near > 1.2 * reach:
                    assert np.abs(ends - t).min() > 1e-9
                    cut[False] += 1
    assert cut[True] >= 4 and cut[False] >= 4
    close = 0
    for q in rounds1:  # the refined rounds (with their spill onto the flank)
        on = scene.shape.on_round(np.arctan2(q[:, 1], q[:, 0]))
        x = q[on] + np.array([0.0, p.e])  # the round proper, placed at β = 0
        if not len(x) or scene.curve2.closest(x)[2].min() > 0.02:
            continue
        close += 1  # a round within 20 µm of gear 2: gear 2 under it has the round's size
        th = np.arctan2(x[:, 1], x[:, 0])
        assert all(any(a.min() <= t <= a.max() for a in spans2) for t in th)
    assert close >= 2
    # … and wherever gear 2's strip is within 20 µm of gear 1, gear 1 (the contact slave) has
    # the round's size too: the slave is never coarser than the master
    checked = 0
    for s in (s for s in scene.gear2.outer if s.zone == "g2_round"):
        y = s.points - np.array([0.0, p.e])  # in gear 1's frame at β = 0
        phi = np.arctan2(y[:, 1], y[:, 0])
        near = np.abs(np.hypot(y[:, 0], y[:, 1]) - scene.shape.radius(phi)) < 0.02
        checked += near.sum()
        assert all(any(a.min() <= t <= a.max() for a in spans1) for t in phi[near])
    assert checked > 0


def clearance_state(plus_um):
    return SimpleNamespace(teeth=[SimpleNamespace(tooth=k, plus_um=c)
                                  for k, c in enumerate(plus_um)])


def test_choose_teeth_pairs_rigid_closures_and_elastic_neighbours():
    # closure 10 µm: rigid threshold 13 µm; within 2 teeth of a closed one 1.5·10 + 3 = 18 µm
    state = clearance_state([4, 17, 60, 60, 16, 60, 60, 60, None, 19, 14.5])
    # 10 (14.5) and 1 (17) are neighbours of 0 (across the wrap); 4 (16) is too far away;
    # 9 (19) is a neighbour but above 18 µm
    assert choose_teeth(state, 10.0) == (0, 1, 10)
    assert choose_teeth(state, 10.0, widen=1) == (0, 1, 2, 9, 10)  # 8 has no + flank
    # nothing within reach: the closest tooth is still paired
    assert choose_teeth(clearance_state([30, 20, 40]), 1.0) == (1,)


def test_hertz_radii_are_those_of_the_gap_once_the_clearance_is_closed(baseline):
    # on the baseline's nearly conformal flanks 1/R* is a small difference of two curvatures
    # near 0.1 /mm, and gear 2's changes fast: taken 6 µm away (where the gear-1 point sits
    # before the clearance closes) it came out half the true value
    p = baseline
    profile = Gear1Profile(p)
    beta = SectorCase(p).beta
    state = ToothContact(p, profile).state(beta)
    shape = RoundedProfile(profile, 0.25)
    first = sorted((c for c in state.teeth if c.plus_um is not None), key=lambda c: c.plus_um)
    cands = candidate_data(p, shape, state, tuple(c.tooth for c in first[:3]), beta)
    assert len(cands) == 3
    g2 = gear2_curve(p)
    for c in cands:
        phi = c.phi1 + np.linspace(-2e-5, 2e-5, 201)
        pts = shape.point(phi)
        closed = rotate(pts, p.ratio * beta + c.clearance_um * 1e-3 / p.r0) + np.array([0, p.e])
        gap = g2.closest(rotate(closed, -beta))[2]
        s = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(pts, axis=0).T))])
        s -= s[100]
        assert gap.min() == pytest.approx(0.0, abs=1e-9)
        assert np.argmin(gap) == 100
        relative = 2 * np.polyfit(s, gap, 2)[0]
        assert relative == pytest.approx(1 / c.radius1 + 1 / c.radius2, rel=1e-3)


@pytest.mark.parametrize("teeth, z, run", [
    ((3,), 10, (3, 0)),
    ((9, 10, 13, 22, 27), 44, (9, 18)),
    ((0, 43), 44, (43, 1)),                              # across the index wrap
    (tuple(range(7, 18)) + tuple(range(19, 31)), 44, (7, 23)),  # more than half the gear
])
def test_sector_is_the_shortest_run_of_teeth_holding_every_paired_tooth(teeth, z, run):
    # at 600 N·m the paired teeth span 230°: taken as the shorter way round from the first
    # index, the sector came out over 360° and gmsh could not mesh it
    assert tooth_run(teeth, z) == run


def test_a_nearly_radial_curve_is_sampled_evenly_in_arc_length():
    # r = 10 + 100 θ runs ten times faster than r dθ: points even in θ fell ten spacings apart
    def spiral(theta):
        r = 10.0 + 100.0 * theta
        return np.column_stack([r * np.cos(theta), r * np.sin(theta)])

    spacing = math.sqrt(8 * 0.5 * 1e-3)  # SPLINE_CHORD at 0.5 mm radius
    seg = sampled("s", PolarCurve(spiral), 0.0, 0.02)
    gaps = np.hypot(*np.diff(seg.points, axis=0).T)
    assert gaps.max() < 1.05 * spacing and gaps.min() > 0.9 * gaps.max()
    assert np.allclose(seg.points[[0, -1]], spiral(np.array([0.0, 0.02])))
    # a circle keeps its points even in polar angle
    arc = sampled("c", CIRCLE, 0.0, 0.5).points
    angles = np.arctan2(arc[:, 1], arc[:, 0])
    assert np.allclose(np.diff(angles), angles[1] - angles[0])


def test_a_tighter_curve_than_the_spacing_assumes_is_sampled_within_the_chord_error():
    # spaced for a 0.5 mm radius, an arc of 0.1 mm strayed 2.5 µm from its 8-point polyline
    # (gear 2's flanks at m = 0.5 turn at 0.26 mm: their nodes, snapped back, inverted elements)
    def small(theta):
        return 0.1 * np.column_stack([np.cos(theta), np.sin(theta)])

    pts = sampled("s", PolarCurve(small), 0.0, math.pi).points
    half_chord = 0.5 * np.hypot(*np.diff(pts, axis=0).T)
    assert np.max(0.1 - np.sqrt(0.1 ** 2 - half_chord ** 2)) <= SPLINE_CHORD
    assert np.allclose(pts[[0, -1]], small(np.array([0.0, math.pi])))


def test_a_boundary_piece_much_shorter_than_its_elements_joins_a_neighbour():
    # gear 1's round zone ended 0.6 µm before its root zone began: a 0.6 µm piece under
    # 57 µm elements, a sliver of shape quality 0.01
    sizes = {"r": 0.05, "round": 0.02, "p_flank": 0.1}
    jump = 0.6 + 2e-7  # a curvature jump 2 µm past the root's end (r dθ, r = 10 mm)
    marks = [(0.3, 0.4 - 1e-7, "round"), (jump, jump, None)]
    segs, names = profile_segments("p", CIRCLE, 0.0, 1.0,
                                   Layout(roots=[("r", 0.5, 0.1)], marks=marks, sizes=sizes))
    for s0, s1 in zip(segs, segs[1:]):
        assert np.allclose(s0.points[-1], s1.points[0], atol=1e-12)
    lengths = [np.hypot(*np.diff(s.points, axis=0).T).sum() for s in segs]
    assert min(lengths) > SHORT * min(sizes.values())
    assert names == ("p_flank", "r")
    ang = {(s.name, s.zone): np.arctan2(s.points[[0, -1], 1], s.points[[0, -1], 0])
           for s in segs}
    assert ang["p_flank", "round"] == pytest.approx([0.3, 0.4], abs=1e-12)  # zone 1 µm longer
    assert ang["r", None] == pytest.approx([0.4, jump], abs=1e-12)  # the root ends on the jump

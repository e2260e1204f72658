"""Drawings for manufacture (fegear/geometry/drawing.py), read back as a CAD program reads
them: the DXF's outline lies on the exact profile (relief, tip rounds and all) within the
stated chord error, its rounds are the solve's rounds; a deviated tooth sits off the exact one
by its deviation, and no other tooth does; the STEP solid carries the profile on its faces to
the kernel's tolerance."""

import math

import numpy as np
import pytest

from fegear.geometry import (
    Deviations,
    PairParameters,
    Placed,
    RoundedProfile,
    ToothDeviation,
    gear1_outline,
    gear1_profile,
    gear2_curve,
    gear2_outline,
    write_dxf,
)
from fegear.geometry.drawing import BLEND

#: the seed paper's pair with a tip relief: a relief's start and the rounds in every tooth
PAIR = PairParameters(m=2, h1=0.3, f1=0.15, shift=0.016, rotation=0.002, relief=10.0)
CHORD = 1e-4       # mm: the default --chord-error, 0.1 µm
ROUND = 0.25       # mm: the solve's default tip round at m 2
BORE, RIM = 36.784, 52.2


def read_dxf(path):
    """(document, vertices (n, 2), bulges (n,), closed, circle radius) of a drawing."""
    import ezdxf

    doc = ezdxf.readfile(path)
    (line,) = doc.modelspace().query("LWPOLYLINE")
    (circle,) = doc.modelspace().query("CIRCLE")
    xyb = np.array(line.get_points("xyb"))
    return doc, xyb[:, :2], xyb[:, 2], line.closed, circle.dxf.radius


def segment_distances(points: np.ndarray, bulges: np.ndarray, i: np.ndarray,
                      x: np.ndarray) -> np.ndarray:
    """Distance (mm) of points ``x`` (n, 2) to the DXF segments ``i`` (n,): the chord from
    vertex i to the next, or the arc its bulge makes."""
    p, q, b = points[i], points[(i + 1) % len(points)], bulges[i]
    pq = q - p
    t = np.clip(np.einsum("ij,ij->i", x - p, pq) / np.einsum("ij,ij->i", pq, pq), 0, 1)
    chord = np.linalg.norm(x - p - t[:, None] * pq, axis=1)
    arc = b != 0
    theta = 4 * np.arctan(b[arc])
    radius = np.linalg.norm(pq[arc], axis=1) / (2 * np.sin(0.5 * theta))
    left = np.column_stack([-pq[arc, 1], pq[arc, 0]]) / np.linalg.norm(pq[arc], axis=1)[:, None]
    centre = 0.5 * (p[arc] + q[arc]) + (radius * np.cos(0.5 * theta))[:, None] * left
    chord[arc] = np.abs(np.linalg.norm(x[arc] - centre, axis=1) - np.abs(radius))
    return chord


def polar(points: np.ndarray) -> np.ndarray:
    return np.unwrap(np.arctan2(points[:, 1], points[:, 0]))


@pytest.fixture(scope="module")
def shape():
    return RoundedProfile(gear1_profile(PAIR), ROUND)


@pytest.fixture(scope="module")
def gear1_dxf(tmp_path_factory):
    path = tmp_path_factory.mktemp("dxf") / "gear1.dxf"
    write_dxf(path, gear1_outline(PAIR, CHORD, ROUND, BORE), "test")
    return read_dxf(path)


def test_gear1_dxf_is_the_exact_rounded_profile_within_the_chord_error(gear1_dxf, shape):
    doc, pts, bulges, closed, bore = gear1_dxf
    assert doc.units == 4 and closed and bore == BORE           # mm, closed, the bore
    assert {"GEAR1_TEETH", "GEAR1_BORE"} <= {layer.dxf.name for layer in doc.layers}
    phi = polar(pts)
    assert np.all(np.diff(phi) > 0) and phi[-1] - phi[0] < 2 * np.pi  # once round, in order
    # every vertex is a point of the exact profile (its radius at its polar angle) …
    assert np.abs(np.hypot(*pts.T) - shape.radius(phi)).max() < 1e-11
    # … and the profile between two vertices stays within the chord error of the DXF's
    # segment there (a chord, or a round's arc by its bulge)
    f = np.array([0.125, 0.25, 0.5, 0.75, 0.875])
    ends = np.append(phi, phi[0] + 2 * np.pi)
    at = (ends[:-1, None] * (1 - f) + ends[1:, None] * f).ravel()
    i = np.repeat(np.arange(len(pts)), len(f))
    gap = segment_distances(pts, bulges, i, shape.point(at))
    assert gap.max() <= CHORD
    print(f"gear 1: {len(pts)} vertices, the exact profile within {gap.max() * 1e3:.4f} µm")


def test_the_dxf_rounds_are_the_solves_tip_rounds(gear1_dxf, shape):
    _, pts, bulges, _, _ = gear1_dxf
    arcs = np.flatnonzero(bulges)
    # each round as arcs: together they turn by the round's angle, on its centre and radius
    starts = arcs[np.diff(np.append(-2, arcs)) > 1]
    assert len(starts) == 2 * PAIR.z1
    first = arcs[arcs < starts[1]]
    theta = 4 * np.arctan(bulges[first])
    p, q = pts[first], pts[first + 1]
    radius = np.linalg.norm(q - p, axis=1) / (2 * np.sin(0.5 * theta))
    assert radius == pytest.approx(ROUND, abs=1e-12)
    f = shape.fillets[0]
    assert np.linalg.norm(p - f.centre, axis=1) == pytest.approx(ROUND, abs=1e-12)
    ends = shape.point(np.array([f.phi_a, f.phi_b]))
    assert np.linalg.norm(p[0] - ends[0]) < 1e-12 and np.linalg.norm(q[-1] - ends[1]) < 1e-12


def test_gear2_dxf_is_the_exact_cycloid_within_the_chord_error(tmp_path):
    write_dxf(tmp_path / "gear2.dxf", gear2_outline(PAIR, CHORD, RIM), "test")
    doc, pts, bulges, closed, rim = read_dxf(tmp_path / "gear2.dxf")
    assert closed and rim == RIM and not bulges.any()
    assert {"GEAR2_TEETH", "GEAR2_RIM"} <= {layer.dxf.name for layer in doc.layers}
    curve = gear2_curve(PAIR)
    assert np.abs(curve.signed_distance(pts)).max() < 1e-11
    xi = np.unwrap(curve.xi_at_angle(polar(pts)))
    assert np.all(np.diff(xi) > 0)
    f = np.array([0.125, 0.25, 0.5, 0.75, 0.875])
    ends = np.append(xi, xi[0] + 2 * np.pi)
    at = (ends[:-1, None] * (1 - f) + ends[1:, None] * f).ravel()
    gap = segment_distances(pts, bulges, np.repeat(np.arange(len(pts)), len(f)),
                            curve.point(at))
    assert gap.max() <= CHORD


def crossing(pts: np.ndarray, radius: float, lo: float, hi: float) -> float:
    """Polar angle where the outline crosses the circle ``radius`` between polar angles
    ``lo`` and ``hi`` (the one crossing of a flank there), linearly between vertices."""
    phi, r = polar(pts), np.hypot(*pts.T)      # from the first vertex, near polar angle 0
    sel = np.flatnonzero((phi >= lo) & (phi <= hi))
    k = sel[np.flatnonzero(np.diff(np.sign(r[sel] - radius)))[0]]
    return phi[k] + (radius - r[k]) / (r[k + 1] - r[k]) * (phi[k + 1] - phi[k])


def test_a_pitch_deviated_tooth_sits_off_the_exact_by_its_deviation(tmp_path):
    """Gear 1's tooth 11 turned by +5 µm, gear 2's tooth 12 by +4 µm: each loaded flank
    crosses its pitch circle that far along it towards the mate (gear 1 counter-clockwise,
    gear 2 clockwise); every other tooth stays where it was."""
    devs = Deviations(gear1={11: ToothDeviation(pitch=5.0)},
                      gear2={12: ToothDeviation(pitch=4.0)})
    for gear, tooth, um, radius in ((1, 11, 5.0, PAIR.r1), (2, 12, 4.0, PAIR.r0)):
        if gear == 1:
            exact = gear1_outline(PAIR, CHORD, ROUND, BORE)
            moved = gear1_outline(PAIR, CHORD, ROUND, BORE, devs)
            profile = gear1_profile(PAIR)
            centre0, pitch, sign = profile.tooth_center, profile.pitch, +1   # loaded: ccw
        else:
            exact, moved = gear2_outline(PAIR, CHORD, RIM), gear2_outline(PAIR, CHORD, RIM, devs)
            centre0, pitch, sign = 0.0, 2 * np.pi / PAIR.z2, -1               # loaded: cw
        write_dxf(tmp_path / "exact.dxf", exact, "exact")
        write_dxf(tmp_path / "moved.dxf", moved, "moved")
        a, b = read_dxf(tmp_path / "exact.dxf")[1], read_dxf(tmp_path / "moved.dxf")[1]
        # a turn: every vertex at its radius, turned by the tooth's deviation over the tooth
        # and by nothing on the other teeth, a blend between across the spaces beside it
        assert np.abs(np.hypot(*a.T) - np.hypot(*b.T)).max() < 1e-12
        turn = np.angle((b[:, 0] + 1j * b[:, 1]) / (a[:, 0] + 1j * a[:, 1]))
        u = np.mod((polar(a) - centre0) / pitch + 0.5, PAIR.z1 if gear == 1 else PAIR.z2)
        on = np.abs(u - (tooth + 0.5)) <= 0.5 - BLEND
        off = np.abs(u - (tooth + 0.5)) >= 0.5 + BLEND
        assert sign * turn[on] * radius * 1e3 == pytest.approx(um, abs=1e-9)
        assert np.abs(turn[off]).max() < 1e-15
        assert on.sum() > 0.8 * len(a) / (PAIR.z1 if gear == 1 else PAIR.z2)
        # the loaded flank at the pitch circle, along it towards the mate
        mid = centre0 + tooth * pitch
        lo, hi = (mid, mid + 0.5 * pitch) if sign > 0 else (mid - 0.5 * pitch, mid)
        moved_um = (crossing(b, radius, lo, hi) - crossing(a, radius, lo, hi)) * radius * 1e3
        assert sign * moved_um == pytest.approx(um, abs=1e-6)


@pytest.mark.parametrize("gear,tooth,deviation", [
    (1, 10, ToothDeviation(slope=-3.0)), (2, 12, ToothDeviation(form=2.0))])
def test_a_profile_deviation_moves_the_loaded_flank_along_its_normal(gear, tooth, deviation,
                                                                     shape):
    """A slope deviation of −3 µm on gear 1's tooth 10, a form deviation of 2 µm on gear 2's
    tooth 12: the vertices of the loaded flank (up to the tooth's peak) moved along the exact
    profile's normal out of the material by the departure the solve takes there
    (Deviations.flank_offset at Placed.roll), the others not at all, and one vertex more: the
    peak's unmoved copy, where the outline steps back to the other flank."""
    devs = Deviations(**{f"gear{gear}": {tooth: deviation}})
    if gear == 1:
        exact = gear1_outline(PAIR, CHORD, ROUND, BORE).points
        moved = gear1_outline(PAIR, CHORD, ROUND, BORE, devs).points
        centre0, pitch, half = shape.tooth_center, shape.pitch, (0.0, 0.5)  # loaded: ccw
    else:
        exact = gear2_outline(PAIR, CHORD, RIM).points
        moved = gear2_outline(PAIR, CHORD, RIM, devs).points
        centre0, pitch, half = 0.0, 2 * np.pi / PAIR.z2, (-0.5, 0.0)       # loaded: cw
    rel = np.mod(polar(exact) - centre0 + 0.5 * pitch, 2 * np.pi) / pitch - 0.5 - tooth
    loaded = (rel >= half[0] - 1e-12) & (rel <= half[1] + 1e-12) & (rel < 0.5)
    peak = int(np.argmin(np.abs(rel)))
    # without the peak's unmoved copy (before the moved peak on gear 1, after it on gear 2)
    # the two outlines pair vertex by vertex
    assert len(moved) == len(exact) + 1
    copy = peak if gear == 1 else peak + 1
    assert np.array_equal(moved[copy], exact[peak])
    aligned = np.delete(moved, copy, axis=0)
    assert np.array_equal(aligned[~loaded], exact[~loaded]) and loaded.sum() > 50
    was = exact[loaded]
    if gear == 1:
        _, normal, _ = shape.frame(polar(was))
    else:
        curve = gear2_curve(PAIR)
        _, _, normal, _ = curve.frame(curve.xi_at_angle(polar(was)))
    depth = devs.flank_offset(gear, np.full(len(was), tooth),
                              Placed(devs, PAIR, 0.0).roll(gear, was))
    assert np.abs(aligned[loaded] - was - depth[:, None] * normal).max() < 1e-12
    assert np.abs(depth).max() == pytest.approx(1e-3 * max(abs(deviation.slope),
                                                           abs(deviation.form)), rel=1e-3)


def test_the_step_solid_carries_the_profile_on_its_faces(tmp_path, shape):
    """gear1.step's lateral faces pass through the outline's vertices, also those of a
    deviated tooth, and stay within the kernel's tolerance (1e-7 mm) of the exact profile
    between them; the solid is the outline's area times the face width."""
    from fegear.fe import Circle, Segment, write_step
    from fegear.fe.mesh import gmsh_session

    devs = Deviations(gear1={1: ToothDeviation(pitch=5.0), 2: ToothDeviation(slope=3.0)})
    outline = gear1_outline(PAIR, CHORD, ROUND, BORE, devs)
    runs = [Segment(f"run {k}", run) for k, run in enumerate(outline.runs())]
    path = write_step(tmp_path / "gear1.step", runs, 5.0, holes=[Circle(BORE)])
    assert path.read_text().startswith("ISO-10303-21;")
    phi = polar(outline.points)
    teeth = np.floor((phi - shape.phi_space) / shape.pitch)
    near = teeth <= 3                            # the deviated teeth and their neighbours
    # as drawn, exact: tooth 3, and tooth 0 short of the blend into tooth 1's turn
    exact = (teeth == 3) | ((teeth == 0) & (phi < shape.phi_space + 0.9 * shape.pitch))
    between = (0.5 * (phi[:-1] + phi[1:]))[exact[:-1] & exact[1:]]
    points = np.vstack([outline.points[near], shape.point(between)])
    distance = np.full(len(points), np.inf)
    with gmsh_session() as gmsh:
        gmsh.model.occ.importShapes(str(path))
        gmsh.model.occ.synchronize()
        (volume,) = gmsh.model.getEntities(3)
        box = gmsh.model.getBoundingBox(*volume)
        mass = gmsh.model.occ.getMass(*volume)
        for _, face in gmsh.model.getEntities(2):
            x0, y0, z0, x1, y1, z1 = gmsh.model.getBoundingBox(2, face)
            inside = np.flatnonzero((points[:, 0] > x0 - 0.01) & (points[:, 0] < x1 + 0.01)
                                    & (points[:, 1] > y0 - 0.01) & (points[:, 1] < y1 + 0.01))
            if z1 - z0 < 1 or not len(inside):   # the end faces, or no point near
                continue
            xyz = np.column_stack([points[inside], np.full(len(inside), 2.5)])
            foot, _ = gmsh.model.getClosestPoint(2, face, xyz.ravel())
            d = np.linalg.norm(np.reshape(foot, (-1, 3)) - xyz, axis=1)
            distance[inside] = np.minimum(distance[inside], d)
    assert box[2] == pytest.approx(0.0, abs=1e-6) and box[5] == pytest.approx(5.0, abs=1e-6)
    n = near.sum()
    assert distance[:n].max() < 1e-9
    assert distance[n:].max() < 1e-7
    x, y = outline.points.T
    area = 0.5 * np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y) - math.pi * BORE**2
    assert mass == pytest.approx(5.0 * area, rel=1e-6)
    print(f"STEP: vertices within {distance[:n].max():.2e} mm, the exact profile between "
          f"them within {distance[n:].max():.2e} mm")

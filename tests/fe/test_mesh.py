"""Meshing: exact boundaries, named parts that survive the quadratic import, refinement, quality.
Invariants only (areas, lengths, node positions), never node counts."""

import math
import os
import signal
from dataclasses import replace

import numpy as np
import pytest
from skfem import Basis, ElementTriP2, FacetBasis, LinearForm, asm

from fegear.fe.assembly import facet_nodes
from fegear.fe.mesh import (
    BodyGeometry,
    MeshError,
    Refinement,
    Segment,
    jiggle,
    mesh_bodies,
    mesh_quality,
)
from fegear.verify.penalty.model import Circle

R = 10.0
C = (0.0, R)
W = 0.05  # half-angle of the refined window, rad


def arc(a0, a1, n=40):
    a = np.linspace(a0, a1, n)
    return np.asarray(C) + R * np.column_stack([np.cos(a), np.sin(a)])


def half_disk(window_size=0.01, size=2.0):
    circle = Circle(C, R)
    down = 1.5 * math.pi
    return BodyGeometry("half_disk", (
        Segment("left", arc(math.pi, down - W), circle.project),
        Segment("window", arc(down - W, down + W), circle.project),
        Segment("right", arc(down + W, 2 * math.pi), circle.project),
        Segment("cut", np.array([[R, R], [-R, R]])),
    ), size=size, refinements=(Refinement(("window",), window_size),))


@pytest.fixture(scope="module")
def disk():
    return mesh_bodies([half_disk()])[0]


def length(mesh, name):
    fb = FacetBasis(mesh, ElementTriP2(), facets=mesh.boundaries[name])
    return asm(LinearForm(lambda v, w: v), fb).sum()


def test_area_and_boundary_lengths_are_exact(disk):
    m = disk.mesh
    area = asm(LinearForm(lambda v, w: v), Basis(m, ElementTriP2())).sum()
    assert area == pytest.approx(math.pi * R * R / 2, rel=1e-5)
    assert length(m, "window") == pytest.approx(2 * W * R, rel=1e-9)
    assert length(m, "cut") == pytest.approx(2 * R, rel=1e-12)
    assert length(m, "left") == pytest.approx((0.5 * math.pi - W) * R, rel=1e-6)


def test_boundary_nodes_including_midside_lie_on_the_exact_curve(disk):
    m = disk.mesh
    for name in ("left", "window", "right"):
        nodes = np.unique(facet_nodes(m, m.boundaries[name]))
        r = np.linalg.norm(m.doflocs.T[nodes] - np.asarray(C), axis=1)
        assert np.abs(r - R).max() < 1e-12


def test_named_parts_partition_the_boundary(disk):
    m = disk.mesh
    named = np.concatenate([m.boundaries[n] for n in ("left", "window", "right", "cut")])
    assert len(named) == len(np.unique(named))
    assert np.array_equal(np.sort(named), np.sort(m.boundary_facets()))


def test_refinement_reaches_the_requested_size_and_grades_out(disk):
    m = disk.mesh
    ends = m.doflocs.T[m.facets[:, m.boundaries["window"]]]
    h = np.linalg.norm(ends[0] - ends[1], axis=1)
    assert h.max() < 1.5 * 0.01
    assert disk.quality.h_max < 2.0 * 1.5
    assert disk.quality.min_shape > 0.3
    assert disk.quality.min_jacobian_ratio > 0.5


def test_quality_check_detects_an_inverted_element(disk):
    m = disk.mesh
    doflocs = m.doflocs.copy()
    corner = m.t[0, 0]
    opposite = 0.5 * (doflocs[:, m.t[1, 0]] + doflocs[:, m.t[2, 0]])
    doflocs[:, corner] = opposite + 2.0 * (opposite - doflocs[:, corner])  # fold it over
    assert mesh_quality(m).min_jacobian_ratio > 0
    assert mesh_quality(replace(m, doflocs=doflocs)).min_jacobian_ratio < 0


def test_bad_geometry_is_refused_with_a_named_reason():
    g = half_disk()
    with pytest.raises(MeshError, match="unknown"):
        mesh_bodies([BodyGeometry(g.name, g.outer, g.size,
                                  refinements=(Refinement(("nowhere",), 0.1),))])
    with pytest.raises(MeshError, match="does not end where"):
        mesh_bodies([BodyGeometry(g.name, g.outer[:3], g.size)])
    with pytest.raises(MeshError, match="finite"):
        Segment("x", np.array([[0.0, np.nan], [1.0, 0.0]]))


def test_jiggle_moves_interior_corners_by_the_fraction_and_keeps_the_boundary(disk):
    moved = jiggle(disk, 0.1, seed=3)
    m0, m1 = disk.mesh, moved.mesh
    shift = np.linalg.norm(m1.doflocs - m0.doflocs, axis=0)
    boundary = np.unique(m0.facets[:, m0.boundary_facets()])
    assert shift[boundary].max() == 0.0
    corners = np.setdiff1d(np.unique(m0.t), boundary)
    t = m0.t.T
    shortest = np.full(m0.doflocs.shape[1], np.inf)
    for a, b in ((0, 1), (1, 2), (0, 2)):
        d = np.linalg.norm(m0.doflocs[:, t[:, a]] - m0.doflocs[:, t[:, b]], axis=0)
        np.minimum.at(shortest, t[:, a], d)
        np.minimum.at(shortest, t[:, b], d)
    assert shift[corners] == pytest.approx(0.1 * shortest[corners], rel=1e-9)
    # interior edges straight, boundary midside nodes still on the circle, area unchanged
    x = m1.doflocs[:, m1.dofs.element_dofs]
    inner = ~np.isin(m1.t2f, m1.boundary_facets())
    for k, (a, b) in enumerate(((0, 1), (1, 2), (0, 2))):
        mid = 0.5 * (x[:, a] + x[:, b])
        assert np.abs(x[:, 3 + k][:, inner[k]] - mid[:, inner[k]]).max() < 1e-12
    area = [asm(LinearForm(lambda v, w: v), Basis(m, ElementTriP2())).sum() for m in (m0, m1)]
    assert area[1] == pytest.approx(area[0], rel=1e-12)
    assert moved.quality.min_jacobian_ratio > 0
    assert list(m1.boundaries) == list(m0.boundaries)


def test_loop_closes_where_two_ends_round_apart():
    # a random tooth pair (m 3.6, z 74/73, shift 0.1 µm) had two segment ends 1e-13 mm apart
    # on either side of a rounding boundary: joined by rounded coordinates, the loop broke
    # ("Curve loop 1 is wrong", a bare gmsh exception)
    y = 0.5e-9
    body = BodyGeometry("square", (
        Segment("bottom", np.array([[0.0, 0.0], [1.0, y + 1e-13]])),
        Segment("right", np.array([[1.0, y - 1e-13], [1.0, 1.0]])),
        Segment("top", np.array([[1.0, 1.0], [0.0, 1.0]])),
        Segment("left", np.array([[0.0, 1.0], [0.0, 0.0]]))), size=0.25)
    (mesh,) = mesh_bodies([body])
    assert mesh.quality.min_jacobian_ratio > 0
    assert sorted(mesh.mesh.boundaries) == ["bottom", "left", "right", "top"]


def annular_sector(a0=0.3, sectors=8, r_in=6.0, r_out=10.0, size=0.8, window=None):
    """One sector of a ring, its two radial cuts periodic (the cut ``cut_b`` is ``cut_a``
    turned by one pitch)."""
    from fegear.fe.mesh import Periodic

    pitch = 2 * math.pi / sectors
    a1 = a0 + pitch

    def ring(r, lo, hi, n=30):
        t = np.linspace(lo, hi, n)
        return r * np.column_stack([np.cos(t), np.sin(t)])

    def snap(r):
        return lambda x: r * x / np.linalg.norm(x, axis=1)[:, None]

    outer = ring(r_out, a0, a1)
    inner = ring(r_in, a1, a0)
    segs = (Segment("cut_a", np.array([inner[-1], outer[0]])),
            Segment("outside", outer, snap(r_out)),
            Segment("cut_b", np.array([outer[-1], inner[0]])),
            Segment("inside", inner, snap(r_in)))
    refine = (Refinement(("outside",), window),) if window else ()
    return BodyGeometry("sector", segs, size=size, refinements=refine,
                        periodic=(Periodic("cut_b", "cut_a", pitch),))


def test_periodic_cuts_carry_the_same_nodes_turned_by_one_pitch():
    (mesh,) = mesh_bodies([annular_sector(window=0.1)])
    pairs = mesh.periodic["cut_b"]
    x = mesh.mesh.doflocs.T
    pitch = 2 * math.pi / 8
    c, s = math.cos(pitch), math.sin(pitch)
    turned = x[pairs[:, 1]] @ np.array([[c, s], [-s, c]])
    assert np.abs(turned - x[pairs[:, 0]]).max() < 1e-9
    # every node of each cut, midside nodes included, is paired once
    for name, col in (("cut_b", 0), ("cut_a", 1)):
        nodes = np.unique(facet_nodes(mesh.mesh, mesh.mesh.boundaries[name]))
        assert sorted(pairs[:, col]) == sorted(nodes)
    assert len(pairs) % 2 == 1  # P2 on a line: corners and midside nodes alternate


@pytest.mark.skipif(not os.path.exists("/proc/self/status"), reason="reads Linux's /proc")
def test_meshing_leaves_a_closed_pipe_to_python_not_to_the_default_signal_action():
    # gmsh's initialisation sets SIGPIPE back to the system's default, at the C level (Python's
    # own record still says ignored): a write to a closed pipe then killed the process
    # silently, as `fegear solve` with its estimate in a worker found at exit after a SIGTERM
    def ignored() -> bool:
        with open("/proc/self/status") as f:
            mask = next(line for line in f if line.startswith("SigIgn"))
        return bool(int(mask.split()[1], 16) >> (signal.SIGPIPE - 1) & 1)

    assert ignored()
    mesh_bodies([half_disk()])
    assert ignored()

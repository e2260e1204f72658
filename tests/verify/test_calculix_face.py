"""The 3D pair check (fegear.verify.calculix_face): the sector peer extruded across the face
into C3D15 wedges, and CalculiX's K_Hβ and worst root stress against fegear's slice model
(docs/validation.md, "Across the face: a 3D FE of the pair")."""

import numpy as np
import pytest
from system import installed, why_not

from fegear.verify.calculix_face import (
    baseline_case,
    end_loads,
    face_bodies,
    face_check,
    layer_means,
    load_factor,
)
from fegear.verify.ccx_face_deck import write_face_deck
from fegear.verify.ccx_face_mesh import extrude
from fegear.verify.sector import solve_pair

#: issue 69: K_Hβ and the worst gear-1 root stress within 5 % of fegear's slice model
TOL = 0.05
#: µm over the face: the issue's 10 is beyond the baseline's room since 2026-12-02 (fegear
#: refuses it: the pair would jam at β = 6°, 9.95 µm admissible)
MISALIGNMENT = 9.9


@pytest.fixture
def ccx():
    """CalculiX, installed from Debian's calculix-ccx where it is missing and can be."""
    if installed("ccx") is None:
        pytest.skip(f"CalculiX: {why_not('ccx')}")


def wedge_volumes(x: np.ndarray) -> np.ndarray:
    """Volumes of straight-sided wedges from their corner nodes (6 per row, CalculiX order):
    the mean of the two triangles' areas times the height (exact for a prism)."""
    def area(a, b, c):
        return 0.5 * ((b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1])
                      - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0]))
    low = area(x[:, 0], x[:, 1], x[:, 2])
    high = area(x[:, 3], x[:, 4], x[:, 5])
    return 0.5 * (low + high) * (x[:, 3, 2] - x[:, 0, 2])


def test_extrusion_fills_the_slab_and_numbers_its_faces(coarse_disks):
    """The disk mesh extruded into 4 layers: wedge volumes sum to area × width, each element's
    upper corners sit one layer above its lower ones, the vertical midsides half way, every
    node is used, and a boundary's wedge faces (3-5) hold the boundary's nodes."""
    body = coarse_disks.bodies[0]
    mesh = body.mesh
    ext = extrude("disk", mesh, lambda p: p, layers=4, width=5.0)
    x = ext.nodes[ext.elements]
    c = mesh.doflocs.T[ext.conn2d[:, :3]]
    area = 0.5 * np.sum((c[:, 1, 0] - c[:, 0, 0]) * (c[:, 2, 1] - c[:, 0, 1])
                        - (c[:, 1, 1] - c[:, 0, 1]) * (c[:, 2, 0] - c[:, 0, 0]))
    assert area > 0
    assert np.sum(wedge_volumes(x[:, :6])) == pytest.approx(area * 5.0, rel=1e-12)
    np.testing.assert_allclose(x[:, 3:6, 2] - x[:, 0:3, 2], 1.25)
    np.testing.assert_allclose(x[:, 12:15, 2], 0.5 * (x[:, 0:3, 2] + x[:, 3:6, 2]))
    np.testing.assert_allclose(x[:, 12:15, :2], x[:, 0:3, :2])
    assert np.array_equal(np.unique(ext.elements), np.arange(len(ext.nodes)))
    face_nodes = {3: (0, 1, 4, 3, 6, 9, 12, 13), 4: (1, 2, 5, 4, 7, 10, 13, 14),
                  5: (2, 0, 3, 5, 8, 11, 14, 12)}
    on = set(ext.boundary_nodes("contact").tolist())
    for layer in (0, 3):
        elem, face = ext.faces("contact", layer)
        assert len(elem) == len(mesh.boundaries["contact"])
        for e, f in zip(elem, face):
            assert set(ext.elements[e, list(face_nodes[f])].tolist()) <= on


def test_the_shear_displaces_each_section_by_its_zeta(coarse_disks):
    """A node at face position ζ is written displaced by ζ × the shear (mm), as the slice
    model displaces gear 1 section by section; the middle plane stays."""
    mesh = coarse_disks.bodies[0].mesh
    flat = extrude("disk", mesh, lambda p: p, layers=2, width=5.0)
    sheared = extrude("disk", mesh, lambda p: p, layers=2, width=5.0, shear=(-0.01, 0.002))
    moved = sheared.nodes - flat.nodes
    np.testing.assert_allclose(moved[:, :2], np.outer(flat.zeta, (-0.01, 0.002)), atol=1e-15)
    assert np.all(moved[:, 2] == 0)
    assert set(np.round(flat.zeta, 12)) == {-0.5, -0.25, 0.0, 0.25, 0.5}


def test_line_load_readers():
    """End values of a linear line load from its layer means are exact; K_Hβ is the largest
    over the largest tooth mean; the slice model's piecewise-linear loads average exactly."""
    zeta = (np.arange(4) + 0.5) / 4 - 0.5
    loads = np.array([100 + 80 * zeta, 50 - 40 * zeta])
    ends = end_loads(loads)
    np.testing.assert_allclose(ends, [[60, 140], [70, 30]])
    assert load_factor(loads, ends) == pytest.approx(140 / 100)
    means = layer_means({"10": [60, 100, 140], "11": [0, 0, 40]}, [-0.5, 0.0, 0.5], 4)
    np.testing.assert_allclose(means[10], 100 + 80 * zeta)
    np.testing.assert_allclose(means[11], [0, 0, 10, 30])


def test_deck_ties_the_bore_and_pairs_each_tooth_layer(tmp_path):
    """The baseline's deck (1 N·m, 2 layers, misaligned 10 µm): a C3D15 per section triangle
    and layer, one contact pair per paired tooth and layer, two bore equations per bore node
    (less the few without a lever), and gear 1 written sheared by ζ·(−10 µm) along x."""
    case = baseline_case(1.0)
    sol = solve_pair(case)
    bodies, zones = face_bodies(sol, 10.0, 2)
    deck = write_face_deck(bodies, case.torque_Nmm, tmp_path, "face", 30.0)
    g1, g2 = bodies.gear1, bodies.gear2
    assert deck.elements == 2 * (g1.conn2d.shape[0] + g2.conn2d.shape[0])
    assert len(deck.tooth) == 2 * len(sol.teeth)
    bore = len(g1.boundary_nodes(bodies.bore))
    assert 2 * bore - 4 <= deck.equations <= 2 * bore
    text = deck.path.read_text()
    assert text.count("*CONTACT PAIR") == len(deck.tooth)
    assert text.count("TYPE=C3D15") == 2
    # the same section nodes at the two ends: 10 µm apart along x, the face width along z
    end, start = g1.plane_node(2, np.arange(3)), g1.plane_node(0, np.arange(3))
    np.testing.assert_allclose(g1.nodes[end] - g1.nodes[start],
                               np.tile([-0.010, 0.0, 5.0], (3, 1)), atol=1e-12)
    assert len(zones[0]) > 0 and len(zones[1]) > 0


@pytest.fixture(scope="module")
def aligned(tmp_path_factory):
    """The baseline at 200 N·m, aligned, by fegear (the 2D pair) and by CalculiX in 3D (about
    8 min)."""
    if installed("ccx") is None:
        pytest.skip(f"CalculiX: {why_not('ccx')}")
    return face_check(0.0, tmp_path_factory.mktemp("aligned"), threads=2, timeout=3600)


@pytest.mark.slow
def test_aligned_3d_pair_carries_the_2d_tooth_loads(aligned):
    """Aligned, the extruded pair carries the 2D pair's tooth loads: each tooth's mean line
    load within 2 % of the 2D load over the face width, for teeth above 10 % of the load
    (measured: 0.2 %), and the torque is the contact moment's."""
    c = aligned.ccx
    total = sum(np.mean(row) for row in c.line_load)
    checked = 0
    for t, row in zip(c.teeth, c.line_load):
        ours = np.mean(aligned.fegear_line_load.get(t, [0.0]))
        if ours > 0.1 * total:
            assert np.mean(row) == pytest.approx(ours, rel=0.02)
            checked += 1
    assert checked >= 3
    assert c.torque == pytest.approx(200e3, rel=0.01)


@pytest.mark.slow
def test_aligned_3d_root_stress_against_the_2d_pair(aligned):
    """Aligned, the 3D pair's worst gear-1 root stress lies above the 2D pair's (plane stress)
    by the face's own 3D effect, at most 10 %: inside the face the root is near plane strain
    and the middle carries 3 % more than the mean (docs/validation.md). Measured 2026-12-02:
    +6.6 % (306.7 against 287.7 MPa), where the same sections as a thin plane-stress slab read
    284.6: the extrusion is not what differs. Within 5 %, as the issue first asked, it is not."""
    ratio = aligned.ccx.root_stress[0] / aligned.fegear_root_stress[0]
    assert 1.0 < ratio < 1.10


@pytest.mark.slow
@pytest.mark.usefixtures("ccx")
def test_misaligned_3d_pair_matches_the_slice_model(tmp_path):
    """Baseline, 200 N·m, 9.9 µm over the face: CalculiX's K_Hβ and worst gear-1 root stress
    within 5 % of the slice model's (issue 69; measured 2026-12-03 at 9.9 µm: −3.3 % and
    −1.1 %)."""
    check = face_check(MISALIGNMENT, tmp_path, threads=2, timeout=3600)
    c = check.ccx
    assert c.load_factor == pytest.approx(check.fegear_load_factor, rel=TOL)
    assert c.root_stress[0] == pytest.approx(check.fegear_root_stress[0], rel=TOL)

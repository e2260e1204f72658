"""CalculiX peer (fegear.peer): the deck written from the coarse Hertz disks, and ccx's answer."""

from pathlib import Path

import numpy as np
import pytest

from fegear.assembly import RigidLink, assemble_body, facet_nodes
from fegear.contact import ContactPair
from fegear.disks import DiskCase, solve_disks
from fegear.peer import (
    CONTROLS,
    PeerConvergenceError,
    PeerError,
    ccx_available,
    ccx_disks,
    run_ccx,
    write_deck,
)

needs_ccx = pytest.mark.skipif(not ccx_available(), reason="CalculiX (ccx) is not installed")

#: ccx's p_max against Hertz on the coarse disks: measured +0.22 % (fegear: +0.18 %)
P_TOL = 0.01


@pytest.fixture(scope="module")
def coarse():
    return solve_disks(DiskCase(quality="coarse"))


def parse_deck(path: Path) -> dict:
    """Nodes {id: (x, y)}, elements {id: nodes}, element types, surfaces {name: [(elem, face)]},
    node sets, number of equations and the raw lines of a deck."""
    deck = {"nodes": {}, "elements": {}, "types": set(), "surfaces": {}, "nsets": {},
            "equations": 0, "lines": path.read_text().splitlines()}
    block = name = None
    for line in deck["lines"]:
        if line.startswith("*"):
            words = [w.strip() for w in line[1:].split(",")]
            block, opts = words[0].upper(), dict(w.split("=", 1) for w in words[1:] if "=" in w)
            name = opts.get("NAME") or opts.get("NSET")
            if block == "ELEMENT":
                deck["types"].add(opts["TYPE"])
            continue
        values = [v.strip() for v in line.split(",") if v.strip()]
        if block == "NODE":
            deck["nodes"][int(values[0])] = (float(values[1]), float(values[2]))
        elif block == "ELEMENT":
            deck["elements"][int(values[0])] = [int(v) for v in values[1:]]
        elif block == "SURFACE":
            deck["surfaces"].setdefault(name, []).append((int(values[0]), int(values[1][1:])))
        elif block == "NSET":
            deck["nsets"].setdefault(name, []).extend(int(v) for v in values)
        elif block == "EQUATION" and len(values) > 1:
            deck["equations"] += 1
    return deck


def test_deck_has_the_same_mesh_in_calculix_order(coarse, tmp_path):
    deck = write_deck(coarse.bodies, 1000.0, tmp_path, "disks", coarse.model.pairs)
    d = parse_deck(deck.path)
    b1, b2 = coarse.bodies
    assert len(d["nodes"]) == deck.nodes == b1.mesh.doflocs.shape[1] + b2.mesh.doflocs.shape[1]
    assert len(d["elements"]) == deck.elements == b1.mesh.t.shape[1] + b2.mesh.t.shape[1]
    assert deck.dofs == coarse.dofs
    assert d["types"] == {"CPE6"}  # plane stress written as its plane-strain equivalent
    x = np.array([[d["nodes"][n] for n in e] for e in d["elements"].values()])  # (ne, 6, 2)
    e1, e2 = x[:, 1] - x[:, 0], x[:, 2] - x[:, 0]
    assert np.all(e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0] > 0)  # counter-clockwise corners
    for mid, (a, b) in zip((3, 4, 5), ((0, 1), (1, 2), (2, 0))):  # 4: 1-2, 5: 2-3, 6: 3-1
        off = np.linalg.norm(x[:, mid] - 0.5 * (x[:, a] + x[:, b]), axis=1)
        off /= np.linalg.norm(x[:, b] - x[:, a], axis=1)
        assert off.max() < 0.05 and np.median(off) < 1e-9  # curved only on the boundary
    # CalculiX reads numbers from at most 20 characters
    fields = [f.strip() for line in d["lines"][2:] if not line.startswith("*")
              for f in line.split(",")]
    assert max(map(len, fields)) <= 20
    assert any(abs(y) < 1e-4 and y != 0 for _, y in d["nodes"].values())  # had 21 characters


def test_deck_supports_contact_and_load(coarse, tmp_path):
    deck = write_deck(coarse.bodies, 1000.0, tmp_path, "disks", coarse.model.pairs)
    d = parse_deck(deck.path)
    b1, b2 = coarse.bodies
    n1 = b1.mesh.doflocs.shape[1]
    cut1 = np.unique(facet_nodes(b1.mesh, b1.mesh.boundaries["cut"])) + 1
    cut2 = np.unique(facet_nodes(b2.mesh, b2.mesh.boundaries["cut"])) + 1 + n1
    assert sorted(d["nsets"]["FIXED"]) == sorted(cut2)
    assert sorted(d["nsets"]["LINK"]) == sorted(cut1)
    assert d["equations"] == len(cut1) - 1  # every cut node's uy tied to the reference's
    assert "LINK, 1, 1" in d["lines"] and "FIXED, 1, 2" in d["lines"]
    assert f"REF, 2, {-1000.0:.13g}" in d["lines"]  # P downwards on the reference
    # each contact face lies on the right boundary: its three nodes are that boundary's
    for surface, body, offset in (("SLAVE1", b1, 0), ("MASTER1", b2, n1)):
        faces = d["surfaces"][surface]
        assert len(faces) == len(body.mesh.boundaries["contact"])
        on = set(np.unique(facet_nodes(body.mesh, body.mesh.boundaries["contact"])) + 1 + offset)
        for elem, face in faces:
            nodes = d["elements"][elem]
            a, b = ((0, 1), (1, 2), (2, 0))[face - 1]
            assert {nodes[a], nodes[b], nodes[face + 2]} <= on
    h = coarse.hertz.b / coarse.case.elements_per_b  # slave facets in the window
    assert deck.penalty[0] == pytest.approx(300.0 * coarse.hertz.E_star / h, rel=0.02)


def test_literal_plane_stress_element(coarse, tmp_path):
    deck = write_deck(coarse.bodies, 1000.0, tmp_path, "disks", plane_stress_element="CPS6")
    d = parse_deck(deck.path)
    assert d["types"] == {"CPS6"} and deck.element_type == "CPS6"
    assert f"{206000.0:.13g}, {0.29:.13g}" in d["lines"]
    with pytest.raises(PeerError, match="CPE6"):
        write_deck(coarse.bodies, 1000.0, tmp_path, plane_stress_element="CPS8")


def test_unsupported_models_are_refused(coarse, tmp_path):
    b1, b2 = coarse.bodies
    turning = assemble_body(b1.mesh_data, b1.material, link=RigidLink("cut", "rotation"))
    with pytest.raises(PeerError, match="translation only"):
        write_deck([turning, b2], 1000.0, tmp_path)
    with pytest.raises(PeerError, match="load"):
        write_deck(coarse.bodies, -1.0, tmp_path)
    with pytest.raises(PeerError, match="no boundary"):
        write_deck(coarse.bodies, 1000.0, tmp_path,
                   pairs=[ContactPair("x", 0, "flank", 1, "contact", None)])


def test_run_reports_missing_ccx_and_deck(tmp_path, monkeypatch):
    monkeypatch.setattr("fegear.peer.shutil.which", lambda name: "/nowhere/ccx")
    with pytest.raises(PeerError, match="no deck"):
        run_ccx(tmp_path, "absent")
    monkeypatch.setattr("fegear.peer.shutil.which", lambda name: None)
    assert not ccx_available()
    with pytest.raises(PeerError, match="not installed"):
        run_ccx(tmp_path, "absent")


@needs_ccx
def test_ccx_failure_is_a_peer_error(tmp_path):
    (tmp_path / "bad.inp").write_text("*NODE\n1, 0, 0, 0\n*STEP\n*STATIC\n*CLOAD\n9, 2, 1.\n"
                                      "*END STEP\n")
    with pytest.raises(PeerError, match="ccx failed"):
        run_ccx(tmp_path, "bad", timeout=60)


@needs_ccx
def test_ccx_giving_up_is_a_convergence_error(coarse, tmp_path):
    deck = write_deck(coarse.bodies, 1000.0, tmp_path, "short")
    text = deck.path.read_text()
    for full, short in zip(CONTROLS[3::2], ("2, 3, 3, 5, 10, 4, 0, 1", "0, 0.1, 1, 5")):
        text = text.replace(full, short)  # at most 5 iterations and 1 cutback
    deck.path.write_text(text)
    with pytest.raises(PeerConvergenceError, match="did not converge"):
        run_ccx(tmp_path, "short", timeout=120)


@needs_ccx
def test_ccx_matches_hertz_on_the_coarse_disks(tmp_path):
    ours, ccx = ccx_disks(DiskCase(quality="coarse"), tmp_path, timeout=300)
    p0 = ours.hertz.p0
    assert abs(ccx.p_max / p0 - 1.0) < P_TOL
    assert abs(ccx.p_max / ours.p_max - 1.0) < P_TOL
    assert ccx.load == pytest.approx(1000.0, rel=0.01)      # contact force balances P
    assert ccx.reaction == pytest.approx(1000.0, rel=0.01)  # and so do the supports
    assert ccx.dofs == ours.dofs and ccx.equations > 0 and ccx.wall_s > 0
    assert ccx.increments >= 2 and ccx.contact_points > 0


@pytest.mark.slow
@needs_ccx
def test_literal_cps6_is_stiffer_than_plane_stress(tmp_path):
    """CalculiX's CPS6 is a one-layer plate of C3D15 wedges: with 2b ≪ t its contact is
    stiffer than 2D plane stress (measured +5.4 % on the coarse disks)."""
    ours, ccx = ccx_disks(DiskCase(quality="coarse"), tmp_path, plane_stress_element="CPS6",
                          timeout=300)
    assert 0.03 < ccx.p_max / ours.hertz.p0 - 1.0 < 0.08
    assert ccx.load == pytest.approx(1000.0, rel=0.01)

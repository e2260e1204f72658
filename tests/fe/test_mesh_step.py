"""Plates written as STEP solids (fegear/fe/mesh.py, write_step): read back through gmsh's
OpenCASCADE kernel, one solid of the plate's area times its thickness; a loop that does not
close or a thickness that is not positive refused; nothing printed on the way."""

import math

import numpy as np
import pytest

from fegear.fe import Circle, MeshError, Segment, write_step
from fegear.fe.mesh import gmsh_session


def square(side: float) -> list[Segment]:
    corners = side * np.array([[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]])
    return [Segment(f"side {k}", np.array([corners[k], corners[(k + 1) % 4]]))
            for k in range(4)]


def solid(path):
    """(volume, bounding box, lateral faces) of the one solid of a STEP file."""
    with gmsh_session() as gmsh:
        gmsh.model.occ.importShapes(str(path))
        gmsh.model.occ.synchronize()
        (volume,) = gmsh.model.getEntities(3)
        return (gmsh.model.occ.getMass(*volume), gmsh.model.getBoundingBox(*volume),
                len(gmsh.model.getEntities(2)))


def test_a_plate_with_a_hole_is_its_area_times_its_thickness(tmp_path, capfd):
    path = write_step(tmp_path / "plate.step", square(10.0), 2.5, holes=[Circle(3.0)])
    # OpenCASCADE's transfer statistics stay off the standard output (a command's JSON)
    assert capfd.readouterr().out == ""
    assert path.read_text().startswith("ISO-10303-21;")
    mass, box, faces = solid(path)
    assert mass == pytest.approx(2.5 * (100.0 - math.pi * 9.0), rel=1e-12)
    assert np.allclose(box, [-5, -5, 0, 5, 5, 2.5], atol=1e-6)
    assert faces == 4 + 1 + 2
    assert [p.name for p in tmp_path.iterdir()] == ["plate.step"]   # nothing else left


def test_a_ring_about_a_spline_hole(tmp_path):
    # a circle of radius 1 as one closed spline through 400 of its points: the hole of a
    # disk of radius 2, a ring of area 3π to the spline's accuracy
    t = np.linspace(0.0, 2 * np.pi, 401)
    hole = [Segment("curve", np.column_stack([np.cos(t), np.sin(t)]))]
    mass, _, _ = solid(write_step(tmp_path / "ring.step", Circle(2.0), 1.0, holes=[hole]))
    assert mass == pytest.approx(3 * math.pi, rel=1e-8)


def test_a_loop_that_does_not_close_or_no_thickness_is_refused(tmp_path):
    sides = square(10.0)
    sides[1] = Segment("side 1", sides[1].points + [0.0, 0.1])
    with pytest.raises(MeshError, match="does not end where the next segment starts"):
        write_step(tmp_path / "open.step", sides, 1.0)
    for thickness in (0.0, -1.0, math.nan):
        with pytest.raises(MeshError, match="thickness"):
            write_step(tmp_path / "flat.step", square(10.0), thickness)
    assert list(tmp_path.iterdir()) == []

"""VTU files as ParaView reads them: a quadratic-triangle mesh and its fields written by
:func:`fegear.fe.write_vtu` come back exactly, in their own types, through VTK (pyvista) and
through meshio: in double precision, and in a solve's (:data:`fegear.fe.FIELD_DTYPE`, 32-bit
cells)."""

import numpy as np
import pytest

from fegear.fe import FIELD_DTYPE, write_vtu, written_name


@pytest.fixture(scope="module", params=[(np.float64, np.int64), (FIELD_DTYPE, np.int32)],
                ids=["double", "solve's"])
def written(tmp_path_factory, request):
    """Two triangle6 elements on a unit square, a vector and two scalar fields."""
    real, integer = request.param
    points = np.array([[0, 0], [1, 0], [1, 1], [0, 1], [0.5, 0], [1, 0.5], [0.5, 0.5],
                       [0, 0.5], [0.5, 1]], dtype=real)
    cells = np.array([[0, 1, 2, 4, 5, 6], [0, 2, 3, 6, 8, 7]], dtype=integer)
    rng = np.random.default_rng(1)
    data = {"displacement": rng.normal(size=(9, 3)).astype(real),
            "von_mises": rng.uniform(0, 900, 9).astype(real), "contact_pressure": np.zeros(9, real)}
    path = write_vtu(tmp_path_factory.mktemp("vtu") / "square.vtu", points, cells, data)
    return path, points, cells, data


def test_vtk_reads_the_mesh_and_every_field_exactly(written):
    pv = pytest.importorskip("pyvista")
    path, points, cells, data = written
    grid = pv.read(path)
    np.testing.assert_array_equal(grid.points[:, :2], points)
    assert set(grid.celltypes) == {22}                  # VTK_QUADRATIC_TRIANGLE
    np.testing.assert_array_equal(grid.cells_dict[22], cells)
    assert grid.points.dtype == points.dtype
    for name, values in data.items():
        assert grid.point_data[written_name(name)].dtype == values.dtype
        np.testing.assert_array_equal(grid.point_data[written_name(name)], values)


def test_meshio_reads_it_back_exactly(written):
    import meshio

    path, points, cells, data = written
    mesh = meshio.read(path)
    np.testing.assert_array_equal(mesh.points[:, :2], points)
    np.testing.assert_array_equal(mesh.cells_dict["triangle6"], cells)
    for name, values in data.items():
        assert mesh.point_data[written_name(name)].dtype == values.dtype
        np.testing.assert_array_equal(mesh.point_data[written_name(name)], values)

"""The files of a mesh cycle for ParaView: VTU fields named with their units, and a .pvd time
series over the rolling angle that lists every position's VTUs."""

import xml.etree.ElementTree as ET

import meshio
import numpy as np
import pytest

from fegear.toothpair import prepare_job, run_job


@pytest.fixture(scope="module")
def cycle(tmp_path_factory):
    out = tmp_path_factory.mktemp("cycle")
    job = prepare_job({"quality": "coarse", "positions": 3, "no-estimate": True})
    return out, run_job(job, out)


def test_the_pvd_lists_both_gears_at_every_position(cycle):
    out, result = cycle
    root = ET.parse(out / "cycle.pvd").getroot()
    assert root.get("type") == "Collection"
    sets = root.findall("./Collection/DataSet")
    betas = [r["position_deg"] for r in result.rows]
    for part, name in ((0, "gear1"), (1, "gear2")):
        mine = [d for d in sets if d.get("part") == str(part)]
        assert [float(d.get("timestep")) for d in mine] == pytest.approx(betas)
        for k, d in enumerate(mine):
            assert d.get("file") == f"cycle/{name}_{k:03d}.vtu"
            m = meshio.read(out / d.get("file"))
            assert "triangle6" in m.cells_dict
            assert m.point_data["contact_pressure_MPa"].max() > 0   # the loaded teeth are in
            assert all(k.endswith(("_mm", "_MPa")) for k in m.point_data)
    # a tenth or so of the whole gear: the loaded sectors and one either side
    whole = meshio.read(out / "gear1.vtu").points.shape[0]
    assert meshio.read(out / "cycle" / "gear1_000.vtu").points.shape[0] < whole / 3


def test_the_series_holds_the_fields_of_its_position(cycle):
    """The position written as the pair's own VTU is in the series with the same stresses."""
    out, result = cycle
    k = max(range(3), key=lambda i: result.rows[i]["root_stress_gear1_MPa"])
    whole = meshio.read(out / "gear1.vtu").point_data["von_mises_MPa"]
    part = meshio.read(out / "cycle" / f"gear1_{k:03d}.vtu").point_data["von_mises_MPa"]
    assert part.max() == pytest.approx(whole.max(), rel=1e-12)


def test_pyvista_reads_the_series_as_time(cycle):
    from fegear.figures import pyvista

    pv = pyvista()
    out, result = cycle
    reader = pv.get_reader(str(out / "cycle.pvd"))
    assert np.allclose(reader.time_values, [r["position_deg"] for r in result.rows])
    reader.set_active_time_value(reader.time_values[1])
    blocks = reader.read()
    assert blocks.n_blocks == 2 and blocks[0].n_points > 1000

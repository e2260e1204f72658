"""The design-space map: its rows agree with the admissibility check and its edges are the
ones refusals state."""

import doctest

import pytest

import fegear.geometry.space as space
from fegear.cli import main
from fegear.errors import ParameterError
from fegear.geometry.admissible import design_defect
from fegear.geometry.refusal import check_design


def test_the_module_example():
    tests = doctest.DocTestFinder().find(space)
    assert sum(doctest.DocTestRunner().run(t).attempted for t in tests) >= 3
    assert all(doctest.DocTestRunner().run(t).failed == 0 for t in tests)


def test_a_row_is_what_the_check_and_a_refusal_say():
    row = space.map_row({}, "h1", "f1", 0.3, [0.2, 0.5])
    assert row.kinds == ("", "loop")
    assert design_defect({"h1": 0.2, "f1": 0.3}) is None
    with pytest.raises(ParameterError) as exc:
        check_design({"h1": 0.5, "f1": 0.3}, given={"h1"})
    stated = float(exc.value.admissible.split("<= h1 <=")[1].split()[0])
    assert row.upper == pytest.approx(stated, abs=5e-4) and row.upper_reason == "loop"


def test_profile_map_writes_the_picture_and_its_tables(tmp_path, capsys):
    out = tmp_path / "map"
    assert main(["profile", "--map", "h1=0.2:0.4,f1=0.1:0.2", "--map-size", "5",
                 "--out", str(out)]) == 0
    assert (out / "map.png").stat().st_size > 10_000
    grid = (out / "map_grid.csv").read_text().splitlines()
    assert grid[0] == "f1,h1,design" and len(grid) == 1 + 25
    assert all(line.endswith("admissible") for line in grid[1:])   # the paper's ranges
    edges = (out / "map_edges.csv").read_text().splitlines()
    assert edges[0] == "f1,h1_lower,reason_below,h1_upper,reason_above" and len(edges) == 6
    assert "loop" in capsys.readouterr().out


@pytest.mark.parametrize("spec", ["h1", "h1,h1", "h1,z1", "h1=0.4:0.2,f1", "h1=a:b,f1"])
def test_a_bad_map_is_one_line(spec, tmp_path, capsys):
    assert main(["profile", "--map", spec, "--out", str(tmp_path / "x")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("fegear: error: --map")
    assert not (tmp_path / "x").exists()

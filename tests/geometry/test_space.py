"""The design-space map: its rows agree with the admissibility check and its edges are the
ones refusals state."""

import doctest
import re

import numpy as np
import pytest

import fegear.geometry.space as space
from fegear.cli import main
from fegear.errors import ParameterError
from fegear.geometry.admissible import design_defect
from fegear.geometry.refusal import check_design, step_of


def test_the_module_example():
    tests = doctest.DocTestFinder().find(space)
    assert sum(doctest.DocTestRunner().run(t).attempted for t in tests) >= 3
    assert all(doctest.DocTestRunner().run(t).failed == 0 for t in tests)


def _stated(err: ParameterError) -> tuple[float, float]:
    m = re.match(rf"(-?[\d.]+) <= {err.name} <= (-?[\d.]+)", err.admissible)
    assert m, err.admissible
    return float(m.group(1)), float(m.group(2))


# 5-6 s each: the default run takes one row each way, the others slow
@pytest.mark.parametrize("x, y, y_value", [
    ("h1", "f1", 0.15), pytest.param("h1", "f1", 0.6, marks=pytest.mark.slow),
    pytest.param("h1", "f1", 0.45, marks=pytest.mark.slow), ("f1", "h1", 0.3)])
def test_a_map_row_and_the_refusals_give_one_answer(x, y, y_value):
    """Along a row of the map every grid design inside the row's interval is admissible and
    every one outside refused; both ends are admissible and a printed step past an end that
    is not the span's is refused; and refusing a design past the interval states the row's
    interval to the digit, from a value just past it and from one far off (at f1 0.6 the map
    once showed h1 0.05-0.2081 while bands inside it were refused, and the same edge was
    printed 0.8308, 0.8309 and 0.8310)."""
    span = space.map_span(x, {})
    xs = np.linspace(*span, 20)
    row = space.map_row({}, x, y, y_value, xs)
    for xv, kind in zip(xs, row.kinds):
        assert (kind == "") == (row.lower <= xv <= row.upper), (xv, kind)
    step = step_of(x)
    at = {y: y_value}
    for end, past, reason in ((row.lower, row.lower - step, row.lower_reason),
                              (row.upper, row.upper + step, row.upper_reason)):
        assert design_defect({**at, x: end}) is None
        if reason is not None:
            assert design_defect({**at, x: past}).kind == reason
    refused = [row.upper + step, *[xv for xv in xs if xv > row.upper][-1:]]
    for xv in refused:
        with pytest.raises(ParameterError) as exc:
            check_design({**at, x: float(xv)}, given={x})
        assert exc.value.name == x
        assert _stated(exc.value) == (round(row.lower, 4), round(row.upper, 4)), xv


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

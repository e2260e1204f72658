"""Refusals: every inadmissible input names the parameter and its admissible range."""

import math

import pytest

from fegear.errors import ParameterError
from fegear.geometry.admissible import design_defect
from fegear.geometry.parameters import PairParameters
from fegear.geometry.refusal import check_design


@pytest.mark.parametrize("kw,name,fragment", [
    (dict(m=0), "m", "0 < m"),
    (dict(m=-2), "m", "0 < m"),
    (dict(m=math.nan), "m", "0 < m <= 100 mm"),        # the range, whatever is wrong
    (dict(m=math.inf), "m", "0 < m <= 100 mm"),
    (dict(m=True), "m", "0 < m <= 100 mm"),             # a bool is no number (not 1 mm)
    (dict(h1=math.nan), "h1", "0.05 <= h1 < 11.25"),
    (dict(f1=-math.inf), "f1", "0 <= f1 <= 1"),
    (dict(z2=44, z1=44), "z2", "45 <= z2 <= 2000 (z2 > z1 = 44)"),
    (dict(z2=40, z1=44), "z2", "z2 > z1 = 44"),
    (dict(z1=2, z2=5), "z1", "an integer 3 <= z1 <= 4"),
    (dict(z1=44.5), "z1", "an integer 3 <= z1 <= 44"),
    (dict(z1=True), "z1", "an integer 3 <= z1 <= 44"),
    (dict(h1=0), "h1", "0.05 <= h1"),
    (dict(h1=0.01), "h1", "0.05 <= h1"),
    (dict(h1=20), "h1", "h1 < 11.25"),
    (dict(f1=-0.1), "f1", "0 <= f1"),
    (dict(shift=-0.001), "shift", "0 <= shift"),
    (dict(rotation=1.0), "rotation", "rotation <= 0.15"),
    (dict(shift=0.01, tip_clearance=-0.02), "tip-clearance", "-0.01 <= tip-clearance"),
])
def test_simple_ranges(kw, name, fragment):
    with pytest.raises(ParameterError) as err:
        PairParameters(**kw)
    assert err.value.name == name
    assert fragment.replace(" ", "") in str(err.value).replace(" ", "")
    assert "\n" not in str(err.value)


@pytest.mark.parametrize("values,name,reason", [
    ({"f1": 0.7}, "f1", "folds back"),                # gear-2 curve loops
    ({"h1": 0.5, "f1": 0.3}, "f1", "folds back"),
    ({"h1": 0.9}, "h1", "folds back"),
    ({"h1": 3.0}, "h1", "folds back"),
])
def test_geometry_refusals_name_parameter_and_range(values, name, reason):
    with pytest.raises(ParameterError) as err:
        check_design(values, given=set(values))
    e = err.value
    assert e.name == name and reason in e.reason
    assert f"{name} <=" in e.admissible and "m=2, z2=45, z1=44" in e.admissible


def test_refusal_limit_is_sharp():
    """The reported limit is admissible and slightly above it is not."""
    with pytest.raises(ParameterError) as err:
        check_design({"h1": 0.9})
    limit = float(err.value.admissible.split("h1 <=")[1].split()[0])
    assert design_defect({"h1": limit}) is None
    assert design_defect({"h1": limit + 4e-4}) is not None


def test_the_loop_limit_of_f1_is_where_the_curve_stops_being_star_shaped():
    assert design_defect({"f1": 0.41}) is None
    assert design_defect({"f1": 0.42}).kind == "loop"

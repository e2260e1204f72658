"""Refusals: every inadmissible input names the parameter and its admissible range."""

import math

import pytest

from fegear.errors import ParameterError
from fegear.geometry.gear1 import Gear1Profile
from fegear.geometry.parameters import PairParameters


@pytest.mark.parametrize("kw,name,fragment", [
    (dict(m=0), "m", "0 < m"),
    (dict(m=-2), "m", "0 < m"),
    (dict(m=math.nan), "m", "finite"),
    (dict(m=math.inf), "m", "finite"),
    (dict(h1=math.nan), "h1", "finite"),
    (dict(f1=-math.inf), "f1", "finite"),
    (dict(z2=44, z1=44), "z2", "z2 > z1"),
    (dict(z2=40, z1=44), "z2", "z2 > z1 = 44"),
    (dict(z1=2, z2=5), "z1", "integer >= 3"),
    (dict(z1=44.5), "z1", "integer"),
    (dict(h1=0), "h1", "0 < h1"),
    (dict(h1=20), "h1", "h1 < 11.25"),
    (dict(f1=-0.1), "f1", "0 <= f1"),
    (dict(shift=-0.001), "shift", "0 <= shift"),
    (dict(rotation=1.0), "rotation", "rotation <= 0.15"),
    (dict(shift=0.01, tip_clearance=-0.02), "tip_clearance", "-0.01 <= tip_clearance"),
])
def test_simple_ranges(kw, name, fragment):
    with pytest.raises(ParameterError) as err:
        PairParameters(**kw)
    assert err.value.name == name
    assert fragment.replace(" ", "") in str(err.value).replace(" ", "")
    assert "\n" not in str(err.value)


@pytest.mark.parametrize("kw,name,reason", [
    (dict(f1=0.7), "f1", "loops"),                # gear-2 curve loops
    (dict(h1=0.5, f1=0.3), "f1", "loops"),
    (dict(h1=0.8), "h1", "no conjugate point"),   # normal misses the pitch circle
    (dict(h1=3.0), "h1", "loops"),
])
def test_geometry_refusals_name_parameter_and_range(kw, name, reason):
    with pytest.raises(ParameterError) as err:
        Gear1Profile(PairParameters(**kw))
    e = err.value
    assert e.name == name and reason in e.reason
    assert f"{name} <=" in e.admissible and "m=2, z2=45, z1=44" in e.admissible


def test_refusal_limit_is_sharp():
    """The reported limit is admissible and slightly above it is not."""
    with pytest.raises(ParameterError) as err:
        Gear1Profile(PairParameters(h1=0.8))
    limit = float(err.value.admissible.split("h1 <=")[1].split()[0])
    Gear1Profile(PairParameters(h1=limit - 2e-4))
    with pytest.raises(ParameterError):
        Gear1Profile(PairParameters(h1=limit + 2e-4))


def test_undercut_detected_for_cusp_on_working_flank():
    from fegear.geometry.admissible import defect
    # just past the f1 limit at h1 = 0.3 the near branch folds (cusp) or loses conjugacy
    assert defect(PairParameters(f1=0.39)) is None
    assert defect(PairParameters(f1=0.40)) is not None

"""The shared checks (:mod:`fegear.checks`): a bool is no number for any numeric input, and a
refusal states the range whatever is wrong with the value."""

import math

import numpy as np
import pytest

from fegear.checks import Input, number, require_finite, require_int, require_range
from fegear.errors import ParameterError


@pytest.mark.parametrize("value", [True, False, np.bool_(True), "2", None, 1j, [2.0]])
def test_a_bool_text_or_none_is_no_number(value):
    assert number(value) is None
    with pytest.raises(ParameterError):
        require_finite("m", value)


@pytest.mark.parametrize("value", [2, 2.5, np.float64(2.5), np.int64(2), np.float32(0.5)])
def test_real_numbers_are_numbers(value):
    assert number(value) == float(value)
    assert require_range("m", value, 0.0, 100.0, lo_open=True) == float(value)


@pytest.mark.parametrize("value", [True, "abc", math.nan, math.inf, -1.0, 101.0])
def test_a_range_is_stated_whatever_is_wrong(value):
    with pytest.raises(ParameterError) as err:
        require_range("m", value, 0.0, 100.0, lo_open=True, unit="mm")
    assert err.value.admissible == "0 < m <= 100 mm"


@pytest.mark.parametrize("value", [True, False, 2.5, math.nan, "3", 1, 400])
def test_an_integer_refusal_states_both_ends(value):
    with pytest.raises(ParameterError) as err:
        require_int("positions", value, 2, 360)
    assert err.value.admissible == "an integer 2 <= positions <= 360"


def test_an_integer_may_be_an_integral_float_or_numpys():
    assert require_int("z1", 44.0, 3) == 44 and require_int("z1", np.int64(44), 3) == 44
    row = Input("extra-pairs", int, 0, "more teeth", low=0, high=5)
    assert row.check(np.int64(2)) == 2 and type(row.check(2.0)) is int
    with pytest.raises(ParameterError):
        row.check(True)

"""The one header grammar of every input table (:mod:`fegear.files`): a name, then its unit in
brackets where it has one, converted where it is given; commas or semicolons (with decimal
commas) between the cells; whatever does not fit refused naming the line or the column."""

import pytest

from fegear.errors import ParameterError
from fegear.files import Column, column_of, read_table, read_text

TORQUE = Column(("torque",), {"N·m": 1.0, "Nm": 1.0, "kN·m": 1e3, "kNm": 1e3}, "N·m")
DEVIATION = Column(("fp", "pitch"), {"µm": 1.0, "um": 1.0, "mm": 1e3}, None)
COUNT = Column(("cycles",))
COLUMNS = (TORQUE, COUNT, DEVIATION)


def _column(heading):
    return column_of(heading, COLUMNS, "spectrum", "a.csv", "a header of torque and cycles")


@pytest.mark.parametrize("heading, name, factor", [
    ("torque", "torque", 1.0), ("Torque [N·m]", "torque", 1.0), ("torque [N*m]", "torque", 1.0),
    ("torque [N m]", "torque", 1.0), ("torque[Nm]", "torque", 1.0),
    ("torque [kN·m]", "torque", 1e3), ("cycles", "cycles", 1.0), ("cycles [-]", "cycles", 1.0),
    ("fp [µm]", "fp", 1.0), ("fp [μm]", "fp", 1.0), ("PITCH [mm]", "fp", 1e3),
])
def test_a_heading_is_a_name_and_an_optional_unit(heading, name, factor):
    column, got = _column(heading)
    assert (column.name, got) == (name, factor)


@pytest.mark.parametrize("heading, says", [
    ("torque [lbf·ft]", "the unit of column 'torque [lbf·ft]' in brackets: [N·m], [Nm], "
                        "[kN·m] or [kNm] (not 'lbf·ft'"),
    ("cycles [h]", "the unit of column 'cycles [h]' in brackets: none, [-] or [1] (not 'h'"),
    ("fp", "the unit of column 'fp' in brackets: [µm], [um] or [mm] (not none"),
    ("torque_Nm", "not 'torque_Nm' (the unit goes in brackets: torque [Nm])"),
    ("fp_um", "(the unit goes in brackets: fp [um])"),
    ("Nm", "not 'Nm' (a unit alone: torque [Nm])"),
    ("load", "a header of torque and cycles, each a name with its unit in brackets where it "
             "has one (e.g. 'torque [N·m]'); not 'load'"),
])
def test_a_heading_outside_the_grammar_is_refused_saying_it(heading, says):
    with pytest.raises(ParameterError) as err:
        _column(heading)
    assert err.value.name == "spectrum" and says in str(err.value), str(err.value)


def _table(text):
    return read_table(text, COLUMNS, "spectrum", "a.csv", "a header of torque and cycles")


def test_a_table_in_units_is_read_in_the_columns_own():
    table = _table("# the duty\ntorque [kN·m], cycles\n\n0.1, 1e6\n0.25, 2e4\n")
    assert table.columns == ("torque", "cycles") and table.separator == ","
    assert [(r.line, r.values) for r in table.rows] == [
        (4, {"torque": 100.0, "cycles": 1e6}), (5, {"torque": 250.0, "cycles": 2e4})]


def test_a_semicolon_file_is_read_with_its_decimal_commas():
    # as a spreadsheet saves CSV where the comma is the decimal mark
    table = _table("torque [N·m];cycles\n62,5;1,5E+06\n200;2e4\n")
    assert table.separator == ";"
    assert [r.values for r in table.rows] == [{"torque": 62.5, "cycles": 1.5e6},
                                              {"torque": 200.0, "cycles": 2e4}]
    assert _table("torque;cycles\n62.5;1e6\n").rows[0].values["torque"] == 62.5  # points


@pytest.mark.parametrize("text, says", [
    ("torque;cycles\n1.000,5;3\n", "line 2: a number in column 'torque', not '1.000,5' (this "
                                   "file's decimal mark is the comma: no thousands separators)"),
    ("torque;cycles\n1,5;1.000\n", "line 2: a number in column 'cycles', not '1.000'"),
    ("torque,cycles\n1,x\n", "line 2: a number in column 'cycles', not 'x'"),
    ("torque,cycles\n1,nan\n", "line 2: a number in column 'cycles', not 'nan'"),
    ("torque,cycles\n\n1,2,3\n", "line 3: 2 cells as in the header, not 3"),
    ("torque,cycles\n1\n", "line 2: 2 cells as in the header, not 1"),
    ("fp [µm], pitch [mm]\n1,2\n", "each column once: 'fp [µm]' and 'pitch [mm]' are both fp"),
])
def test_a_bad_table_is_refused_naming_the_line_or_column(text, says):
    with pytest.raises(ParameterError) as err:
        _table(text)
    assert says in str(err.value) and "\n" not in str(err.value), str(err.value)


def test_a_spreadsheet_s_text_is_read_whatever_it_is_saved_as(tmp_path):
    path = tmp_path / "a.csv"
    for encoding in ("utf-8-sig", "cp1252"):   # a byte order mark; a Western "ANSI" file
        path.write_bytes("fp [µm]\n1\n".encode(encoding))
        assert read_text(path, "deviations", "CSV file") == "fp [µm]\n1\n"
    with pytest.raises(ParameterError, match="a readable CSV file"):
        read_text(tmp_path / "missing.csv", "deviations", "CSV file")

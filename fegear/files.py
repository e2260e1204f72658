"""Files: writing results (atomic files: nothing half-written is ever left behind; CSV, JSON),
and reading the tables a user gives (a deviations file, a load spectrum) in one grammar.

Every input table's header speaks one grammar: each column a name, then its unit in brackets
where it has one (``fp [µm]``, ``torque [kN·m]``; a column without a unit is in its own unit,
where it has one), the names matched without regard to case, values converted to the column's
own unit. Cells are separated by commas, or by semicolons (as spreadsheets save CSV in locales
with a decimal comma: there ``1,5`` is 1.5), found from the header line; blank lines and lines
starting with ``#`` are skipped. Whatever does not fit is one
:class:`~fegear.errors.ParameterError` naming the input, the line or the column.
"""

from __future__ import annotations

import json
import math
import os
import re
import tempfile
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .errors import FegearError, ParameterError


class OutputError(FegearError):
    """An output path cannot be created or written."""


def prepare_dir(path: str | os.PathLike) -> Path:
    """Prove ``path`` can be a writable directory (:func:`check_dir`), then create it (and
    its parents); raise :class:`OutputError`."""
    out = check_dir(path)
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise OutputError(f"--out {str(out)!r} cannot be created: {exc.strerror}") from None
    return out


def check_dir(path: str | os.PathLike) -> Path:
    """Check that ``path`` is, or can be made, a writable directory, and leave nothing behind:
    raise :class:`OutputError` if not. A command checks its ``--out`` with this before it
    computes, and makes the directory with :func:`prepare_dir` only when it has results to
    write. The check is proof, not permission bits (``os.access`` says yes to root on /proc
    and on a read-only mount): a probe directory is made and removed in ``path``, or in its
    nearest existing ancestor, where the directory would be made."""
    out = Path(path)
    base = out.absolute()
    while not base.exists() and base != base.parent:
        base = base.parent
    if not base.is_dir():
        what = "is a file, not a directory" if base == out.absolute() else (
            f"cannot be created: {str(base)!r} is a file, not a directory")
        raise OutputError(f"--out {str(out)!r} {what}")
    try:
        probe = tempfile.mkdtemp(prefix=".fegear-probe-", dir=base)
    except OSError as exc:
        where = "is not writable" if base == out.absolute() else (
            f"cannot be created in {str(base)!r}")
        raise OutputError(f"--out {str(out)!r} {where}: {exc.strerror or exc}") from None
    os.rmdir(probe)
    return out


def write_atomic(path: Path, writer: Callable[[Path], None]) -> Path:
    """Call ``writer(tmp)`` on a temporary file beside ``path``, then rename it into place
    with the permissions an ordinary file gets (the temporary file is private: 0600)."""
    path = Path(path)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=path.suffix, dir=path.parent)
    os.close(fd)
    try:
        writer(Path(tmp))
        os.chmod(tmp, 0o666 & ~_umask())
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return path


def _umask() -> int:
    mask = os.umask(0o022)  # reading the mask means setting it: put it back at once
    os.umask(mask)
    return mask


def write_points_csv(path: Path, points: np.ndarray, extra: dict | None = None) -> Path:
    """Write an (n, 2) point array as CSV with header ``x_mm,y_mm`` (full float precision),
    and the ``extra`` columns (name → (n,) values) after them."""
    extra = extra or {}
    table = np.column_stack([points, *extra.values()]) if extra else points

    def w(tmp: Path) -> None:
        np.savetxt(tmp, table, delimiter=",", header=",".join(["x_mm", "y_mm", *extra]),
                   comments="", fmt="%.17g")

    return write_atomic(path, w)


def write_csv(path: Path, header: Sequence[str], rows: Iterable[Sequence]) -> Path:
    """Write a table as CSV: floats at full precision (``repr``), anything else as ``str``; a
    cell with a comma, quote or line break (a refused design's reason) quoted."""
    import csv

    def cell(v) -> str:
        return repr(float(v)) if isinstance(v, (float, np.floating)) else str(v)

    def w(tmp: Path) -> None:
        with open(tmp, "w", newline="") as f:
            writer = csv.writer(f, lineterminator="\n")
            writer.writerow(header)
            writer.writerows([cell(v) for v in row] for row in rows)

    return write_atomic(path, w)


def write_json(path: Path, data: dict) -> Path:
    def w(tmp: Path) -> None:
        tmp.write_text(json.dumps(data, indent=2, allow_nan=False) + "\n")

    return write_atomic(path, w)


# --- reading the tables a user gives ---------------------------------------------------------

#: the units of a column without one: none given, or [-] or [1]
DIMENSIONLESS = {"-": 1.0, "1": 1.0}


@dataclass(frozen=True)
class Column:
    """A column an input table takes: its ``names`` (the first its own, the others the same
    column; matched without regard to case), the ``units`` it takes in brackets (as written
    → the factor to its own unit) and the one a heading without a unit means (``default``, a
    key of ``units``; None: the unit must be given, where a wrong guess is a factor of
    1000)."""

    names: tuple[str, ...]
    units: Mapping[str, float] = field(default_factory=lambda: dict(DIMENSIONLESS))
    default: str | None = "-"

    @property
    def name(self) -> str:
        return self.names[0]

    def factor(self, unit: str | None) -> float | None:
        """The factor from ``unit`` (as written in brackets; None: none written) to the
        column's own unit, None if the column does not take it."""
        if unit is None:
            return None if self.default is None else self.units[self.default]
        spelled = {_unit_key(u): f for u, f in self.units.items()}
        return spelled.get(_unit_key(unit))

    @property
    def units_text(self) -> str:
        """The units it takes, as a refusal lists them: ``[µm], [um] or [mm]``."""
        shown = [f"[{u}]" for u in self.units]
        if self.default is not None and set(self.units) == set(DIMENSIONLESS):
            shown = ["none", *shown]
        return ", ".join(shown[:-1]) + f" or {shown[-1]}"


def _unit_key(unit: str) -> str:
    """A unit as compared: spaces out, ``N*m``, ``N⋅m`` and ``N.m`` as ``N·m``, the Greek mu
    as the micro sign; case kept (``mm`` is not ``Mm``)."""
    return re.sub(r"\s+", "", unit).translate(str.maketrans("*⋅.μ", "···µ"))


#: a heading: a name, then its unit in brackets where one is given
HEADING = re.compile(r"\s*(?P<name>[^\[\]]*?)\s*(?:\[\s*(?P<unit>[^\[\]]*?)\s*\])?\s*")


def column_of(heading: str, columns: Sequence[Column], parameter: str, path, expects: str,
              *, where: str = "", word: str = "column") -> tuple[Column, float]:
    """The column of ``columns`` a ``heading`` (``name`` or ``name [unit]``) names and the
    factor from its unit to the column's own. A heading that names no column, or a unit the
    column does not take, is refused as a :class:`~fegear.errors.ParameterError` of
    ``parameter`` = ``path``, after ``where`` it is (a TOML file's ``level 2``) and calling it
    a ``word`` (a TOML file's ``key``); ``expects`` says what header the file wants."""
    def refuse(what: str) -> ParameterError:
        return ParameterError(parameter, str(path), f"{where}: {what}" if where else what)

    m = HEADING.fullmatch(heading)
    name, unit = (m.group("name"), m.group("unit")) if m else (heading.strip(), None)
    by_name = {n.lower(): c for c in columns for n in c.names}
    column = by_name.get(name.lower()) if m else None
    if column is None:
        raise refuse(f"{expects}, each a name with its unit in brackets where it has one "
                     f"(e.g. {_example(columns)!r}); not {heading.strip()!r}"
                     + _hint(name, columns))
    factor = column.factor(unit)
    if factor is None:
        given = "none" if unit is None else repr(unit)
        example = f"{column.name} [{next(iter(column.units))}]"
        raise refuse(f"the unit of {word} {heading.strip()!r} in brackets: "
                     f"{column.units_text} (not {given}; e.g. {example!r})")
    return column, factor


def _example(columns: Sequence[Column]) -> str:
    """A heading with a unit, as a refusal shows the grammar."""
    column = next((c for c in columns if set(c.units) != set(DIMENSIONLESS)), columns[0])
    return f"{column.name} [{next(iter(column.units))}]"


def _hint(name: str, columns: Sequence[Column]) -> str:
    """What a heading that names no column may have meant: a unit after an underscore
    (``torque_Nm``) or a unit alone (``Nm``)."""
    for c in columns:
        for n in c.names:
            if name.lower().startswith(n.lower() + "_"):
                unit = name[len(n) + 1:]
                shown = next((u for u in c.units if _unit_key(u) == _unit_key(unit)),
                             next(iter(c.units)))
                return f" (the unit goes in brackets: {c.name} [{shown}])"
        if c.factor(name) is not None and set(c.units) != set(DIMENSIONLESS):
            return f" (a unit alone: {c.name} [{name}])"
    return ""


@dataclass(frozen=True)
class TableRow:
    """A data row of an input table: its ``line`` in the file (from 1) and its ``values``
    by column name, each in its column's own unit."""

    line: int
    values: dict[str, float]


@dataclass(frozen=True)
class Table:
    """An input table read (:func:`read_table`): the names of its ``columns`` in the order of
    its header, its ``rows``, and the ``separator`` of its cells."""

    columns: tuple[str, ...]
    rows: tuple[TableRow, ...]
    separator: str


def read_text(path, parameter: str, what: str) -> str:
    """The text of the file an input ``parameter`` names: UTF-8 (a spreadsheet's byte order
    mark dropped) or, failing that, Windows-1252, as spreadsheets save CSV in Western
    locales. A file that cannot be read is refused naming ``what`` it should be."""
    try:
        raw = Path(path).read_bytes()
    except OSError as exc:
        raise ParameterError(parameter, str(path), f"a readable {what} "
                             f"({exc.strerror or exc.__class__.__name__})") from None
    try:
        return raw.decode("utf-8-sig")
    except UnicodeDecodeError:
        try:
            return raw.decode("cp1252")
        except UnicodeDecodeError:
            raise ParameterError(parameter, str(path), f"a readable {what} (text in UTF-8 "
                                 "or Windows-1252)") from None


def read_table(text: str, columns: Sequence[Column], parameter: str, path,
               expects: str) -> Table:
    """The table in ``text`` (module docstring): its header's columns (each once) and its
    rows, every cell a finite number in its column's own unit. Anything else is refused as a
    :class:`~fegear.errors.ParameterError` of ``parameter`` = ``path`` naming the line and
    column; ``expects`` says what header the file wants. Which columns the file needs
    together is the caller's to check."""
    import csv

    def refuse(what: str) -> ParameterError:
        return ParameterError(parameter, str(path), what)

    numbered = [(k + 1, line) for k, line in enumerate(text.splitlines())
                if line.strip() and not line.lstrip().startswith("#")]
    if not numbered:
        return Table((), (), ",")
    separator = ";" if ";" in numbered[0][1] else ","
    cells = list(csv.reader([line for _, line in numbered], delimiter=separator,
                            skipinitialspace=True))
    headings = [h.strip() for h in cells[0]]
    found: dict[str, tuple[str, float]] = {}    # column name → (heading, factor)
    for heading in headings:
        column, factor = column_of(heading, columns, parameter, path, expects)
        if column.name in found:
            raise refuse(f"each column once: {found[column.name][0]!r} and {heading!r} are "
                         f"both {column.name}")
        found[column.name] = (heading, factor)
    # a semicolon file with a comma in a cell writes decimal commas: a point there is a
    # thousands separator, which is refused rather than read as a decimal point
    commas = separator == ";" and any("," in c for row in cells[1:] for c in row)
    rows = []
    for (line, _), row in zip(numbered[1:], cells[1:]):
        if len(row) != len(headings):
            raise refuse(f"line {line}: {len(headings)} cells as in the header, not "
                         f"{len(row)}")
        values = {}
        for (name, (heading, factor)), cell in zip(found.items(), row):
            number = _number(cell.strip(), commas)
            if not math.isfinite(number):
                mark = (" (this file's decimal mark is the comma: no thousands separators)"
                        if commas and "." in cell else "")
                raise refuse(f"line {line}: a number in column {heading!r}, not "
                             f"{cell.strip()!r}{mark}")
            values[name] = number * factor
        rows.append(TableRow(line, values))
    return Table(tuple(found), tuple(rows), separator)


def _number(text: str, decimal_comma: bool) -> float:
    """``text`` as a number (nan if it is none); with a ``decimal_comma``, ``1,5`` is 1.5 and
    a point is no part of a number."""
    if decimal_comma:
        if "." in text:
            return math.nan
        text = text.replace(",", ".")
    try:
        return float(text)
    except ValueError:
        return math.nan

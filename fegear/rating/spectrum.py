"""A load spectrum (``--spectrum FILE``): the duty cycle's torque levels and how often each is
met (docs/rating.md, "The spectrum file").

A file gives levels of torque (N·m) with either their ``cycles`` (revolutions of gear 1
against gear 2: each gear-1 tooth meshes once a revolution) or their ``share`` of the time, which
a speed (rpm, gear 1 against gear 2) and a required life (hours) turn into cycles. CSV: a
header ``torque,cycles`` or ``torque,share`` and a row a level, in the header grammar of every
input table (:mod:`fegear.files`: a unit in brackets where one is given, ``torque [kN·m]``,
``share [%]``; commas, or semicolons with decimal commas); TOML: ``[[level]]`` tables with the
same keys. Every fault (no level, a negative count, shares that do not add up to 1, shares
without a speed and a life, a torque of zero or less) is one error naming the file, the line or
level, and what it needs.
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass
from pathlib import Path

from ..errors import ParameterError
from ..files import Column, column_of, read_table, read_text

#: how far the shares may add up from 1 (a table typed to three decimals)
SHARE_TOLERANCE = 1e-3
#: a level's columns (a CSV file's) or keys (a TOML file's), each in its own unit
COLUMNS = (Column(("torque",), {"N·m": 1.0, "Nm": 1.0, "kN·m": 1e3, "kNm": 1e3}, "N·m"),
           Column(("cycles",)), Column(("share",), {"-": 1.0, "1": 1.0, "%": 0.01}, "-"))
HEADER = "a header torque,cycles or torque,share"


@dataclass(frozen=True)
class LoadLevel:
    """One load level of a spectrum: ``torque`` (N·m) met ``cycles`` times (revolutions of
    gear 1 against gear 2)."""

    torque: float
    cycles: float


@dataclass(frozen=True)
class Spectrum:
    """The levels of a duty cycle, their cycles over the required life, and the ``hours``
    that life is (None where the file gives cycles and no life is asked for)."""

    levels: tuple[LoadLevel, ...]
    hours: float | None = None

    @property
    def cycles(self) -> float:
        """The revolutions over the whole spectrum."""
        return sum(level.cycles for level in self.levels)


def read_spectrum(path, speed_rpm: float | None = None, life_h: float | None = None
                  ) -> Spectrum:
    """The spectrum in ``path`` (CSV or TOML, module docstring); shares become cycles over
    ``life_h`` hours at ``speed_rpm``. Raises :class:`~fegear.errors.ParameterError` naming
    ``spectrum`` (or ``speed``, ``life``) with what is wrong."""
    path = Path(path)
    rows = _rows(path)
    if not rows:
        raise ParameterError("spectrum", str(path), "a file with at least one level")
    for where, row in rows:
        _check_row(path, where, row)
    kinds = {"cycles" in r for _, r in rows}
    if len(kinds) > 1:
        raise ParameterError("spectrum", str(path), "cycles at every level or shares at "
                             "every level, not both")
    if kinds == {True}:
        levels = tuple(LoadLevel(float(r["torque"]), float(r["cycles"])) for _, r in rows)
        hours = None if life_h is None or speed_rpm is None else life_h
        return Spectrum(levels, hours)
    total = sum(float(r["share"]) for _, r in rows)
    if abs(total - 1.0) > SHARE_TOLERANCE:
        raise ParameterError("spectrum", str(path), f"shares that add up to 1 (they add up "
                             f"to {total:.4g})")
    if speed_rpm is None or life_h is None:
        raise ParameterError("spectrum", str(path), "--speed and --life with shares of "
                             "time (they turn them into cycles)")
    revolutions = speed_rpm * 60.0 * life_h
    return Spectrum(tuple(LoadLevel(float(r["torque"]), float(r["share"]) / total * revolutions)
                          for _, r in rows), life_h)


def _rows(path: Path) -> list[tuple[str, dict]]:
    """The file's levels as (where, values by key in the keys' own units) pairs: "line 3" of
    a CSV, "level 2" of a TOML."""
    text = read_text(path, "spectrum", "file")
    if path.suffix == ".toml":
        try:
            levels = tomllib.loads(text).get("level", [])
        except tomllib.TOMLDecodeError as exc:
            raise ParameterError("spectrum", str(path), f"valid TOML ({exc})") from None
        if not isinstance(levels, list) or not all(isinstance(v, dict) for v in levels):
            raise ParameterError("spectrum", str(path), "[[level]] tables")
        return [(f"level {k + 1}", _level(path, f"level {k + 1}", v))
                for k, v in enumerate(levels)]
    if path.suffix != ".csv":
        raise ParameterError("spectrum", str(path), "a .csv or .toml file")
    table = read_table(text, COLUMNS, "spectrum", path, HEADER)
    if table.columns and set(table.columns) not in ({"torque", "cycles"}, {"torque", "share"}):
        raise ParameterError("spectrum", str(path), f"{HEADER} (not "
                             f"{table.separator.join(table.columns)})")
    return [(f"line {row.line}", row.values) for row in table.rows]


def _level(path: Path, where: str, keys: dict) -> dict:
    """A TOML level's keys by their names, the values in their own units (a key names its
    unit as a CSV file's heading does: ``"torque [kN·m]" = 0.25``)."""
    out: dict[str, object] = {}
    for key, value in keys.items():
        column, factor = column_of(key, COLUMNS, "spectrum", path, "keys torque and cycles, or "
                                   "torque and share", where=where, word="key")
        if column.name in out:
            raise ParameterError("spectrum", str(path), f"{where}: each key once (two give "
                                 f"{column.name})")
        number = None if isinstance(value, bool) else _number(value)
        out[column.name] = value if number is None else number * factor
    return out


def _number(value) -> float | None:
    try:
        return float(value)
    except (TypeError, ValueError):
        return None


def _check_row(path: Path, where: str, row: dict) -> None:
    """One level's keys and values, refused by name."""
    keys = set(row)
    if keys not in ({"torque", "cycles"}, {"torque", "share"}):
        raise ParameterError("spectrum", str(path), f"torque and cycles, or torque and share, "
                             f"at {where} (not {', '.join(sorted(map(str, keys)))})")
    for key in keys:
        try:
            value = float(row[key])
        except (TypeError, ValueError):
            raise ParameterError("spectrum", str(path), f"{where}: a number in key {key!r}, "
                                 f"not {row[key]!r}") from None
        if not math.isfinite(value) or value < 0 or (key == "torque" and value == 0):
            need = "a torque > 0" if key == "torque" else f"{key} >= 0"
            raise ParameterError("spectrum", str(path), f"{need} at {where} (not {value:g})")

"""A load spectrum (``--spectrum FILE``): the duty cycle's torque levels and how often each is
met (docs/rating.md, "Load spectra").

A file gives levels of torque (N·m) with either their ``cycles`` (revolutions of gear 1
against gear 2: each gear-1 tooth meshes once a revolution) or their ``share`` of the time, which
a speed (rpm, gear 1 against gear 2) and a required life (hours) turn into cycles. CSV: a
header ``torque,cycles`` or ``torque,share`` and a row a level; TOML: ``[[level]]`` tables
with the same keys. Every fault (no level, a negative count, shares that do not add up to 1,
shares without a speed and a life, a torque of zero or less) is one error naming the file,
the line or level, and what it needs.
"""

from __future__ import annotations

import csv
import math
import tomllib
from dataclasses import dataclass
from pathlib import Path

from ..errors import ParameterError

#: how far the shares may add up from 1 (a table typed to three decimals)
SHARE_TOLERANCE = 1e-3


@dataclass(frozen=True)
class Level:
    """One level: ``torque`` (N·m) met ``cycles`` times (revolutions of gear 1 against gear
    2)."""

    torque: float
    cycles: float


@dataclass(frozen=True)
class Spectrum:
    """The levels of a duty cycle, their cycles over the required life, and the ``hours``
    that life is (None where the file gives cycles and no life is asked for)."""

    levels: tuple[Level, ...]
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
        levels = tuple(Level(float(r["torque"]), float(r["cycles"])) for _, r in rows)
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
    return Spectrum(tuple(Level(float(r["torque"]), float(r["share"]) / total * revolutions)
                          for _, r in rows), life_h)


def _rows(path: Path) -> list[tuple[str, dict]]:
    """The file's levels as (where, keys) pairs: "line 3" of a CSV, "level 2" of a TOML."""
    try:
        text = path.read_text()
    except OSError as exc:
        raise ParameterError("spectrum", str(path), f"a readable file ({exc.strerror})") \
            from None
    if path.suffix == ".toml":
        try:
            levels = tomllib.loads(text).get("level", [])
        except tomllib.TOMLDecodeError as exc:
            raise ParameterError("spectrum", str(path), f"valid TOML ({exc})") from None
        if not isinstance(levels, list):
            raise ParameterError("spectrum", str(path), "[[level]] tables")
        return [(f"level {k + 1}", dict(v)) for k, v in enumerate(levels)]
    if path.suffix != ".csv":
        raise ParameterError("spectrum", str(path), "a .csv or .toml file")
    if not text.strip():
        return []
    reader = csv.DictReader(line for line in text.splitlines() if line.strip())
    header = set(reader.fieldnames or ())
    if header not in ({"torque", "cycles"}, {"torque", "share"}):
        raise ParameterError("spectrum", str(path), "a header torque,cycles or torque,share "
                             f"(not {','.join(reader.fieldnames or ()) or 'none'})")
    return [(f"line {reader.line_num}", row) for row in reader]


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
            raise ParameterError("spectrum", str(path), f"a number for {key} at {where} "
                                 f"(not {row[key]!r})") from None
        if not math.isfinite(value) or value < 0 or (key == "torque" and value == 0):
            need = "a torque > 0" if key == "torque" else f"{key} >= 0"
            raise ParameterError("spectrum", str(path), f"{need} at {where} (not {value:g})")

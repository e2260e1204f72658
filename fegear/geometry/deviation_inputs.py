"""Deviations as a user gives them (:mod:`.deviations`): on the command line and in study files
as short texts, or as a file of measured deviations.

* ``GEAR:TOOTH=µm``, comma-separated: a tooth's pitch, slope or form deviation
  (``--pitch-deviation 1:11=5,2:30=-3``);
* ``GEAR=µm[@deg]``, comma-separated: a gear's radial runout and the angle of its high point
  (``--runout 1=10@90``; without ``@deg``, 0°);
* a CSV file, one row per tooth as a gear measuring machine reports them: columns ``gear``,
  ``tooth`` and any of ``fp`` (the tooth's position deviation; also ``pitch``), ``fpt`` (its
  single pitch deviation from the tooth before, summed into positions: every tooth of that gear
  then), ``fHa`` (profile slope) and ``ffa`` (profile form), each with its unit in brackets,
  ``[µm]``, ``[um]`` or ``[mm]`` (``fp [µm]``), in the header grammar of every input table
  (:mod:`fegear.files`: commas, or semicolons with decimal commas; lines starting with ``#``
  are comments). A tooth has one row.

Whatever is wrong is refused in one line naming the option, the row or the column.
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping
from dataclasses import replace

from ..errors import ParameterError
from ..files import Column, read_table, read_text
from .deviations import LIMIT_UM, Deviations, Runout, ToothDeviation

#: the per-tooth options and the field each sets
PER_TOOTH = {"pitch-deviation": "pitch", "slope-deviation": "slope", "form-deviation": "form"}
#: a deviation column's units: one must be given (µm or mm, a factor of 1000 apart)
UNITS = {"µm": 1.0, "um": 1.0, "mm": 1e3}
#: the file's columns, and the field each deviation column sets ("fpt" is summed into
#: positions)
COLUMNS = (Column(("gear",)), Column(("tooth",)), Column(("fp", "pitch"), UNITS, None),
           Column(("fpt",), UNITS, None), Column(("fHa", "slope"), UNITS, None),
           Column(("ffa", "form"), UNITS, None))
FIELDS = {"fp": "pitch", "fpt": "fpt", "fHa": "slope", "ffa": "form"}
HEADER = "columns gear, tooth and any of fp (or pitch), fpt, fHa (or slope), ffa (or form)"
TOOTH_SPEC = "GEAR:TOOTH=µm, comma-separated (e.g. 1:11=5,2:30=-3), GEAR 1 or 2"
RUNOUT_SPEC = ("GEAR=µm[@deg], comma-separated (e.g. 1=10@90; without @deg, 0°), GEAR 1 or 2, "
               "0 <= µm <= 1000")


def per_tooth(name: str, text) -> dict[tuple[int, int], float]:
    """``GEAR:TOOTH=µm`` entries of option ``name`` → {(gear, tooth): µm}."""
    out: dict[tuple[int, int], float] = {}
    for part in _parts(text):
        m = re.fullmatch(r"\s*([12])\s*:\s*(\d+)\s*=\s*([^=]+?)\s*", part)
        value = _number(m.group(3)) if m else math.nan
        if not m or not math.isfinite(value) or abs(value) > LIMIT_UM:
            raise ParameterError(name, text, f"{TOOTH_SPEC}, |µm| <= {LIMIT_UM:g}")
        out[(int(m.group(1)), int(m.group(2)))] = value
    return out


def runouts(text) -> dict[int, Runout]:
    """``GEAR=µm[@deg]`` entries of ``--runout`` → {gear: Runout} (without ``@deg``, the high
    point at 0°)."""
    out: dict[int, Runout] = {}
    for part in _parts(text):
        m = re.fullmatch(r"\s*([12])\s*=\s*([^@]+?)\s*(?:@\s*(.+?)\s*)?", part)
        fr = _number(m.group(2)) if m else math.nan
        phase = _number(m.group(3)) if m and m.group(3) is not None else 0.0
        if not m or not (math.isfinite(fr) and 0 <= fr <= LIMIT_UM and math.isfinite(phase)):
            raise ParameterError("runout", text, RUNOUT_SPEC)
        out[int(m.group(1))] = Runout(fr, phase)
    return out


def deviations_of(values: Mapping[str, object], z1: int, z2: int) -> Deviations:
    """The deviations the solve inputs name (by their option names: the file first, then the
    per-tooth options over it, the centre distance and the runouts), their teeth checked
    against ``z1`` and ``z2``."""
    teeth: dict[tuple[int, int], ToothDeviation] = {}
    if values.get("deviations"):
        teeth.update(read_deviations(values["deviations"], z1, z2))
    for name, attr in PER_TOOTH.items():
        for key, um in per_tooth(name, values.get(name)).items():
            teeth[key] = replace(teeth.get(key, ToothDeviation()), **{attr: um})
    runout = runouts(values.get("runout"))
    found = Deviations({t: d for (g, t), d in teeth.items() if g == 1},
                       {t: d for (g, t), d in teeth.items() if g == 2},
                       float(values.get("centre-distance-deviation") or 0.0),
                       runout.get(1, Runout()), runout.get(2, Runout()))
    found.check_teeth(z1, z2)
    return found


def read_deviations(path, z1: int, z2: int) -> dict[tuple[int, int], ToothDeviation]:
    """The per-tooth deviations of the file ``path`` (module docstring) → {(gear, tooth):
    deviation}."""
    table = read_table(read_text(path, "deviations", "CSV file of measured deviations"),
                       COLUMNS, "deviations", path, HEADER)
    fields = [c for c in table.columns if c in FIELDS]
    if not {"gear", "tooth"} <= set(table.columns) or not fields:
        raise ParameterError("deviations", str(path), "a header with gear, tooth and at least "
                             "one deviation column (with its unit: fp [µm]), and a row a "
                             "tooth")
    z = {1: z1, 2: z2}
    got: dict[tuple[int, int], dict[str, float]] = {}
    lines: dict[tuple[int, int], int] = {}
    for row in table.rows:
        gear, tooth = _whole(path, row, "gear"), _whole(path, row, "tooth")
        if gear not in z or not 0 <= tooth < z[gear]:
            raise ParameterError("deviations", str(path), f"line {row.line}: gear 1 (teeth 0 "
                                 f"... {z1 - 1}) or 2 (teeth 0 ... {z2 - 1}), not gear {gear} "
                                 f"tooth {tooth}")
        if (gear, tooth) in lines:   # measured twice: which row is meant is the user's call
            raise ParameterError("deviations", str(path), f"one row a tooth (lines "
                                 f"{lines[(gear, tooth)]} and {row.line} both give gear "
                                 f"{gear} tooth {tooth})")
        lines[(gear, tooth)] = row.line
        got[(gear, tooth)] = {FIELDS[c]: row.values[c] for c in fields}
    for gear in (1, 2):   # single pitch deviations: each tooth's position is their running sum
        mine = sorted(t for g, t in got if g == gear)
        if "fpt" in fields and mine:
            if mine != list(range(z[gear])):
                raise ParameterError("deviations", str(path), f"every tooth 0 ... "
                                     f"{z[gear] - 1} of gear {gear}: fpt, the single pitch "
                                     "deviations, add up to the teeth's positions")
            total = 0.0
            for t in mine:
                total += got[(gear, t)].pop("fpt")
                got[(gear, t)]["pitch"] = got[(gear, t)].get("pitch", 0.0) + total
    try:
        return {key: ToothDeviation(**v) for key, v in got.items()}
    except ParameterError as err:
        raise ParameterError("deviations", str(path), err.admissible, err.reason) from None


def _whole(path, row, column: str) -> int:
    value = row.values[column]
    if value != int(value):
        raise ParameterError("deviations", str(path), f"line {row.line}: a whole number in "
                             f"column {column!r}, not {value:g}")
    return int(value)


def _parts(given) -> list[str]:
    """The entries of a deviation option: a text of comma-separated entries, a list of such
    texts (the option given more than once, a study file's list) or a mapping of entries to
    values (``{"1:11": 5}`` from Python)."""
    if isinstance(given, Mapping):
        given = [f"{k}={v}" for k, v in given.items()]
    if isinstance(given, (list, tuple)):
        given = ",".join(str(g) for g in given)
    return [p for p in str(given or "").split(",") if p.strip()]


def _number(text) -> float:
    try:
        return float(text)
    except (TypeError, ValueError):
        return math.nan

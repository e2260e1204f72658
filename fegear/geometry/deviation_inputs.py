"""Deviations as a user gives them (:mod:`.deviations`): on the command line and in study files
as short texts, or as a file of measured deviations.

* ``GEAR:TOOTH=µm``, comma-separated: a tooth's pitch, slope or form deviation
  (``--pitch-deviation 1:11=5,2:30=-3``);
* ``GEAR=µm@deg``, comma-separated: a gear's radial runout and the angle of its high point
  (``--runout 1=10@90``; without ``@deg``, 0°);
* a CSV file, one row per tooth as a gear measuring machine reports them: columns ``gear``,
  ``tooth`` and any of ``fp`` (the tooth's position deviation; also ``pitch``), ``fpt`` (its
  single pitch deviation from the tooth before, summed into positions: every tooth of that gear
  then), ``fHa`` (profile slope) and ``ffa`` (profile form), each with its unit in brackets,
  ``[µm]``, ``[um]`` or ``[mm]`` (``fp [µm]``); lines starting with ``#`` are comments.

Whatever is wrong is refused in one line naming the option, the row or the column.
"""

from __future__ import annotations

import csv
import math
import re
from collections.abc import Mapping
from dataclasses import replace
from pathlib import Path

from ..errors import ParameterError
from .deviations import LIMIT_UM, Deviations, Runout, ToothDeviation

#: the per-tooth options and the field each sets
PER_TOOTH = {"pitch-deviation": "pitch", "slope-deviation": "slope", "form-deviation": "form"}
#: the file's columns: name (lower case) → field; "fpt" is summed into positions
COLUMNS = {"fp": "pitch", "pitch": "pitch", "fpt": "fpt", "fha": "slope", "slope": "slope",
           "ffa": "form", "form": "form"}
UNITS = {"µm": 1.0, "um": 1.0, "μm": 1.0, "mm": 1e3}
TOOTH_SPEC = "GEAR:TOOTH=µm, comma-separated (e.g. 1:11=5,2:30=-3), GEAR 1 or 2"
RUNOUT_SPEC = "GEAR=µm@deg, comma-separated (e.g. 1=10@90), GEAR 1 or 2, 0 <= µm <= 1000"


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
    """``GEAR=µm@deg`` entries of ``--runout`` → {gear: Runout}."""
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
    rows, fields = _rows(Path(str(path)))
    z = {1: z1, 2: z2}
    got: dict[tuple[int, int], dict[str, float]] = {}
    for line, row in rows:
        gear, tooth = _whole(path, line, row, "gear"), _whole(path, line, row, "tooth")
        if gear not in z or not 0 <= tooth < z[gear]:
            raise ParameterError("deviations", str(path), f"line {line}: gear 1 (teeth 0 ... "
                                 f"{z1 - 1}) or 2 (teeth 0 ... {z2 - 1}), not gear {gear} "
                                 f"tooth {tooth}")
        got[(gear, tooth)] = {attr: scale * _cell(path, line, row, column)
                              for column, (attr, scale) in fields.items()}
    for gear in (1, 2):   # single pitch deviations: each tooth's position is their running sum
        mine = sorted(t for g, t in got if g == gear)
        if "fpt" in {a for a, _ in fields.values()} and mine:
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


def _rows(path: Path):
    """The file's data rows (line number, dict) and its deviation columns: name → (field,
    factor to µm)."""
    try:
        lines = path.read_text().splitlines()
    except (OSError, UnicodeDecodeError) as err:
        raise ParameterError("deviations", str(path), "a readable CSV file of measured "
                             f"deviations ({err.__class__.__name__})") from None
    numbered = [(k + 1, text) for k, text in enumerate(lines)
                if text.strip() and not text.lstrip().startswith("#")]
    if not numbered:
        raise ParameterError("deviations", str(path), "a header (gear, tooth and deviation "
                             "columns with their units) and a row per tooth")
    reader = csv.reader([text for _, text in numbered], skipinitialspace=True)
    header = [h.strip() for h in next(reader)]
    fields = {}
    for h in header:
        m = re.fullmatch(r"(.+?)\s*\[\s*(.+?)\s*\]", h)
        name = (m.group(1) if m else h).strip().lower()
        if name in ("gear", "tooth"):
            continue
        if name not in COLUMNS:
            raise ParameterError("deviations", str(path), f"columns gear, tooth and any of "
                                 f"{', '.join(sorted(set(COLUMNS)))}, not {h!r}")
        if not m or m.group(2) not in UNITS:
            raise ParameterError("deviations", str(path), f"the unit of column {h!r} in "
                                 "brackets: [µm], [um] or [mm]")
        fields[h] = (COLUMNS[name], UNITS[m.group(2)])
    if not {"gear", "tooth"} <= {h.lower() for h in header} or not fields:
        raise ParameterError("deviations", str(path), "a header with gear, tooth and at least "
                             "one deviation column")
    rows = []
    for (line, _), cells in zip(numbered[1:], reader):
        if len(cells) != len(header):
            raise ParameterError("deviations", str(path), f"line {line}: {len(header)} cells "
                                 f"as in the header, not {len(cells)}")
        rows.append((line, {h.lower() if h.lower() in ("gear", "tooth") else h: c.strip()
                            for h, c in zip(header, cells)}))
    return rows, fields


def _cell(path, line: int, row: dict, column: str) -> float:
    value = _number(row[column])
    if not math.isfinite(value):
        raise ParameterError("deviations", str(path), f"line {line}: a number in column "
                             f"{column!r}, not {row[column]!r}")
    return value


def _whole(path, line: int, row: dict, column: str) -> int:
    value = _number(row[column])
    if not math.isfinite(value) or value != int(value):
        raise ParameterError("deviations", str(path), f"line {line}: a whole number in "
                             f"column {column!r}, not {row[column]!r}")
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

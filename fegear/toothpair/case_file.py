"""A design as a file: ``fegear solve --case design.toml`` and ``--save-case FILE``.

A case file is a study's ``[base]`` on its own: every key a ``fegear solve`` input by its option
name, in the units of ``--help``::

    # the relieved baseline
    m = 2.0
    torque = 150.0              # N·m
    relief = 3.0                # µm
    positions = 24
    pitch-deviation = ["1:11=5"]
    deviations = "measured.csv" # found beside this file, as a study finds it

The ``summary.json`` of a solve loads as a case too: its ``case`` table (every input as run,
written since the case files came), or an older summary's ``inputs`` by their summary names
(the pair, the load's position, the material, the model and the deviations).

:func:`case_record` is every input as a solve ran it, the defaults written out (a derived one,
such as the tip clearance or the rims, at the value it took), and :func:`case_toml` writes it so
that the file, read back, gives the same solve.
"""

from __future__ import annotations

import json
import math
import os
import tomllib
from collections.abc import Mapping
from pathlib import Path

from ..errors import FegearError
from ..geometry import PER_TOOTH, Runout, ToothEntry, runout_text
from .inputs import JOB_INPUTS, REQUIRES

#: the solve's inputs that name a file: measured deviations, a load spectrum, a material (a
#: name of the table, or a .toml file)
FILE_INPUTS = ("deviations", "spectrum", "material", "lead")

#: an older summary's ``inputs`` (summary name → option name) where the name differs
SUMMARY_NAMES = {"torque_Nm": "torque", "position_deg": "position", "thickness_mm": "face-width",
                 "E_MPa": "E", "tip_round_mm": "tip-round", "rim1_mm": "rim1",
                 "rim2_mm": "rim2", "extra_pairs": "extra-pairs", "relief_um": "relief",
                 "relief_extent_mm": "relief-extent", "relief_start_mm": "relief-start",
                 "relief_shape": "relief-shape", "tip_clearance": "tip-clearance",
                 "allowable_bending_MPa": "allowable-bending",
                 "allowable_contact_MPa": "allowable-contact"}


class CaseFileError(FegearError):
    """A case file that cannot be read as written: the message names the file and the key."""


def is_file(name: str, value) -> bool:
    """Whether the input ``name`` = ``value`` names a file (:data:`FILE_INPUTS`)."""
    if not isinstance(value, str) or not value:
        return False
    return name != "material" or value.endswith(".toml")


def relative_to(path: str | os.PathLike, values: Mapping) -> dict:
    """``values`` with the files they name (:data:`FILE_INPUTS`) relative to the file ``path``
    (a study or a case) made absolute: it runs the same from any folder."""
    values = dict(values)
    for name in FILE_INPUTS:
        value = values.get(name)
        if is_file(name, value) and not Path(value).is_absolute():
            values[name] = str((Path(path).parent / value).resolve())
    return values


def read_case(path: str | os.PathLike) -> dict:
    """The inputs of the case file ``path`` by option name (TOML, or a summary.json), the
    files it names made absolute; raises :class:`CaseFileError` naming the file and key."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as exc:
        raise CaseFileError(f"--case {str(path)!r} cannot be read: {exc.strerror}") from None
    except UnicodeDecodeError:
        raise CaseFileError(f"--case {str(path)!r}: not a text file (UTF-8)") from None
    if path.suffix.lower() == ".json":
        values = _from_summary(text, path)
    else:
        try:
            values = tomllib.loads(text)
        except tomllib.TOMLDecodeError as exc:
            raise CaseFileError(f"{path}: not valid TOML ({exc}); a case file is `name = "
                                "value` lines, one fegear solve input each") from None
    for key, value in values.items():
        if isinstance(value, dict):
            raise CaseFileError(f"{path}: [{key}] is a table; a case file's keys are plain "
                                "`name = value` lines (a study's [base] without its header)")
        if key not in JOB_INPUTS:
            import difflib

            close = difflib.get_close_matches(key, list(JOB_INPUTS), n=1)
            hint = f" (did you mean {close[0]!r}?)" if close else ""
            raise CaseFileError(f"{path}: unknown key {key!r}{hint}; a case file's keys are "
                                "fegear solve's options (fegear solve --help)")
    return relative_to(path, {JOB_INPUTS.canonical(k): _plain(k, v) for k, v in
                              values.items()})


def _plain(name: str, value):
    """A TOML value as the command line gives it: a repeated text input's list stays a list of
    texts, an on/off flag's false is its default."""
    if JOB_INPUTS[name].repeat and isinstance(value, str):
        return [value]
    return value


def _from_summary(text: str, path: Path) -> dict:
    """A summary.json's inputs by option name: its ``case``, else its ``inputs`` renamed."""
    try:
        data = json.loads(text)
    except json.JSONDecodeError as exc:
        raise CaseFileError(f"{path}: not valid JSON ({exc.msg}, line {exc.lineno})") from None
    if not isinstance(data, dict) or not isinstance(data.get("case", data.get("inputs")),
                                                     dict):
        raise CaseFileError(f"{path}: a JSON case is the summary.json of a solve (its "
                            "'case' or 'inputs'); this one has neither")
    if "case" in data:
        return {k: v for k, v in data["case"].items() if v is not None}
    inputs = dict(data["inputs"])
    deviations = inputs.pop("deviations", None) or {}
    out = {SUMMARY_NAMES.get(k, k): v for k, v in inputs.items()
           if SUMMARY_NAMES.get(k, k) in JOB_INPUTS and v is not None}
    out.update(_deviation_texts(deviations, path))
    return out


def _deviation_texts(summary: Mapping, path: Path) -> dict:
    """A summary's ``deviations`` record as the options that give it again."""
    out: dict[str, object] = {}
    for gear in (1, 2):
        for tooth, d in summary.get(f"gear{gear}", {}).items():
            if d.get("form_curve_um"):
                raise CaseFileError(f"{path}: gear {gear} tooth {tooth} has a measured form "
                                    "curve, which only its deviations file holds: give that "
                                    "file with --deviations")
            for name, field in PER_TOOTH.items():
                if d.get(f"{field}_um"):
                    out.setdefault(name, []).append(
                        ToothEntry(name, gear, int(tooth), d[f"{field}_um"]).text)
    if summary.get("centre_distance_um"):
        out["centre-distance-deviation"] = summary["centre_distance_um"]
    runouts = [runout_text(g, Runout(r["fr_um"], r["phase_deg"])) for g in (1, 2)
               if (r := summary.get(f"runout{g}") or {}).get("fr_um")]
    if runouts:
        out["runout"] = runouts
    return out


def case_record(values: Mapping[str, object], resolved: Mapping[str, object]) -> dict:
    """Every input of a solve by option name as it ran: ``values`` (the inputs given) over
    the defaults, with the derived defaults (None in the schema) at ``resolved``'s values;
    an input that stays None is off (no class, one position), and so is one that only an
    input that is off reads (:data:`~.inputs.REQUIRES`: the samples without a class)."""
    record = JOB_INPUTS.with_defaults(values)
    for name, value in resolved.items():
        if record.get(name) is None:
            record[name] = value
    for name, switch in REQUIRES.items():
        if record[switch] is None:
            record[name] = None
    return record


def case_toml(record: Mapping[str, object], where: str | os.PathLike | None = None,
              title: str = "") -> str:
    """``record`` (:func:`case_record`) as a case file's text: a line an input, its unit and
    an input that is off as comments; the files it names relative to the folder ``where``
    where they sit below it. Read back (:func:`read_case`), it gives the same inputs."""
    lines = [f"# {line}" for line in title.splitlines()] + [""] if title else []
    for name, row in JOB_INPUTS.items():
        value = record.get(name)
        if value is None:
            switch = REQUIRES.get(name)
            lines.append(f"# {name} = {_toml(row.default)}  (read with {switch} only)"
                         if switch and record.get(switch) is None else
                         f"# {name}: {row.default_text or 'none'}")
            continue
        if where is not None and is_file(name, value):
            value = _below(Path(value), Path(where))
        unit = f"  # {row.unit}" if row.unit else ""
        lines.append(f"{name} = {_toml(value)}{unit}")
    return "\n".join(lines) + "\n"


def _below(file: Path, folder: Path) -> str:
    """``file`` relative to ``folder`` where it sits below it, else as it is."""
    try:
        return str(file.resolve().relative_to(folder.resolve()))
    except ValueError:
        return str(file)


def _toml(value) -> str:
    """One TOML value: a bool, number, text (JSON's escapes are TOML's) or list of texts."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if not math.isfinite(value):
            raise ValueError(f"{value!r} has no TOML form a case file takes")
        return repr(value)
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_toml(v) for v in value) + "]"
    return json.dumps(str(value))

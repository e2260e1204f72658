"""Study files: a base case plus sweeps over any ``fegear solve`` input, read from TOML.

A study file is data, never code::

    [study]                       # optional
    name = "paper_trends"         # default: the file name without .toml
    description = "…"

    [outputs]                     # optional: files kept per case (default: none, only numbers)
    vtu = false                   # gear1.vtu, gear2.vtu
    png = false                   # von_mises.png (and cycle.png with `positions`)

    [base]                        # any `fegear solve` input by its option name; the others
    torque = 50                   # keep `fegear solve`'s defaults
    quality = "fast"

    [[sweep]]                     # every [[sweep]] block adds its cases to the study
    m = [1.0, 1.5, 2.0, 2.5]      # a list …
    h1 = {start = 0.2, stop = 0.4, step = 0.05}   # … or a range: step or num, stop included
    combine = "product"           # "product" (default): every combination; "zip": in step

A scalar in a block sets that input for the block's cases only. A case that two blocks both
produce is run once. Every case is checked as ``fegear solve`` would check it before anything
runs. A case it refuses (a value outside its range, a design that cannot be built) is kept
aside with its reason (:class:`RefusedCase`) and the others run; a study none of whose cases
can run is an error. An error in the file itself names the file, the block, the key and the
reason.
"""

from __future__ import annotations

import difflib
import hashlib
import itertools
import json
import math
import tomllib
from dataclasses import dataclass
from pathlib import Path

from ..checks import Input
from ..errors import FegearError
from ..provenance import code_version
from ..toothpair import FILE_INPUTS, JOB_INPUTS, RENAMED, is_file, prepare_job, relative_to

MAX_CASES = 100_000
_SECTIONS = ("study", "outputs", "base", "sweep")
_STUDY_KEYS = ("name", "description")
_OUTPUT_KEYS = ("vtu", "png", "report")
_BLOCK_KEYS = ("combine",)


class StudyError(FegearError):
    """A study file that cannot be run as written: the message names the file and the key."""


@dataclass(frozen=True)
class Outputs:
    """Files kept per case besides the numbers: the VTU fields, the pictures, the one-page
    report (and the study's index page of them)."""

    vtu: bool = False
    png: bool = False
    report: bool = False


@dataclass(frozen=True)
class StudyCase:
    """One solve of a study: its position in the study, its key (hash of the inputs, the kept
    outputs and the code version; :func:`case_key`), every ``fegear solve`` input by name, and
    the values its sweep block set (what tells it apart in tables and plots). Cases that
    differ in the allowable stresses alone share a key: one solve, a row each."""

    index: int
    key: str
    values: dict
    swept: dict


@dataclass(frozen=True)
class RefusedCase:
    """A case of the file that ``fegear solve`` refuses: its number in the study, its inputs,
    the values its sweep block set, where it comes from (``[[sweep]] 2``, ``[base]``) and
    the refusal (the input, its value and the admissible range)."""

    index: int
    values: dict
    swept: dict
    block: str
    reason: str

    @property
    def where(self) -> str:
        """The block and the values it set: ``[[sweep]] 1 (h1 = 0.95)``."""
        return f"{self.block} ({_describe(self.swept) or 'base'})"

    def describe(self, path: Path) -> str:
        """One line: the file, the block, the case's values and the reason."""
        return f"{path}: {self.where}: {self.reason}"


@dataclass(frozen=True)
class Study:
    """A checked study: name, source file, kept outputs, the base inputs, the cases that run
    and those refused (:class:`RefusedCase`), each numbered in the order of the file, and the
    inputs that differ between all of them (the plots' axes)."""

    name: str
    path: Path
    description: str
    outputs: Outputs
    base: dict
    cases: tuple[StudyCase, ...]
    varied: tuple[str, ...]
    refused: tuple[RefusedCase, ...] = ()


def load_study(path: str | Path) -> Study:
    """Read, check and expand a study file; raise :class:`StudyError` naming file and key."""
    path = Path(path)
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except OSError as exc:
        raise StudyError(f"{path}: cannot be read: {exc.strerror}") from None
    except tomllib.TOMLDecodeError as exc:
        raise StudyError(f"{path}: not valid TOML: {exc}") from None
    except UnicodeDecodeError:
        raise StudyError(f"{path}: not a text file (UTF-8)") from None
    return build_study(data, path)


def build_study(data: dict, path: Path) -> Study:
    """The study of an already parsed TOML document (``path`` names it in errors)."""
    where = str(path)
    _known(data, _SECTIONS, where, "section")
    head = _table(data, "study", where)
    _known(head, _STUDY_KEYS, f"{where}: [study]", "key")
    name = _string(head.get("name", path.stem), f"{where}: [study] name")
    if not name or not all(ch.isalnum() or ch in "-_." for ch in name):
        raise StudyError(f"{where}: [study] name = {name!r}: use letters, digits, - _ . only")
    description = _string(head.get("description", ""), f"{where}: [study] description")
    out = _table(data, "outputs", where)
    _known(out, _OUTPUT_KEYS, f"{where}: [outputs]", "key")
    outputs = Outputs(**{k: _bool(out[k], f"{where}: [outputs] {k}") for k in out})
    inputs = JOB_INPUTS
    base = {k: _value(v, inputs[k].kind.__name__, f"{where}: [base] {k}", inputs[k])
            for k, v in _known(_table(data, "base", where), inputs, f"{where}: [base]",
                               "fegear solve input").items()}
    blocks = data.get("sweep", [])
    if not isinstance(blocks, list) or not all(isinstance(b, dict) for b in blocks):
        raise StudyError(f"{where}: sweep must be an array of tables, written [[sweep]]")
    combos = []
    for i, block in enumerate(blocks, start=1):
        combos.extend(_expand(block, inputs, f"{where}: [[sweep]] {i}", f"[[sweep]] {i}"))
        if len(combos) > MAX_CASES:
            raise StudyError(f"{where}: more than {MAX_CASES} cases")
    if not combos:
        combos = [("[base]", {})]
    code = code_version()
    cases, refused, seen = [], [], set()
    for block, swept in combos:
        values = relative_to(path, {**base, **swept})
        key = case_key(values, outputs, code)
        # cases that differ in an allowable stress alone share a key (one solve) but not a row
        same = (key, json.dumps(JOB_INPUTS.with_defaults(values), sort_keys=True))
        if same in seen:
            continue
        seen.add(same)
        index = len(cases) + len(refused)
        reason = _refusal(values)
        if reason is None:
            cases.append(StudyCase(index, key, values, swept))
        else:
            refused.append(RefusedCase(index, values, swept, block, reason))
    if not cases:
        first = refused[0]
        raise StudyError(first.describe(path) if len(refused) == 1 else
                         f"{where}: all {len(refused)} cases are refused; the first, "
                         f"{first.where}: {first.reason}")
    full = [JOB_INPUTS.with_defaults(c.values) for c in (*cases, *refused)]
    varied = tuple(n for n in inputs if len({json.dumps(f[n]) for f in full}) > 1)
    return Study(name, path, description, outputs, base, tuple(cases), varied, tuple(refused))


#: inputs renamed since studies were first stored, hashed under their earlier names so that
#: those studies' records stay valid
KEY_NAMES = {"face-width": "thickness"}


def case_key(values: dict, outputs: Outputs, code: str) -> str:
    """Hash (first 16 hex digits of SHA-256) of every input that decides the solve's numbers
    (not the allowable stresses: the tables compute the safety factors from the stored
    stresses), the kept outputs and the code version: equal keys are equal results."""
    full = {KEY_NAMES.get(k, k): v for k, v in JOB_INPUTS.keyed(values).items()}
    for name in FILE_INPUTS:   # a file decides by what it holds, not by its name
        if is_file(name, full.get(name)):
            full[name] = _digest(Path(str(full[name])))
    kept = [outputs.vtu, outputs.png] + [True] * outputs.report   # older keys stay valid
    text = json.dumps({"inputs": full, "outputs": kept, "code": code}, sort_keys=True)
    return hashlib.sha256(text.encode()).hexdigest()[:16]


def _digest(file: Path) -> str:
    """The SHA-256 of ``file``'s bytes; its name where it cannot be read (the solve refuses
    it by name)."""
    try:
        return hashlib.sha256(file.read_bytes()).hexdigest()
    except OSError:
        return str(file)


def _expand(block: dict, inputs, where: str, label: str) -> list[tuple[str, dict]]:
    """The cases of one [[sweep]] block: (``label``, the values it sets)."""
    combine = _string(block.get("combine", "product"), f"{where} combine")
    if combine not in ("product", "zip"):
        raise StudyError(f"{where} combine = {combine!r}: admissible: \"product\" or \"zip\"")
    swept = {}
    for k, v in _known({k: v for k, v in block.items() if k not in _BLOCK_KEYS}, inputs,
                       where, "fegear solve input").items():
        kind = inputs[k].kind.__name__
        if isinstance(v, dict):
            values = _range(v, kind, f"{where} {k}")
        elif isinstance(v, list):
            if not v:
                raise StudyError(f"{where} {k} = []: give at least one value")
            values = [_value(x, kind, f"{where} {k}[{j}]", inputs[k]) for j, x in enumerate(v)]
        else:
            values = [_value(v, kind, f"{where} {k}", inputs[k])]
        swept[k] = values
    if not swept:
        raise StudyError(f"{where}: sweeps nothing (give at least one input)")
    names = list(swept)
    if combine == "zip":
        lengths = {k: len(v) for k, v in swept.items() if len(v) > 1}
        if len(set(lengths.values())) > 1:
            raise StudyError(f"{where}: combine = \"zip\" needs equally long lists; got "
                             + ", ".join(f"{k} {n}" for k, n in lengths.items()))
        n = max(len(v) for v in swept.values())
        rows = [[v[j] if len(v) > 1 else v[0] for v in swept.values()] for j in range(n)]
    else:
        rows = itertools.product(*swept.values())
    return [(label, dict(zip(names, row))) for row in rows]


def _range(spec: dict, kind: str, where: str) -> list:
    """``{start, stop, step}`` or ``{start, stop, num}``, stop included."""
    if kind not in ("float", "int"):
        raise StudyError(f"{where}: a range needs a numeric input; give a list")
    keys = set(spec)
    if keys not in ({"start", "stop", "step"}, {"start", "stop", "num"}):
        raise StudyError(f"{where} = {spec}: a range is {{start, stop, step}} or "
                         "{start, stop, num}")
    start = _value(spec["start"], kind, f"{where}.start")
    stop = _value(spec["stop"], kind, f"{where}.stop")
    if "num" in spec:
        num = _value(spec["num"], "int", f"{where}.num")
        if not 1 <= num <= MAX_CASES:
            raise StudyError(f"{where}.num = {num}: admissible 1 <= num <= {MAX_CASES}")
        if num == 1:
            return [start]
        step = (stop - start) / (num - 1)
    else:
        step = _value(spec["step"], kind, f"{where}.step")
        if step == 0 or (stop - start) / step < 0:
            raise StudyError(f"{where}.step = {step}: must be non-zero and lead from start "
                             "to stop")
        num = math.floor((stop - start) / step * (1 + 1e-9) + 1e-9) + 1
        if num > MAX_CASES:
            raise StudyError(f"{where}: {num} values, more than {MAX_CASES}")
    values = [start + j * step for j in range(num)]
    if kind == "int":
        if any(v != int(v) for v in values):
            raise StudyError(f"{where}: an integer input needs integer steps")
        return [int(v) for v in values]
    return [round(v, 12) for v in values]  # 0.2 + 2 × 0.05 is 0.30000000000000004


def _value(v, kind: str, where: str, row: Input | None = None):
    """``v`` as an input of ``kind`` takes it (a bool is no number); a refusal states the
    input's range where ``row`` is given."""
    if kind == "bool":
        return _bool(v, where)
    if kind == "str":
        return _string(v, where)
    span = f"; admissible: {row.range_text}" if row is not None and row.range_text else ""
    if isinstance(v, bool) or not isinstance(v, (int, float)):
        what = "an integer" if kind == "int" else "a number"
        raise StudyError(f"{where} = {v!r}: must be {what}{span}")
    if kind == "int":
        if isinstance(v, float):
            raise StudyError(f"{where} = {v!r}: must be an integer{span}")
        return v
    if not math.isfinite(v):
        raise StudyError(f"{where} = {v!r}: must be a finite number{span}")
    return float(v)


def _bool(v, where: str) -> bool:
    if not isinstance(v, bool):
        raise StudyError(f"{where} = {v!r}: must be true or false")
    return v


def _string(v, where: str) -> str:
    if not isinstance(v, str):
        raise StudyError(f"{where} = {v!r}: must be a string")
    return v


def _table(data: dict, name: str, where: str) -> dict:
    t = data.get(name, {})
    if not isinstance(t, dict):
        raise StudyError(f"{where}: {name} must be a table, written [{name}]")
    return t


def _known(table: dict, known, where: str, what: str) -> dict:
    for k in table:
        if k not in known:
            close = difflib.get_close_matches(k, list(known), n=1)
            hint = f" (did you mean {close[0]!r}?)" if close else ""
            if k in RENAMED:
                hint = f" (renamed: now {RENAMED[k]})"
            raise StudyError(f"{where}: unknown {what} {k!r}{hint}; known: "
                             + ", ".join(known))
    return table


def _describe(values: dict) -> str:
    return ", ".join(f"{k} = {v!r}" for k, v in values.items())


def _refusal(values: dict) -> str | None:
    """Why ``fegear solve`` refuses a case (parameters, geometry; no meshing), or None."""
    try:
        prepare_job(values)
    except FegearError as exc:
        return str(exc)
    return None

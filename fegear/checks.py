"""Checks of input values: finite numbers, ranges, integers.

Every check raises :class:`~fegear.errors.ParameterError`, whose message names the parameter,
the offending value and the admissible range, so that a user sees one line saying what to change.
"""

from __future__ import annotations

import difflib
import math
import numbers
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass

from .errors import ParameterError


def number(value: object) -> float | None:
    """``value`` as a float if it is a real number, else None: a bool is no number (True
    would be 1), nor is text ("2" is the command line's to read), nor a complex."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        return None      # numpy's bool_ is no numbers.Real either; its floats and ints are
    return float(value)


def require_finite(name: str, value: object, admissible: str = "a finite number") -> float:
    """Return ``value`` as float or raise :class:`ParameterError` (stating ``admissible``) if
    it is not a finite number (:func:`number`)."""
    x = number(value)
    if x is None or not math.isfinite(x):
        raise ParameterError(name, value, admissible)
    return x


def require_range(name: str, value: object, lo: float | None, hi: float | None,
                  lo_open: bool = False, hi_open: bool = False, unit: str = "",
                  reason: str = "") -> float:
    """Check ``lo (<|<=) value (<|<=) hi``; raise a :class:`ParameterError` naming the range
    (and ``reason``, what bounds it), whatever is wrong with the value (no number, not
    finite, outside)."""
    admissible = (describe_range(name, lo, hi, lo_open, hi_open, unit)
                  if lo is not None or hi is not None else "a finite number")
    x = number(value)
    ok = x is not None and math.isfinite(x)
    ok = ok and (lo is None or (x > lo if lo_open else x >= lo))
    if not (ok and (hi is None or (x < hi if hi_open else x <= hi))):
        raise ParameterError(name, value, admissible, reason)
    return x


def describe_range(name: str, lo: float | None, hi: float | None,
                   lo_open: bool = False, hi_open: bool = False, unit: str = "") -> str:
    """Human-readable interval such as ``0 < h1 <= 0.412``."""
    u = f" {unit}" if unit else ""
    name = name.replace("_", "-")
    left = "" if lo is None else f"{_figure(lo)} {'<' if lo_open else '<='} "
    right = "" if hi is None else f" {'<' if hi_open else '<='} {_figure(hi)}{u}"
    return f"{left}{name}{right}"


def _figure(x: float) -> str:
    """A bound as a range states it: an integer in full, else to six figures."""
    return str(x) if isinstance(x, int) else f"{x:.6g}"


def require_int(name: str, value: object, lo: int, hi: int | None = None) -> int:
    """Return ``value`` as int (an integral float is accepted, a bool is not) or raise a
    :class:`ParameterError` naming the range ``lo <= value (<= hi)``."""
    admissible = f"an integer {describe_range(name, lo, hi)}"
    x = number(value)
    if x is None or not math.isfinite(x) or x != int(x) or not lo <= x <= (
            math.inf if hi is None else hi):
        raise ParameterError(name, value, admissible)
    return int(x)


@dataclass(frozen=True)
class Input:
    """One user input of a command: a row of its schema.

    ``name`` as on the command line without ``--`` (``dest`` is the Python name), ``kind``
    (``float``, ``int``, ``str``, or ``bool`` for an on/off flag), ``default``, ``unit``,
    ``help``, and the admissible range: ``low``/``high`` (open or closed) for numbers,
    ``choices`` for strings. Where the range depends on other inputs (a shift against the
    tooth height, say), ``limits`` says it in words (``0 <= shift <= m h1/4 …``) and the
    object the inputs build checks it, stating it at those inputs' values; ``low``/``high``
    then give its static part. Where the default is derived from other inputs, or means
    "none" (``default`` None), ``rule`` says how (``0.008 m, at most m h1/4``). ``post``: the
    input only reads the results (an allowable stress): it changes no number of the solve, so
    a cache key leaves it out (:meth:`InputTable.keyed`). ``aliases``: other names the command
    line and study files take for it (an earlier name, say). ``repeat``: a text input the
    command line takes more than once, as a list of its texts (a list of entries).
    ``metavar``: what ``--help`` shows for the value (default: the unit, else N for an
    integer, X for a number, TEXT).
    """

    name: str
    kind: type
    default: object
    help: str
    unit: str = ""
    low: float | None = None
    high: float | None = None
    low_open: bool = False
    high_open: bool = False
    choices: tuple[str, ...] = ()
    post: bool = False
    aliases: tuple[str, ...] = ()
    limits: str = ""
    rule: str = ""
    repeat: bool = False
    metavar: str = ""

    def __post_init__(self) -> None:
        if self.kind not in (float, int, str, bool):
            raise TypeError(f"input {self.name!r}: kind must be float, int, str or bool")
        if self.kind is int and self.low is None:
            raise TypeError(f"input {self.name!r}: an integer input needs its lowest value")

    @property
    def dest(self) -> str:
        """The Python name: ``tip-clearance`` → ``tip_clearance``."""
        return self.name.replace("-", "_")

    @property
    def range_text(self) -> str:
        """The admissible range as a refusal and ``--help`` state it, e.g. ``0 < m <= 100
        mm``, ``an integer 2 <= positions <= 360``, ``coarse / fast`` or the ``limits`` in
        words ('' for an on/off flag, or a text input that takes any text)."""
        if self.choices:
            return " / ".join(self.choices)
        if self.limits:
            return self.limits
        if self.kind is int:
            return f"an integer {describe_range(self.name, self.low, self.high)}"
        if self.low is None and self.high is None:
            return "a finite number" if self.kind is float else ""
        return describe_range(self.name, self.low, self.high, self.low_open, self.high_open,
                              self.unit)

    @property
    def default_text(self) -> str:
        """The default as ``--help`` states it: the value, or its rule where derived."""
        if self.default is None:
            return self.rule
        if self.kind is bool:
            return "on" if self.default else "off"
        return f"{self.default:g}" if self.kind in (float, int) else str(self.default)

    def check(self, value: object, name: str | None = None) -> object:
        """``value`` checked against the static range (``None`` passes where the default is
        None); raises :class:`ParameterError` naming ``name`` (default: ``dest``) and
        :attr:`range_text`, whatever is wrong with the value (a bool or text for a number,
        NaN, outside)."""
        name = name or self.dest
        if value is None and self.default is None:
            return None
        if self.kind is bool:
            if not isinstance(value, bool):
                raise ParameterError(name, value, "true or false")
            return value
        if self.kind is str:
            if not isinstance(value, str) or self.choices and value not in self.choices:
                raise ParameterError(name, value, self.range_text or "text")
            return value
        try:
            if self.kind is int:
                return require_int(name, value, int(self.low), None if self.high is None
                                   else int(self.high))
            return require_range(name, value, self.low, self.high, self.low_open,
                                 self.high_open, self.unit)
        except ParameterError:
            raise ParameterError(name, value, self.range_text) from None


class InputTable(Mapping[str, Input]):
    """An ordered, read-only schema of inputs by name, from which a command line, a study
    file's keys and a cache key are all built."""

    def __init__(self, *groups: Iterable[Input]) -> None:
        rows = [row for group in groups for row in group]
        self._rows = {row.name: row for row in rows}
        self._alias = {a: row.name for row in rows for a in row.aliases}
        if len(self._rows) != len(rows) or set(self._alias) & set(self._rows):
            raise ValueError("two inputs share a name")

    def __getitem__(self, name: str) -> Input:
        return self._rows[self._alias.get(name, name)]

    def canonical(self, name: str) -> str:
        """The input's own name for ``name`` (an alias → the name it stands for)."""
        return self._alias.get(name, name)

    def __iter__(self) -> Iterator[str]:
        return iter(self._rows)

    def __len__(self) -> int:
        return len(self._rows)

    def defaults(self) -> dict[str, object]:
        """Every input's default, by name."""
        return {name: row.default for name, row in self._rows.items()}

    def with_defaults(self, values: Mapping[str, object]) -> dict[str, object]:
        """``values`` by name with every missing input at its default; an unknown name is a
        :class:`ParameterError` that lists the known ones."""
        unknown = [k for k in values if k not in self]
        if unknown:
            close = difflib.get_close_matches(unknown[0], [*self._rows, *self._alias], n=1)
            hint = f"did you mean {close[0]}? " if close else ""
            raise ParameterError(unknown[0], values[unknown[0]], f"{hint}one of "
                                 + ", ".join(self._rows), "unknown input")
        return {**self.defaults(), **{self.canonical(k): v for k, v in values.items()}}

    def keyed(self, values: Mapping[str, object]) -> dict[str, object]:
        """The inputs that decide a solve's numbers, by name, missing ones at their defaults:
        :meth:`with_defaults` without the post-processing inputs (``post``), for a cache key."""
        return {k: v for k, v in self.with_defaults(values).items() if not self._rows[k].post}

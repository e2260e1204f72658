"""Command-line options built from the input schemas (:class:`~fegear.checks.Input`), and the
parser that prints one line for a usage error."""

from __future__ import annotations

import argparse
import difflib
from collections.abc import Iterable

from ..checks import Input

EXIT_USAGE = 2


class _NotTyped(list):
    """The mark of an option not typed (:meth:`Parser.parse_known_args`): a list, since an
    ``append`` option copies what the namespace holds before it appends."""


_NOT_TYPED = _NotTyped()


class Parser(argparse.ArgumentParser):
    """An argument parser whose usage errors are one line (no usage dump), exit code 2; an
    unknown option gets the nearest one of the command it was given to ("did you mean …?")."""

    def __init__(self, *args, **kwargs) -> None:
        super().__init__(*args, **kwargs)
        self.inputs: list[Input] = []   # the schema rows of its options (add_inputs)

    def parse_known_args(self, args=None, namespace=None):
        # argparse leaves a command's unknown words to the top parser, which cannot tell
        # whose they were: each parser refuses its own, hinting from its own options
        # (`fegear solve --module-mm 2` is not told about `drive reducer`'s --module-mm)
        namespace = argparse.Namespace() if namespace is None else namespace
        # argparse sets a default only where the namespace has no value yet: a mark there
        # that is still in place after parsing is an option not typed (typed at its default
        # value is still typed: it wins over a --case file's value)
        marked = {a.dest: a.default for a in self._actions if a.option_strings
                  and a.default is not argparse.SUPPRESS and not hasattr(namespace, a.dest)}
        for dest in marked:
            setattr(namespace, dest, _NOT_TYPED)
        namespace, extras = super().parse_known_args(args, namespace)
        if extras:
            self.error(f"unrecognized arguments: {' '.join(extras)}")
        typed = set(getattr(namespace, "typed", ()))
        for dest, default in marked.items():
            value = getattr(namespace, dest)
            if value is _NOT_TYPED:
                setattr(namespace, dest, default)
                continue
            typed.add(dest)
            if isinstance(value, _NotTyped):   # the mark's copy an append option filled
                setattr(namespace, dest, list(value))
        namespace.typed = typed
        return namespace, extras

    def error(self, message: str) -> None:
        if message.startswith("unrecognized arguments:"):
            words = message.split(":", 1)[1].split()
            unknown = next((w.split("=")[0] for w in words if w.startswith("--")), None)
            close = self._nearest(unknown) if unknown else None
            if close:
                message += f" (did you mean {close}?)"
        self.exit(EXIT_USAGE, f"fegear: error: {message}\n")

    def _nearest(self, unknown: str) -> str | None:
        """This parser's option nearest ``unknown`` by its name or by the first word of its
        help (``--modul`` → ``--m``, "module"), or None."""
        words = {}
        # argparse's table of this parser's option strings, its groups' included
        for option, action in self._option_string_actions.items():
            if option.startswith("--"):
                first = (action.help or "").split(" ", 1)[0].strip(",:;").lower()
                words.setdefault(first, option)
                words[option[2:].lower()] = option
        words.pop("", None)
        close = difflib.get_close_matches(unknown[2:].lower(), words, n=1, cutoff=0.7)
        return words[close[0]] if close else None


def add_inputs(parser: argparse.ArgumentParser, rows: Iterable[Input],
               title: str | None = None, into=None) -> None:
    """One ``--name`` option per schema row: its type, default, and a help text with the
    unit, the admissible range (:attr:`~fegear.checks.Input.range_text`) and the default or
    its rule; in a new group ``title``, or in the group ``into`` of ``parser``."""
    group = into or (parser.add_argument_group(title) if title else parser)
    rows = list(rows)
    if isinstance(parser, Parser):
        parser.inputs += rows
    for row in rows:
        names = [f"--{row.name}", *(f"--{a}" for a in row.aliases)]
        if row.kind is bool:
            group.add_argument(*names, action="store_true", help=row.help, dest=row.dest)
            continue
        text = row.help + (f" [{row.unit}]" if row.unit else "")
        text += f"; admissible: {row.range_text}" if row.range_text else ""
        text += f"; default: {row.default_text}"
        metavar = row.metavar or row.unit or {int: "N", float: "X"}.get(row.kind, "TEXT")
        group.add_argument(*names, type=_Read(row.kind), default=row.default, dest=row.dest,
                           help=text.replace("%", "%%"), metavar=metavar,
                           **({"action": "append"} if row.repeat else {}))


class _Read:
    """argparse's ``type`` of an input: the text as a number where it reads as one, else as
    typed, for the input's check to refuse with its range (argparse's own refusal, "invalid
    float value: 'abc'", says neither the range nor the default). Text inputs stay text."""

    def __init__(self, kind: type) -> None:
        self.kind = kind
        self.__name__ = kind.__name__    # argparse names the type in its messages

    def __call__(self, text: str) -> object:
        if self.kind is str:
            return text
        for read in (int, float) if self.kind is int else (float,):
            try:
                return read(text)
            except ValueError:
                pass
        return text


def checked(a: argparse.Namespace, rows: Iterable[Input]) -> dict[str, object]:
    """The parsed values of the schema rows' options, each checked against its range
    (:meth:`~fegear.checks.Input.check`: a refusal states it), by Python name."""
    return {row.dest: row.check(getattr(a, row.dest), row.name) for row in rows}


def typed_values(a: argparse.Namespace, rows: Iterable[Input]) -> dict[str, object]:
    """The parsed values of the schema rows' options typed on the command line (at their
    default value too), by input name: those that win over a ``--case`` file's."""
    typed = getattr(a, "typed", set())
    return {row.name: getattr(a, row.dest) for row in rows if row.dest in typed}


def given_values(a: argparse.Namespace, rows: Iterable[Input]) -> dict[str, object]:
    """The parsed values of the schema rows' options that differ from their defaults, by
    input name: the inputs the user changed, which a refused design may be blamed on (the
    others take their defaults from the schema)."""
    return {row.name: getattr(a, row.dest) for row in rows
            if getattr(a, row.dest) != row.default}


def workers_input(text: str, rule: str) -> Input:
    """The ``--workers`` row of a command that solves in a local pool: 1 to four times this
    machine's cores, ``text`` its help and ``rule`` its default."""
    import os

    return Input("workers", int, None, text, low=1, high=4 * (os.cpu_count() or 1), rule=rule)

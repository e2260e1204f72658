"""Command-line options built from the input schemas (:class:`~fegear.checks.Input`), and the
parser that prints one line for a usage error."""

from __future__ import annotations

import argparse
import difflib
from collections.abc import Iterable

from ..checks import Input

EXIT_USAGE = 2


class Parser(argparse.ArgumentParser):
    """An argument parser whose usage errors are one line (no usage dump), exit code 2; an
    unknown option gets the nearest one of the command it was given to ("did you mean …?")."""

    def parse_known_args(self, args=None, namespace=None):
        # argparse leaves a command's unknown words to the top parser, which cannot tell
        # whose they were: each parser refuses its own, hinting from its own options
        # (`fegear solve --module-mm 2` is not told about `drive reducer`'s --module-mm)
        namespace, extras = super().parse_known_args(args, namespace)
        if extras:
            self.error(f"unrecognized arguments: {' '.join(extras)}")
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
               title: str | None = None) -> None:
    """One ``--name`` option per schema row: its type, default, and a help text with the
    unit, the static range or choices, and the default."""
    group = parser.add_argument_group(title) if title else parser
    for row in rows:
        text = row.help + (f" [{row.unit}]" if row.unit else "")
        names = [f"--{row.name}", *(f"--{a}" for a in row.aliases)]
        if row.kind is bool:
            group.add_argument(*names, action="store_true", help=text, dest=row.dest)
            continue
        if row.choices:
            text += ": " + " / ".join(row.choices)
        if row.default is not None:
            default = f"{row.default:g}" if row.kind in (float, int) else row.default
            text += f" (default {default})"
        group.add_argument(*names, type=row.kind, default=row.default, dest=row.dest,
                           help=text.replace("%", "%%"))


def input_values(a: argparse.Namespace, rows: Iterable[Input]) -> dict[str, object]:
    """The parsed values of the schema rows' options, by input name."""
    return {row.name: getattr(a, row.dest) for row in rows}


def given_values(a: argparse.Namespace, rows: Iterable[Input]) -> dict[str, object]:
    """The parsed values of the schema rows' options that differ from their defaults, by
    input name: the inputs the user changed, which a refused design may be blamed on (the
    others take their defaults from the schema)."""
    return {row.name: getattr(a, row.dest) for row in rows
            if getattr(a, row.dest) != row.default}

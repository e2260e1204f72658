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
    unknown option gets the nearest known one ("did you mean …?")."""

    def error(self, message: str) -> None:
        if message.startswith("unrecognized arguments:"):
            words = message.split(":", 1)[1].split()
            unknown = next((w.split("=")[0] for w in words if w.startswith("--")), None)
            close = difflib.get_close_matches(unknown, sorted(_option_strings(self)), n=1,
                                              cutoff=0.6) if unknown else []
            if close:
                message += f" (did you mean {close[0]}?)"
        self.exit(EXIT_USAGE, f"fegear: error: {message}\n")


def _option_strings(parser: argparse.ArgumentParser) -> set[str]:
    """Every ``--option`` of ``parser`` and of its subcommands."""
    found = set()
    for action in parser._actions:
        found.update(s for s in action.option_strings if s.startswith("--"))
        if isinstance(action, argparse._SubParsersAction):
            for sub in action.choices.values():
                found |= _option_strings(sub)
    return found


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

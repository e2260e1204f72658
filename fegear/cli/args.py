"""Command-line options built from the input schemas (:class:`~fegear.checks.Input`), and the
parser that prints one line for a usage error."""

from __future__ import annotations

import argparse
from collections.abc import Iterable

from ..checks import Input

EXIT_USAGE = 2


class Parser(argparse.ArgumentParser):
    """An argument parser whose usage errors are one line (no usage dump), exit code 2."""

    def error(self, message: str) -> None:
        self.exit(EXIT_USAGE, f"fegear: error: {message}\n")


def add_inputs(parser: argparse.ArgumentParser, rows: Iterable[Input],
               title: str | None = None) -> None:
    """One ``--name`` option per schema row: its type, default, and a help text with the
    unit, the static range or choices, and the default."""
    group = parser.add_argument_group(title) if title else parser
    for row in rows:
        text = row.help + (f" [{row.unit}]" if row.unit else "")
        if row.kind is bool:
            group.add_argument(f"--{row.name}", action="store_true", help=text)
            continue
        if row.choices:
            text += ": " + " / ".join(row.choices)
        if row.default is not None:
            default = f"{row.default:g}" if row.kind in (float, int) else row.default
            text += f" (default {default})"
        group.add_argument(f"--{row.name}", type=row.kind, default=row.default,
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

"""Command line: ``fegear profile``, ``hertz``, ``solve``, ``relief``, ``crowning``, ``study``,
``optimize``, ``drive``, ``bench`` and ``cache``.

One module per command, each with ``add_parser`` (its options) and ``run`` (the command). User
errors (bad parameters, unwritable output) print one line ``fegear: error: …`` on stderr and exit
with code 2, without a traceback. Options are built from the input schemas, and heavy libraries
are imported by the commands that use them, so ``fegear --help`` answers at once.

>>> from fegear.cli import main
>>> main(["drive", "ratio", "--train", "internal", "--teeth", "44,45"])
internal-teeth: 2 fixed, H → 1
ratio ω_H/ω_1 = -44  (output turns against the input)
transformed (carrier-fixed) ratio i^H = 1.02273
0
>>> main(["solve", "--h1", "0.9", "--out", "never-made"])  # one line on stderr, exit code 2
2
"""

from __future__ import annotations

import argparse
import logging
import os
import signal
import sys

from .. import __version__, progress
from ..errors import FegearError, ParameterError
from . import bench, cache, crowning, drive, hertz, optimize, profile, relief, solve, study
from .args import EXIT_USAGE, Parser
from .terminal import StageBar, Stopped, stop_on_signals

#: exit code when the reader of stdout has gone away, as a shell reports SIGPIPE
EXIT_BROKEN_PIPE = 128 + signal.SIGPIPE

#: the commands in the order of ``fegear --help``
COMMANDS = {"profile": profile, "hertz": hertz, "solve": solve, "relief": relief,
            "crowning": crowning, "study": study, "optimize": optimize, "drive": drive,
            "bench": bench, "cache": cache}


DESCRIPTION = ("Finite-element stresses of compound-cycloid internal gear tooth pairs: "
               "profiles, tooth-pair solves, studies, design searches and the drive level.")


def _add_common(parser: Parser, default) -> None:
    """``-v`` and ``-q``, taken before the command or after it."""
    parser.add_argument("-v", "--verbose", action="store_true", default=default,
                        help="log what the solver does (on stderr)")
    parser.add_argument("-q", "--quiet", action="store_true", default=default,
                        help="no progress bar (it shows only on a terminal anyway)")


def build_parser(only: str | None = None) -> Parser:
    """The command line's parser: every command's, or ``only`` that command's (what a command
    run parses: the others' options are most of the time it takes to build them all, 20 ms
    of a command's start)."""
    parser = Parser(prog="fegear", description=DESCRIPTION)
    parser.add_argument("--version", action="version", version=f"fegear {__version__}")
    _add_common(parser, False)
    sub = parser.add_subparsers(dest="command", required=True, parser_class=Parser)
    for name, module in COMMANDS.items():
        if only is None or name == only:
            module.add_parser(sub)
    for command in _commands(parser):
        # SUPPRESS: a command's own default does not undo ``fegear -q solve``
        _add_common(command, argparse.SUPPRESS)
    return parser


def _commands(parser: Parser):
    """Every (sub)command's parser below ``parser``: ``solve``, ``drive``, ``drive ratio``, …"""
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for command in action.choices.values():
                yield command
                yield from _commands(command)


def _options(parser: Parser, a: argparse.Namespace) -> set[str]:
    """The option strings of the command ``a`` ran (its subcommands' too)."""
    command = next((c for name, c in _subcommands(parser) if name == a.command), parser)
    found = set()
    for p in (command, *(c for _, c in _subcommands(command))):
        found.update(s for action in p._actions for s in action.option_strings)
    return found


def _subcommands(parser: Parser):
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            yield from action.choices.items()


def main(argv: list[str] | None = None) -> int:
    """Run ``fegear`` with ``argv`` (default: the process's arguments); the exit code."""
    given = sys.argv[1:] if argv is None else argv
    # the command: the first word that is no option (the options before it take no value)
    command = next((w for w in given if not w.startswith("-")), None)
    parser = build_parser(command if command in COMMANDS else None)
    a = parser.parse_args(argv)
    a.argv = list(given)   # as typed: a report repeats it
    logging.basicConfig(level=logging.INFO if a.verbose else logging.WARNING,
                        format="%(levelname)s %(name)s: %(message)s")
    bar = StageBar(enabled=not a.quiet and sys.stderr.isatty())
    try:
        with stop_on_signals(), progress.reporting(bar):
            return COMMANDS[a.command].run(a)
    except ParameterError as exc:
        bar.close()
        typed = f"--{exc.name}"
        known = typed in _options(parser, a)
        print(f"fegear: error: {exc.describe(typed) if known else exc}", file=sys.stderr)
        return EXIT_USAGE
    except FegearError as exc:
        bar.close()
        print(f"fegear: error: {exc}", file=sys.stderr)
        return EXIT_USAGE
    except Stopped as exc:
        bar.close()
        print(f"fegear: stopped by {exc}; nothing half-written was left behind",
              file=sys.stderr)
        return 128 + exc.signum
    except BrokenPipeError:
        # the reader went away (``fegear drive bearings | head``): nothing more to say;
        # stdout goes to devnull so that Python's own flush at exit is silent too
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return EXIT_BROKEN_PIPE
    except OSError as exc:
        # an output that passed the early check and still cannot be written (a directory
        # where a file goes, a full file system): one line, no traceback
        bar.close()
        target = exc.filename2 or exc.filename
        print(f"fegear: error: cannot write {target}: {exc.strerror or exc}", file=sys.stderr)
        return EXIT_USAGE
    finally:
        bar.close()


__all__ = ["main", "build_parser", "COMMANDS", "EXIT_USAGE"]

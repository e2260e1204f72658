"""Command line: ``fegear profile``, ``hertz``, ``solve``, ``relief``, ``study``, ``drive`` and
``bench``.

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

import logging
import sys

from .. import progress
from ..errors import FegearError
from . import bench, drive, hertz, profile, relief, solve, study
from .args import EXIT_USAGE, Parser
from .terminal import StageBar, Stopped, stop_on_signals

#: the commands in the order of ``fegear --help``
COMMANDS = {"profile": profile, "hertz": hertz, "solve": solve, "relief": relief,
            "study": study, "drive": drive, "bench": bench}


def build_parser() -> Parser:
    from .. import __version__

    parser = Parser(prog="fegear", description=__doc__.splitlines()[0])
    parser.add_argument("--version", action="version", version=f"fegear {__version__}")
    parser.add_argument("-v", "--verbose", action="store_true",
                        help="log what the solver does (on stderr)")
    parser.add_argument("-q", "--quiet", action="store_true",
                        help="no progress bar (it shows only on a terminal anyway)")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=Parser)
    for module in COMMANDS.values():
        module.add_parser(sub)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Run ``fegear`` with ``argv`` (default: the process's arguments); the exit code."""
    a = build_parser().parse_args(argv)
    logging.basicConfig(level=logging.INFO if a.verbose else logging.WARNING,
                        format="%(levelname)s %(name)s: %(message)s")
    bar = StageBar(enabled=not a.quiet and sys.stderr.isatty())
    try:
        with stop_on_signals(), progress.reporting(bar):
            return COMMANDS[a.command].run(a)
    except FegearError as exc:
        bar.close()
        print(f"fegear: error: {exc}", file=sys.stderr)
        return EXIT_USAGE
    except Stopped as exc:
        bar.close()
        print(f"fegear: stopped by {exc}; nothing half-written was left behind",
              file=sys.stderr)
        return 128 + exc.signum
    finally:
        bar.close()


__all__ = ["main", "build_parser", "COMMANDS", "EXIT_USAGE"]

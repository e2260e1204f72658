"""``fegear`` run in the test's own process, as a process would show it: its exit code, its
stdout, and the lines of its stderr with the warnings it raised counted among them (Python's
default filters print those on stderr). A command started as a process of its own costs 0.2-3 s
more; one such start a command keeps the process itself checked (tests/cli/test_cli.py)."""

from __future__ import annotations

import warnings
from dataclasses import dataclass

#: what Python's default warning filters do not print for a module other than __main__
NOT_PRINTED = (DeprecationWarning, PendingDeprecationWarning, ImportWarning, ResourceWarning)


@dataclass(frozen=True)
class Ran:
    """What ``fegear`` gave: exit code, stdout, stderr's lines (the printed warnings last)."""

    code: int
    out: str
    lines: list[str]


def fegear(capture, *argv: str) -> Ran:
    """Run ``fegear argv`` by :func:`fegear.cli.main`, its output read from ``capture``
    (pytest's ``capsys``, or ``capfd`` for what is written at the file descriptors too)."""
    from fegear.cli import main

    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("default")
        try:
            code = main(list(argv))
        except SystemExit as exc:   # argparse's own refusals
            code = exc.code
    std = capture.readouterr()
    printed = [f"{w.category.__name__}: {w.message}" for w in seen
               if not issubclass(w.category, NOT_PRINTED)]
    return Ran(code, std.out, std.err.strip().splitlines() + printed)

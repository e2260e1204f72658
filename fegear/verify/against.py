"""The user's commands timed here and in another checkout, alternately, in one run
(``fegear bench --against DIR``): what a change does to what a designer waits for, measured
as a ratio on one machine at one time.

Each command runs as a fresh process (imports included, as a user types it), here with this
interpreter's fegear and there with the other checkout's ``.venv/bin/fegear``, in its own
checkout folder, with an empty model cache that is off; the two sides alternate, the order
flipped every repetition, so that a machine that slows down or speeds up meanwhile weighs on
both alike. The median of each side is kept.
"""

from __future__ import annotations

import os
import shutil
import statistics
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

from ..errors import FegearError
from ..timing import Stopwatch

#: what is timed: a name and ``fegear``'s arguments ({tmp}: a fresh folder of the run's)
COMMANDS = (
    ("one position: fegear solve --no-estimate", ("solve", "--no-estimate")),
    ("fegear solve", ("solve",)),
    ("24-position cycle: fegear solve --positions 24 --no-estimate",
     ("solve", "--positions", "24", "--no-estimate")),
    ("fegear solve --positions 24", ("solve", "--positions", "24")),
    ("fegear relief", ("relief", "--no-cache")),
    ("the paper study: fegear study studies/paper_trends.toml",
     ("study", "studies/paper_trends.toml", "--no-cache", "--out", "{tmp}/study")),
    ("fegear optimize --trials 40", ("optimize", "--trials", "40", "--out", "{tmp}/opt")),
    ("revolution, one pitch deviation: fegear solve --revolution --pitch-deviation 1:11=5",
     ("solve", "--revolution", "--pitch-deviation", "1:11=5", "--no-estimate",
      "--out", "{tmp}/rev")),
    ("revolution, gear-1 runout: fegear solve --revolution --runout 1=10@0",
     ("solve", "--revolution", "--runout", "1=10@0", "--no-estimate", "--out", "{tmp}/rev")),
    ("a tolerance class: fegear solve --grade 5 --samples 100 --shift 0.03",
     ("solve", "--grade", "5", "--samples", "100", "--shift", "0.03", "--no-estimate")),
)


@dataclass(frozen=True)
class Timed:
    """One command's wall times (s) here and there, each run; ``failed_there``: why the other
    checkout could not run it (a command it does not have: its times are then empty)."""

    name: str
    here: tuple[float, ...]
    there: tuple[float, ...]
    failed_there: str = ""

    @property
    def ratio(self) -> float:
        """Here over there, medians (NaN where it did not run there)."""
        if not self.there:
            return float("nan")
        return statistics.median(self.here) / statistics.median(self.there)


def checkout(path: str | Path) -> Path:
    """The other checkout's folder, refused by name unless it holds ``.venv/bin/fegear``."""
    root = Path(path).resolve()
    if not (root / ".venv" / "bin" / "fegear").exists():
        raise FegearError(f"--against {path}: no fegear checkout with its .venv there "
                          "(make .venv/.installed-stamp in it first)")
    return root


def time_against(there: Path, repeat: int, commands=COMMANDS) -> list[Timed]:
    """Each of ``commands`` run ``repeat`` times here and in the checkout ``there``,
    alternately (module docstring)."""
    here = Path(__file__).resolve().parents[2]
    sides = {"here": ([sys.executable, "-m", "fegear"], here),
             "there": ([str(there / ".venv" / "bin" / "fegear")], there)}
    out = []
    for name, args in commands:
        times: dict[str, list[float]] = {"here": [], "there": []}
        failed = ""
        for k in range(repeat):
            for side in ("here", "there") if k % 2 == 0 else ("there", "here"):
                try:
                    times[side].append(_run(*sides[side], args))
                except FegearError as err:
                    if side == "here":
                        raise
                    failed = str(err)   # a command the other checkout does not have
                    break
            if failed:
                times["there"].clear()
                break
        row = Timed(name, tuple(times["here"]), tuple(times["there"]), failed)
        out.append(row)
    return out


def _run(fegear: list[str], cwd: Path, args: tuple[str, ...]) -> float:
    """The wall time (s) of one command in a fresh process with a fresh, unused cache."""
    tmp = tempfile.mkdtemp(prefix="fegear-against-")
    try:
        env = {**os.environ, "FEGEAR_CACHE": "off", "FEGEAR_CACHE_DIR": f"{tmp}/cache"}
        argv = [*fegear, "-q", *(a.replace("{tmp}", tmp) for a in args)]
        watch = Stopwatch()
        done = subprocess.run(argv, cwd=cwd, env=env, capture_output=True, text=True)
        wall = watch.s
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    if done.returncode != 0:
        raise FegearError(f"`fegear {' '.join(args)}` failed in {cwd}: "
                          f"{done.stderr.strip().splitlines()[-1] if done.stderr else ''}")
    return wall


def _line(row: Timed) -> str:
    def runs(ts):
        return ", ".join(f"{t:.2f}" for t in ts)

    here = f"{statistics.median(row.here):.2f} ({runs(row.here)})" if row.here else "-"
    if row.failed_there:
        return f"| {row.name} | {here} | failed there: {row.failed_there} | - |"
    return (f"| {row.name} | {here} | "
            f"{statistics.median(row.there):.2f} ({runs(row.there)}) | {row.ratio:.3f} |")


def against_table(rows: list[Timed], there: Path) -> str:
    """Markdown: each command's median wall time here and there (every run in brackets) and
    the ratio."""
    head = [f"| command | here [s] | {there} [s] | here / there |", "|---|---:|---:|---:|"]
    return "\n".join(head + [_line(r) for r in rows])

"""Running CalculiX (``ccx``) and reading its answers back: the status and data files of a run,
its contact stresses and forces, and the decks' own counts."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
from pathlib import Path

import numpy as np

from ..errors import FegearError
from ..timing import Stopwatch


class PeerError(FegearError):
    """CalculiX is missing or failed, or the model cannot be exported."""


class PeerConvergenceError(PeerError):
    """CalculiX gave up on the load step (too many cutbacks) or did not complete it."""


def number(token: str) -> float:
    """A Fortran number, including the E-less ``1.0-100`` of three-digit exponents."""
    t = token.upper().replace("D", "E")
    if "E" not in t:
        t = re.sub(r"(\d)([-+]\d+)$", r"\1E\2", t)
    return float(t)


def floats(line: str) -> list[float]:
    out = []
    for token in line.replace(",", " ").split():
        try:
            out.append(number(token))
        except ValueError:
            pass
    return out


def rows(lines: list[str], header: int) -> list[str]:
    """The data lines after line ``header``: blank lines skipped, up to the next blank one."""
    i = header + 1
    while i < len(lines) and not lines[i].strip():
        i += 1
    rows = []
    while i < len(lines) and lines[i].strip():
        rows.append(lines[i])
        i += 1
    return rows


def last_block(lines: list[str], header: str) -> tuple[list[str], float]:
    """Data lines of the last block titled ``header``, and the time in its title."""
    at = [i for i, line in enumerate(lines) if header in line]
    if not at:
        raise PeerError(f"ccx wrote no {header!r} output")
    return rows(lines, at[-1]), floats(lines[at[-1]])[-1]


def contact_forces(dat: list[str], npairs: int) -> np.ndarray:
    """Per deck pair, from the last ``CF`` blocks: fx, fy, fz, mx, my, mz (about the origin)
    and the normal force (+ = tension)."""
    stats = [i for i, line in enumerate(dat) if "statistics for slave set" in line]
    if len(stats) < npairs:
        raise PeerError(f"ccx wrote {len(stats)} contact force blocks for {npairs} pairs")
    out = []
    for i in stats[len(stats) - npairs:]:
        block = dat[i:i + 20]
        total = block_row(block, "total surface force")[:6]
        area, normal = block_row(block, "normal force (+ = tension)")[:2]
        out.append(total + [normal if area > 0 else 0.0])  # ccx: NaN on a pair out of contact
    return np.array(out)


def block_row(block: list[str], title: str) -> list[float]:
    """The numbers of the first data line under the line containing ``title``."""
    j = next((j for j, line in enumerate(block) if title in line), None)
    if j is None:
        raise PeerError(f"ccx's contact force block has no {title!r} line")
    return floats(rows(block, j)[0])


def save_deck(directory, jobname: str, lines: list[str]) -> Path:
    """The deck's ``lines`` written as ``directory``/``jobname``.inp (the folder made), or one
    line naming the folder that could not take it."""
    out = Path(directory)
    try:
        out.mkdir(parents=True, exist_ok=True)
        path = out / f"{jobname}.inp"
        path.write_text("\n".join(lines) + "\n")
    except OSError as exc:
        raise PeerError(f"cannot write the deck in {str(out)!r}: {exc.strerror}") from None
    return path


def read_text(path: Path) -> str:
    try:
        return path.read_text(errors="replace")
    except OSError as exc:
        raise PeerError(f"cannot read ccx output {str(path)!r}: {exc.strerror}") from None


def deck_counts(inp: str) -> tuple[int, int, float, int]:
    """Nodes, elements, applied load (N, the ``*CLOAD``) and contact pairs of a deck."""
    counts, block, load = {"NODE": 0, "ELEMENT": 0, "CONTACT PAIR": 0}, None, float("nan")
    for line in inp.splitlines():
        if line.startswith("*"):
            block = line[1:].split(",")[0].strip().upper()
            continue
        if block in counts and line.strip():
            counts[block] += 1
        elif block == "CLOAD":
            load = abs(float(line.split(",")[2]))
    return counts["NODE"], counts["ELEMENT"], load, counts["CONTACT PAIR"]


def execute(work: Path, jobname: str, threads: int = 1, timeout: float | None = None
            ) -> tuple[float, str, list[list[str]], list[str]]:
    """Run ``ccx -i <jobname>`` in ``work`` with ``threads`` threads: its wall time (s), log,
    the converged increments of the ``.sta`` (rows: step, increment, attempts, iterations, …)
    and the ``.dat`` lines. Raises :class:`PeerError` when ccx is missing, fails or times out,
    :class:`PeerConvergenceError` when it gives up or does not complete step 2."""
    exe = shutil.which("ccx")
    if exe is None:
        raise PeerError("CalculiX (ccx) is not installed or not on the PATH")
    inp = work / f"{jobname}.inp"
    if not inp.is_file():
        raise PeerError(f"no deck {str(inp)!r}")
    if not (isinstance(threads, int) and threads >= 1):
        raise PeerError(f"threads must be an integer >= 1: {threads!r}")
    env = dict(os.environ)
    for var in ("OMP_NUM_THREADS", "CCX_NPROC_EQUATION_SOLVER", "CCX_NPROC_STIFFNESS",
                "CCX_NPROC_RESULTS"):
        env[var] = str(threads)
    log = work / f"{jobname}.log"
    watch = Stopwatch()
    try:
        with open(log, "w") as out:
            proc = subprocess.run([exe, "-i", jobname], cwd=work, env=env, stdout=out,
                                  stderr=subprocess.STDOUT, timeout=timeout)
    except subprocess.TimeoutExpired:
        raise PeerError(f"ccx did not finish within {timeout} s (log: {log})") from None
    wall = watch.s
    text = read_text(log)
    out = text.splitlines() + [""]
    errors = [" ".join(f"{out[i]} {out[i + 1] if '*' not in out[i + 1] else ''}".split())
              for i in range(len(out) - 1) if "*ERROR" in out[i]]
    if proc.returncode != 0 or errors:
        why = "; ".join(dict.fromkeys(errors[:2])) or f"exit code {proc.returncode}"
        if "cutback" in why:
            raise PeerConvergenceError(f"ccx did not converge: {why} (log: {log})")
        raise PeerError(f"ccx failed: {why} (log: {log})")
    steps = [line.split() for line in read_text(work / f"{jobname}.sta").splitlines()
             if re.match(r"^\s*\d+\s+\d+\s+\d+\s+\d+\s+\S+\s+\S+\s+\S+\s*$", line)]
    if not steps or int(steps[-1][0]) != 2 or abs(floats(steps[-1][5])[0] - 1.0) > 1e-9:
        raise PeerConvergenceError(f"ccx did not complete the load step ({work / jobname}.sta)")
    return wall, text, steps, read_text(work / f"{jobname}.dat").splitlines()

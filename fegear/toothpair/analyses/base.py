"""The protocol every analysis of a solved pair meets (:class:`Analysis`), what it is handed
(:class:`Run` to solve, :class:`Writing` to write files) and what it judges (:class:`Verdict`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from ...running import SERIAL, Executor

if TYPE_CHECKING:   # the job hands itself over; the analyses never import it
    from ..job import Job, Solved


@dataclass(frozen=True)
class Verdict:
    """Whether a design passes an analysis's check, and the line that says why (with its
    scope: ``static: …``, ``for the life: …``, ``for the class: …``)."""

    passed: bool
    line: str


@dataclass(frozen=True)
class Run:
    """What an analysis is handed to solve: the job, the solver the positions were solved
    with (its model kept), the solutions at every position, the one the pictures and the
    estimate take, the executor for parallel work, the core's summary so far and what the
    analysis that drove the positions kept (:meth:`Analysis.drive`; None otherwise)."""

    job: Job
    solver: object
    solutions: tuple
    solution: object
    executor: Executor = SERIAL
    summary: dict = field(default_factory=dict)
    driven: object = None


@dataclass(frozen=True)
class Writing:
    """What an analysis is handed to write its files: the solved job, the folder (made), the
    pictures' title, whether to write fields (VTU) and pictures."""

    solved: Solved
    out: Path
    title: str
    fields: bool = True
    pictures: bool = True


class Analysis:
    """One analysis of a solved pair. ``key`` names its entry in the summary (and so in
    ``fegear solve --json``, the study records and the report page), ``replaces`` the entries
    whose presentation it takes over (a revolution's table stands where a cycle's would), and
    ``before_pair`` prints it before the pair's own table. Each method has a default that
    does nothing, so an analysis defines what it has."""

    key: str = ""
    replaces: tuple[str, ...] = ()
    before_pair: bool = False
    #: its pictures on the report page, in order: the key of each among its files, with a
    #: caption
    pictures: dict[str, str] = {}

    def wanted(self, job: Job) -> bool:
        """Whether ``job`` asks for this analysis."""
        return False

    def drive(self, job: Job, executor: Executor):
        """Solve the positions itself, where the analysis needs more than the exact pair at
        them (a class's samples): ``(solver, solutions, kept)``; None: the core drives."""
        return None

    def solve(self, run: Run) -> dict | None:
        """Its summary entry (JSON-ready), or None where the core's summary holds it."""
        return None

    def printed(self, entry: dict, summary: dict) -> str:
        """What ``fegear solve`` prints of it ('' for nothing)."""
        return ""

    def write(self, entry: dict, writing: Writing) -> dict[str, Path]:
        """Its files (name → path)."""
        return {}

    def verdict(self, entry: dict) -> Verdict | None:
        """Its verdict, where it judges the design."""
        return None

    def page(self, entry: dict) -> list[tuple[str, str]]:
        """Its parts of the report page as (slot, HTML): ``safety`` under the static safety
        factors, ``sections`` after the stresses."""
        return []

    def stress_columns(self, entry: dict) -> tuple[list[str], dict[str, list[str]]]:
        """Its columns beside the report page's stress table: their heads, and each
        headline's cells by its key (a headline it has no cells for gets dashes)."""
        return [], {}

    def columns(self, entry: dict) -> dict | None:
        """Its columns in a study's table; None: its entry flattened as the rest."""
        return None

"""A whole revolution of the exact pair (``--revolution``): every pitch of gear 1's turn, the
worst of each stress with its tooth, each tooth's largest, the loaded rotation's spectrum
(:mod:`.solve`), its table and files (:mod:`.report`) and pictures (:mod:`.plot`); a class's
pairs over a revolution are the samples' own."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

from ...present.tables import deviations_words
from ..base import Analysis, Run, Writing
from .report import revolution_table, write_revolution_outputs
from .solve import revolution_summary


class Revolution(Analysis):
    key = "revolution"
    pictures = {"revolution_png": "The stresses over a whole revolution",
                "revolution_teeth_png": "Each tooth's largest stresses over the revolution"}
    replaces = ("cycle",)
    before_pair = True

    def wanted(self, job) -> bool:
        return job.revolution and job.draw is None

    def solve(self, run: Run) -> dict:
        return revolution_summary(tuple(run.solutions), run.job.allowables)

    def printed(self, entry: dict, summary: dict) -> str:
        return (f"{revolution_table(entry)}\n\n{entry['positions']} positions over "
                f"{entry['pitches']} pitches (one turn of gear 1) in "
                f"{summary['cycle']['solve_s']:.1f} s; the details below are at the position "
                "of the largest gear-1 root stress\n")

    def write(self, entry: dict, writing: Writing) -> dict[str, Path]:
        words = deviations_words(writing.solved.summary["inputs"].get("deviations"))
        deviations = f"deviations: {words}" if words else "no deviations (a perfect pair)"
        return write_revolution_outputs(entry, replace(writing,
                                                       title=f"{writing.title}\n{deviations}"))


REVOLUTION = Revolution()

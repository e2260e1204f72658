"""The sensitivities (``--sensitivities``): each headline's rate with each deviation of the
teeth in mesh at the pictured position (:mod:`fegear.toothpair.ring.sensitivity`: the core's
ring model forms them), and with a class what one tolerance of each moves, its table and
files (:mod:`.report`) and its tornado (:mod:`.plot`)."""

from __future__ import annotations

import math
from pathlib import Path

from .... import progress
from ..base import Analysis, Run, Writing


class Sensitivities(Analysis):
    key = "sensitivities"

    def wanted(self, job) -> bool:
        return job.sensitivities

    def solve(self, run: Run) -> dict:
        from ...ring.sensitivity import solved_sensitivities
        from .report import sensitivity_summary

        progress.stage("sensitivities: each stress's rate with each deviation in mesh")
        sol, draw = run.solution, run.job.draw
        return sensitivity_summary(solved_sensitivities(sol), math.degrees(sol.case.beta),
                                   None if draw is None else draw.grade)

    def printed(self, entry: dict, summary: dict) -> str:
        from .report import sensitivity_table

        return ("\nSensitivities: each stress's rate with each deviation of the teeth in mesh "
                "(the largest first):\n\n" + sensitivity_table(entry))

    def write(self, entry: dict, writing: Writing) -> dict[str, Path]:
        from .report import write_sensitivity_outputs

        return write_sensitivity_outputs(entry, writing.out, writing.title, writing.pictures)

    def columns(self, entry: dict) -> dict:
        from .report import sensitivity_columns

        return sensitivity_columns(entry)


SENSITIVITIES = Sensitivities()

"""The sensitivities (``--sensitivities``): each headline's rate with each deviation of the
teeth in mesh at the pictured position (:mod:`fegear.toothpair.ring.sensitivity`: the core's
ring model forms them), and with a class what one tolerance of each moves, its table and
files (:mod:`.report`) and its tornado (:mod:`.plot`)."""

from __future__ import annotations

import math
from pathlib import Path

from .... import progress
from ..base import Analysis, Run, Writing
from .report import (
    sensitivity_columns,
    sensitivity_summary,
    sensitivity_table,
    write_sensitivity_outputs,
)


class Sensitivities(Analysis):
    key = "sensitivities"
    pictures = {"sensitivities_png": "Which deviation decides the stress"}

    def wanted(self, job) -> bool:
        return job.sensitivities

    def solve(self, run: Run) -> dict:
        from ...ring.sensitivity import solved_sensitivities  # lazy: heavy: scikit-fem

        progress.stage("sensitivities: each stress's rate with each deviation in mesh")
        sol, draw = run.solution, run.job.draw
        return sensitivity_summary(solved_sensitivities(sol), math.degrees(sol.case.beta),
                                   None if draw is None else draw.grade)

    def printed(self, entry: dict, summary: dict) -> str:
        return ("\nSensitivities: each stress's rate with each deviation of the teeth in mesh "
                "(the largest first):\n\n" + sensitivity_table(entry))

    def write(self, entry: dict, writing: Writing) -> dict[str, Path]:
        return write_sensitivity_outputs(entry, writing.out, writing.title, writing.pictures)

    def columns(self, entry: dict) -> dict:
        return sensitivity_columns(entry)


SENSITIVITIES = Sensitivities()

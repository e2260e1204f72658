"""Across the face width (``--misalignment``, ``--tilt``, ``--crowning``, ``--end-relief``,
``--face-sections``): the pair at each position solved at sections across the face on the
contact the solver kept there (:mod:`.solve`), K_Hβ beside ISO's method C and each headline
at its worst section (:mod:`.report`), and the contact pattern (:mod:`.plot`)."""

from __future__ import annotations

from pathlib import Path

from ..base import Analysis, Run, Writing
from .report import face_summary, face_table, write_face_outputs


class Face(Analysis):
    key = "face"
    pictures = {"face_png": "The line load across the face: the contact pattern"}

    def wanted(self, job) -> bool:
        return job.face is not None

    def drive(self, job, executor):
        from .solve import drive_face  # lazy: heavy: scikit-fem

        solver, sols, rows = drive_face(job, executor)
        return solver, sols, rows

    def solve(self, run: Run) -> dict:
        from .solve import coupling_of  # lazy: heavy: scikit-fem

        face = run.job.face
        return face_summary(list(run.driven), coupling_of(run.job.case, face), face)

    def printed(self, entry: dict, summary: dict) -> str:
        width = summary["inputs"]["thickness_mm"]
        return (f"\nAcross the face ({entry['inputs']['sections']} sections; each "
                "stress at its worst section against the 2D pair's):\n\n"
                + face_table(entry, width))

    def write(self, entry: dict, writing: Writing) -> dict[str, Path]:
        width = writing.solved.job.case.thickness
        return write_face_outputs(entry, writing.out, writing.title, width, writing.pictures)


FACE = Face()

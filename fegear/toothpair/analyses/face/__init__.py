"""Across the face width (``--misalignment``, ``--tilt``, ``--crowning``, ``--end-relief``,
``--face-sections``): the pair at each position solved at sections across the face on the
contact the solver kept there (:mod:`.solve`), K_Hβ beside ISO's method C and each headline
at its worst section (:mod:`.report`), and the contact pattern (:mod:`.plot`)."""

from __future__ import annotations

from pathlib import Path

from ..base import Analysis, Run, Verdict, Writing
from .report import (
    face_html,
    face_safety_html,
    face_summary,
    face_table,
    face_verdict,
    write_face_outputs,
)


class Face(Analysis):
    key = "face"
    pictures = {"face_png": "The line load across the face: the contact pattern"}

    def wanted(self, job) -> bool:
        return job.face is not None

    def drive(self, job, executor):
        from .solve import drive_face  # lazy: heavy: scikit-fem

        return drive_face(job, executor)

    def solve(self, run: Run) -> dict:
        job = run.job
        return face_summary(run.driven.rows, run.driven.coupling, job.face, job.allowables,
                            job.case.thickness)

    def printed(self, entry: dict, summary: dict) -> str:
        width = entry["width_mm"]
        return (f"\nAcross the face ({entry['inputs']['sections']} sections; each "
                "stress at its worst section against the 2D pair's):\n\n"
                + face_table(entry, width))

    def write(self, entry: dict, writing: Writing) -> dict[str, Path]:
        patterns = writing.solved.driven.patterns if writing.fields else None
        return write_face_outputs(entry, writing.out, writing.title, entry["width_mm"],
                                  writing.pictures, patterns)

    def verdict(self, entry: dict) -> Verdict:
        passed, line = face_verdict(entry, entry["width_mm"])
        return Verdict(passed, f"across the face: {line}")

    def page(self, entry: dict) -> list[tuple[str, str]]:
        width = entry["width_mm"]
        return [("safety", f"<h3>Across the face, at {entry['inputs']['sections']} "
                           "sections: each factor at its stress's worst section</h3>\n"
                 + face_safety_html(entry, width)),
                ("sections", "<h2>Across the face</h2>\n" + face_html(entry, width))]


FACE = Face()

"""A tolerance class's pairs (``--grade``): drawn, each solved at the job's positions on each
position's kept contact (:mod:`.solve`) beside the exact pair, which they drive; across the
face (a job with a face) each at its worst section with its K_Hβ (:mod:`.across`), after the
face's analysis has driven the exact pair across it; their quantiles, the safety factors at
the quantile and the verdict, samples.csv (:mod:`.report`) and each safety factor's
distribution (:mod:`.plot`)."""

from __future__ import annotations

from pathlib import Path

from ....running import Executor
from ...summary import cycle_rows
from ..base import Analysis, Run, Verdict, Writing
from .report import (
    ClassReading,
    samples_columns,
    samples_summary,
    samples_table,
    stress_cells,
    write_samples_outputs,
)


class Samples(Analysis):
    key = "samples"
    pictures = {"samples_png": "Each safety factor over the tolerance class's pairs"}

    def wanted(self, job) -> bool:
        return job.draw is not None

    def drive(self, job, executor: Executor):
        if job.face is not None:   # the face's analysis drives the exact pair across it
            return None
        solver, sampled = _sampled(job, executor)
        # the exact pair's stresses as the samples' are read: von Mises from the surface
        # estimate, before the peaks' submodels
        return solver, sampled.nominal, (sampled, cycle_rows(sampled.nominal, job.allowables))

    def solve(self, run: Run) -> dict:
        job = run.job
        if job.face is None:
            sampled, estimated = run.driven
        else:   # the exact pair at its worst sections, as the samples are read
            sampled = _sampled(job, run.executor)[1]
            estimated = list(sampled.across)
        return samples_summary(sampled.rows, estimated, ClassReading(
            draw=job.draw, quantile=job.quantile, allowables=job.allowables,
            positions=len(job.betas), revolution=job.revolution, face=job.face,
            solved_per_pair=sampled.solved_per_pair))

    def printed(self, entry: dict, summary: dict) -> str:
        over = ("the same positions" if entry["over"] == "cycle" else
                f"a whole revolution each ({entry['positions_per_pair']} positions: the "
                "cycle's at every pitch of gear 1)")
        if entry.get("screened"):
            over += (", screened: each at every pitch at a few of the cycle's places, then "
                     "about and beside those nearest its largest, "
                     f"{entry['positions_solved_per_pair']:.0f} positions a pair on average")
        face = (", across the face, the exact pair and each of them at its worst section"
                if "across" in entry else "")
        return (f"\nThe exact pair above; the pairs of its tolerance class over {over}{face} "
                "(von Mises from the templates' surface estimate, as the samples' is read):"
                "\n\n" + samples_table(entry))

    def write(self, entry: dict, writing: Writing) -> dict[str, Path]:
        return write_samples_outputs(entry, writing.out, writing.title,
                                     writing.solved.job.allowables, writing.pictures)

    def verdict(self, entry: dict) -> Verdict:
        line = entry["verdict"]
        return Verdict(entry.get("passed", line.startswith("PASS")), f"for the class: {line}")

    def stress_columns(self, entry: dict) -> tuple[list[str], dict[str, list[str]]]:
        return stress_cells(entry)

    def columns(self, entry: dict) -> dict:
        return samples_columns(entry)


def _sampled(job, executor: Executor):
    """The job's class solved at its positions (:func:`~.solve.solve_samples`), across its
    face where it has one: (the solver, the :class:`~.solve.Sampled`)."""
    from ...ring.solver import RingSolver, SolverModes  # lazy: heavy: scikit-fem
    from .solve import class_case, solve_samples  # lazy: heavy: scikit-fem

    solver = RingSolver(None, SolverModes(keep_phases=True))
    return solver, solve_samples(class_case(job, job.allowables, job.face), solver, executor)


SAMPLES = Samples()

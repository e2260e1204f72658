"""A rating for a life (``--spectrum``): each level of the load spectrum solved on the kept
model over the job's positions, each gear's root and flank rated on the material's S-N lines
by Miner's rule (:mod:`.solve`, :mod:`fegear.rating`); its table, rating.csv and its two parts
of the report page (:mod:`.report`), its verdict."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

from ....running import Executor
from ....timing import Stopwatch
from ...case import in_given_order, phase_major
from ..base import Analysis, Run, Verdict, Writing
from .report import life_html, rating_table, spectrum_html, write_rating_outputs
from .solve import across_face, level_stresses, rated, same_teeth, solve_levels


class Rating(Analysis):
    key = "rating"

    def wanted(self, job) -> bool:
        return job.rating is not None

    def solve(self, run: Run) -> dict:
        from ...positions import drive_torques  # lazy: heavy: scipy
        from ...ring.solver import RingSolver, SolverModes  # lazy: heavy: scikit-fem

        job, model = run.job, run.solver.model
        watch = Stopwatch()

        # the model kept, the roots and the pressures read alone
        roots = SolverModes(roots_only=True)

        def in_plane(case, betas, torques, executor: Executor):
            # over a revolution, phase by phase: the lighter levels on the contacts the
            # heaviest one keeps for the phases (each repeating its own pitches)
            if not job.revolution:
                return drive_torques(case, betas, torques, RingSolver(model, roots), executor)
            order = phase_major(len(betas), case.params.z1)
            solver = RingSolver(model, replace(roots, keep_phases=True))
            by_torque = drive_torques(case, [betas[k] for k in order], torques, solver,
                                      executor)
            return [in_given_order(order, sols) for sols in by_torque]

        # across the face, each level solved so too: its tooth stresses at their worst
        # sections (the job's own solutions are the 2D pair's)
        across = job.face is not None
        levels = solve_levels(job.case, job.betas, job.rating,
                              across_face(job, model) if across else in_plane,
                              run.executor, None if across else run.solutions)
        z = (job.case.params.z1, job.case.params.z2)
        return {**rated(level_stresses(job, levels), job.rating, z,
                        every_tooth=same_teeth(job)),
                "across_face": across, "solve_s": watch.s}

    def printed(self, entry: dict, summary: dict) -> str:
        across = (" across the face, each tooth's stresses at its worst section"
                  if entry.get("across_face") else "")
        return (f"\nRated for a life: each level of the spectrum solved over the positions"
                f"{across} ({entry['solve_s']:.1f} s):\n\n" + rating_table(entry))

    def write(self, entry: dict, writing: Writing) -> dict[str, Path]:
        return write_rating_outputs(entry, writing.out)

    def verdict(self, entry: dict) -> Verdict:
        line = entry["verdict"]
        return Verdict(entry.get("passed", line.startswith("PASS")), f"for the life: {line}")

    def page(self, entry: dict) -> list[tuple[str, str]]:
        return [("safety", "<h3>For the life</h3>\n" + life_html(entry)),
                ("sections", "<h2>The load spectrum</h2>\n" + spectrum_html(entry))]


RATING = Rating()

"""A rating for a life (``--spectrum``): each level of the load spectrum solved on the kept
model over the job's positions (:mod:`..levels`), each gear's root and flank rated on the
material's S-N lines by Miner's rule (:mod:`fegear.rating`); its table, rating.csv, its
verdict and its two parts of the report page."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

from ...running import Executor
from ...timing import Stopwatch
from ..html_parts import escape, safety_cell, table
from .base import Analysis, Run, Verdict, Writing


class Rating(Analysis):
    key = "rating"

    def wanted(self, job) -> bool:
        return job.rating is not None

    def solve(self, run: Run) -> dict:
        from ..levels import rated, solve_levels
        from ..positions import drive_torques, positions_of
        from ..ring.solver import RingSolver, SolverModes

        job, model = run.job, run.solver.model
        watch = Stopwatch()

        # the model kept, the roots and the pressures read alone
        roots = SolverModes(roots_only=True)

        def level(case, betas, torques, executor: Executor):
            # a revolution's kept phases hold solutions at one torque: there a solver of its
            # own a level
            if not job.revolution:
                return drive_torques(case, betas, torques, RingSolver(model, roots), executor)
            keeping = replace(roots, keep_phases=True)
            return [positions_of(RingSolver(model, keeping), job.revolution)(
                replace(case, torque=torque), betas, executor) for torque in torques]

        levels = solve_levels(job.case, job.betas, job.rating, level, run.executor,
                              run.solutions)
        return {**rated(levels, job.rating, every_tooth=not job.case.deviations),
                "solve_s": watch.s}

    def printed(self, entry: dict, summary: dict) -> str:
        from ..rating_report import rating_table

        return (f"\nRated for a life: each level of the spectrum solved over the positions "
                f"({entry['solve_s']:.1f} s):\n\n" + rating_table(entry))

    def write(self, entry: dict, writing: Writing) -> dict[str, Path]:
        from ..output import write_rating_outputs

        return write_rating_outputs(entry, writing.out)

    def verdict(self, entry: dict) -> Verdict:
        line = entry["verdict"]
        return Verdict(entry.get("passed", line.startswith("PASS")), f"for the life: {line}")

    def page(self, entry: dict) -> list[tuple[str, str]]:
        return [("safety", "<h3>For the life</h3>\n" + _life_table(entry)),
                ("sections", "<h2>The load spectrum</h2>\n" + _spectrum_table(entry))]


def _life_table(r: dict) -> str:
    """Each mode's Miner's sum, life and safety factor at the required life, and the
    material's lines."""
    from ..rating_report import damage_text, life_text

    rows = []
    for mode, m in r["modes"].items():
        rows.append([mode, "all" if m["tooth"] is None else str(m["tooth"]),
                     damage_text(m["miner"]), life_text(m), safety_cell(m["safety"])])
    mat = r["material"]
    note = (f"<p>{escape(mat['name'])} ({escape(mat['treatment'])}): σ_Hlim "
            f"{mat['sigma_Hlim_MPa']:g} MPa, σ_FE {mat['sigma_FE_MPa']:g} MPa; "
            f"{escape(mat['source'])}. KA {r['KA']:g}, KV {r['KV']:g}.</p>")
    return table(["mode", "tooth", "Miner's sum", "life", "S at the required life"],
                 rows) + note


def _spectrum_table(r: dict) -> str:
    """Each level's torque, solved torque, cycles and each mode's stress and damage."""
    from ..rating_report import damage_text

    rows = []
    modes = list(r["modes"].items())
    for k, level in enumerate(r["levels"]):
        rows.append([str(k + 1), f"{level['torque_Nm']:g}", f"{level['solved_torque_Nm']:.4g}",
                     f"{level['cycles']:.3g}",
                     *[f"{m['stress_MPa'][k]:.1f} / {damage_text(m['damage'][k])}"
                       for _, m in modes]])
    head = ["level", "torque N·m", "solved N·m", "cycles",
            *[f"{name}: MPa / damage" for name, _ in modes]]
    return table(head, rows)


RATING = Rating()

"""The mesh cycle (``--positions N``): the core solves the positions and its summary holds
their rows (``summary["cycle"]``); this analysis prints their table and writes cycle.csv, the
mesh stiffness (:mod:`.report`), the ParaView series and cycle.png (:mod:`.plot`)."""

from __future__ import annotations

from pathlib import Path

from ...present.writers import write_cycle_series
from ..base import Analysis, Writing
from .report import cycle_table, write_cycle_outputs, write_mesh_stiffness


class Cycle(Analysis):
    key = "cycle"
    pictures = {"cycle_png": "The stresses and safety factors over the mesh cycle"}
    before_pair = True

    def wanted(self, job) -> bool:
        return len(job.betas) > 1

    def printed(self, entry: dict, summary: dict) -> str:
        also = " (and the class's pairs)" if "samples" in summary else ""
        default = entry.get("default")
        return (f"{cycle_table(entry['rows'])}\n\n{len(entry['rows'])} positions on one "
                f"mesh{also} in {entry['solve_s']:.1f} s; the details below are at the "
                "position of the largest gear-1 root stress"
                + (f"\n(not given: {default})" if default else "") + "\n")

    def write(self, entry: dict, writing: Writing) -> dict[str, Path]:
        solved, out = writing.solved, writing.out
        files = dict(write_mesh_stiffness(out, solved.rows, solved.job.case))
        if writing.fields:
            files.update(write_cycle_series(solved.solutions, out))
        if writing.pictures:
            files.update(write_cycle_outputs(solved.rows, out, writing.title,
                                             solved.job.allowables))
        return files


CYCLE = Cycle()

"""The pair solved across the face at the job's positions (``fegear solve --misalignment`` and
the options beside it): each position on the contact the solver kept for it
(:func:`~fegear.toothpair.ring.face_results.face_sections`), its sections' headlines, the
teeth's line loads and K_Hβ, with ISO 6336-1's method C beside it for the same mismatch and
the pair's own approach."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ....running import Executor
from ...face_drive import coupling_of, drive_across
from ...ring.face import FaceCoupling
from ...ring.face_results import FaceSections


def method_c(mismatch_um: float, approach_um: float) -> float:
    """ISO 6336-1's method C face load factor for a linear mismatch F_βy (µm over the face)
    on a mesh whose mean load approaches it by ``approach_um`` (F_m/b over c_γβ): 1 + F_βy
    c_γβ / (2 F_m/b) while that is at most 2, else √(2 F_βy c_γβ / (F_m/b)) (the face only
    partly in contact).

    >>> method_c(0.0, 5.0), method_c(5.0, 5.0), method_c(40.0, 5.0)
    (1.0, 1.5, 4.0)
    """
    ratio = abs(mismatch_um) / approach_um
    return 1.0 + 0.5 * ratio if ratio <= 2.0 else math.sqrt(2.0 * ratio)


@dataclass(frozen=True)
class FacePattern:
    """One position's contact across the face as the slices' VTU shows it: the loaded grids'
    points in the fixed frame (mm), their gear-1 tooth, and their pressure (MPa) and gap
    (µm) at each section (points × sections)."""

    xy: np.ndarray
    tooth: np.ndarray
    pressure: np.ndarray
    gap_um: np.ndarray


@dataclass(frozen=True)
class FaceDriven:
    """What :func:`drive_face` keeps: a summary row a position (:func:`position_entry`),
    each position's :class:`FacePattern` and the sections' coupling they were solved with."""

    rows: list
    patterns: list
    coupling: FaceCoupling


def pattern_of(sections: FaceSections) -> FacePattern:
    """The :class:`FacePattern` of the grids that carry pressure at any section."""
    loaded = np.flatnonzero([sections.solution.pressure[sections.grid == k].any()
                             for k in range(len(sections.teeth))])
    on = np.isin(sections.grid, loaded)
    return FacePattern(sections.xy[on], np.asarray(sections.teeth)[sections.grid[on]],
                       sections.solution.pressure[on], 1e3 * sections.solution.gap[on])


def drive_face(job, executor: Executor):
    """The job's positions solved across the face (:func:`~...face_drive.drive_across`):
    (solver, the 2D solutions, a :class:`FaceDriven`)."""
    coupling = coupling_of(job.case, job.face)
    solver, sols, taken = drive_across(
        job, lambda sol, sections: (position_entry(sol, sections[0]), pattern_of(sections[0])),
        coupling, executor)
    return solver, sols, FaceDriven([row for row, _ in taken],
                                    [pattern for _, pattern in taken], coupling)


def position_entry(sol, sections: FaceSections) -> dict:
    """One position's summary row: K_Hβ, method C's, each headline at its worst section with
    its ratio to the 2D pair's, and each tooth's line load along the face."""
    flat = sol.headline()
    worst = {}
    for key, (s, value) in sections.worst_headlines().items():
        worst[key] = {"value": value, "section": s,
                      "zeta": float(sections.coupling.zeta[s]),
                      "ratio": value / flat[key] if flat[key] else None}
    mismatch, approach = _mismatch_and_approach(sol, sections)
    loads = {str(t): [float(x) for x in row]
             for t, row in zip(sections.teeth, sections.line_loads) if row.any()}
    return {"position_deg": math.degrees(sol.case.beta), "K_Hbeta": sections.load_factor,
            "K_Hbeta_method_c": method_c(mismatch, approach), "mismatch_um": mismatch,
            "approach_um": approach, "worst": worst, "line_loads_N_per_mm": loads}


def _mismatch_and_approach(sol, sections: FaceSections) -> tuple[float, float]:
    """The most loaded tooth's mismatch across the face at its most loaded point (µm: the
    face's offset of the rigid gap from the first end to the second there) and the 2D pair's
    elastic approach there (µm: its rotation past the first touch times the gap's rate with
    the turn)."""
    mean = sections.solution.pressure @ sections.coupling.share
    tooth = int(np.argmax(sections.line_loads @ sections.coupling.share))
    on = np.flatnonzero(sections.grid == tooth)
    i = on[int(np.argmax(mean[on]))]
    offsets = sections.offsets[i]
    approach = abs(sections.rate[i]) * (sol.rotation - sol.first_touch) * 1e3
    return float(1e3 * (offsets[-1] - offsets[0])), float(approach)

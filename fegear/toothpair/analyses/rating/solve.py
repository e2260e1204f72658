"""A load spectrum's levels solved (``fegear solve --spectrum``, docs/rating.md): each level's
torque, times the application and dynamic factors, at the job's positions on the model kept
from the solve before it (the contact is nonlinear in the load: every level is solved, none
scaled; at each position the lighter levels on the heavier one's contact, the job's way:
:func:`~.positions.drive_torques`), each tooth's largest stresses over the positions, and the
pair rated for its life (:func:`fegear.rating.rate`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import replace
from typing import TYPE_CHECKING

from .... import progress
from ....quantities import LEVEL_STRESSES
from ....running import SERIAL, Executor
from ...case import PairSolution, SolveCase

if TYPE_CHECKING:   # the job's input, which the job hands over: the analyses never import it
    from ...job import Rating


def solve_levels(case: SolveCase, betas, rating: Rating, solve, executor: Executor = SERIAL,
                 cycle: tuple[PairSolution, ...] | None = None
                 ) -> list[tuple[PairSolution, ...]]:
    """Each level of ``rating``'s spectrum at the rolling angles ``betas``, by level:
    ``solve(case, betas, torques, executor)`` (the job's own way of solving its positions
    at several torques, its model kept) at the levels' torques times KA·KV. A level whose
    torque is ``case``'s is ``cycle``, the job's own solve at ``betas`` where given: the
    same numbers in the rating as in the static verdict, and a solve fewer."""
    torques = [level.torque * rating.KA * rating.KV for level in rating.spectrum.levels]
    same = [cycle is not None and math.isclose(t, case.torque, rel_tol=1e-12)
            for t in torques]
    others = [t for t, s in zip(torques, same) if not s]
    progress.stage(f"spectrum: {len(torques)} levels, "
                   + ", ".join(f"{t:.4g}" for t in torques) + " N·m"
                   + (" (the cycle's own torque taken from it)" if any(same) else ""))
    solved = iter(solve(case, betas, others, executor) if others else ())
    return [cycle if s else next(solved) for s in same]


def across_face(job, model) -> Callable:
    """The job's way of solving its positions at several torques across its face
    (:func:`solve_levels`' ``solve``), on ``model``: the torques by families, as in the plane
    (:func:`~...positions.families`), a drive across the face a family
    (:func:`~...face_drive.drive_across`): its heaviest placed and kept at each position, the
    lighter ones solved across the face on that contact; each position's tooth stresses at
    their worst sections (:func:`tooth_stresses` over its sections' pairs)."""
    from ...face_drive import coupling_of, drive_across  # lazy: heavy: scikit-fem
    from ...positions import families  # lazy: heavy: scipy
    every_tooth = same_teeth(job)
    coupling = coupling_of(job.case, job.face)   # the same at every torque

    def level(case: SolveCase, betas, torques, executor: Executor) -> list[list[dict]]:
        out: list = [None] * len(torques)
        for family in families(torques):
            head = replace(job, case=replace(case, torque=torques[family[0]]), betas=betas)
            taken = drive_across(head, lambda sol, by_torque: [
                tooth_stresses(sections.sections, every_tooth) for sections in by_torque],
                coupling, executor, model, lighter=[torques[k] for k in family[1:]])[2]
            for j, k in enumerate(family):
                out[k] = [tables[j] for tables in taken]
        return out

    return level


def level_stresses(job, levels: list) -> list[dict[str, dict]]:
    """Each level's tooth stresses: a 2D level's over its positions' solutions, a level across
    the face over its positions' tables (:func:`across_face`)."""
    if job.face is None:
        return [tooth_stresses(sols, same_teeth(job)) for sols in levels]
    return [merged(tables) for tables in levels]


def same_teeth(job) -> bool:
    """Whether every tooth of a gear passes every place a tooth is seen at over the job's
    positions (:func:`tooth_stresses`): a pair without a tooth of its own deviations, in the
    plane or across the face."""
    return not job.case.deviations and not (job.face is not None and job.face.uneven_teeth)


def tooth_stresses(sols: tuple[PairSolution, ...], every_tooth: bool) -> dict[str, dict]:
    """Each tooth's largest stresses over ``sols`` (MPa), by key
    (:data:`~fegear.quantities.LEVEL_STRESSES`): ``root1`` and ``flank1`` by gear-1 tooth,
    ``root2`` and ``flank2`` by gear-2 tooth (where the tooth it presses on is known).
    ``every_tooth``: the positions of a perfect pair within a pitch, where each tooth passes
    every place a tooth is seen at: one value for every tooth of a gear, tooth None."""
    out: dict[str, dict] = {key: {} for key in LEVEL_STRESSES}
    for sol in sols:
        for t in sol.teeth:
            if t.load_N <= 0:
                continue
            for key, (q, gear) in LEVEL_STRESSES.items():
                tooth = t.tooth if gear == 1 else t.tooth2
                if tooth is not None:
                    _keep(out[key], None if every_tooth else tooth, getattr(t, q.attribute))
    return out


def merged(tables: list[dict[str, dict]]) -> dict[str, dict]:
    """Each tooth's largest stresses over ``tables`` (:func:`tooth_stresses`' tables: a
    position's across the face each, say), by key."""
    out: dict[str, dict] = {key: {} for key in LEVEL_STRESSES}
    for table in tables:
        for key, teeth in table.items():
            for tooth, value in teeth.items():
                _keep(out[key], tooth, value)
    return out


def rated(stresses: list[dict[str, dict]], rating: Rating, z: tuple[int, int],
          every_tooth: bool) -> dict:
    """The summary's ``rating``: the inputs, each level's torque, cycles and largest stresses
    (``stresses``: each level's tooth stresses, :func:`tooth_stresses`), and the four modes
    rated on gears of ``z`` teeth (:func:`fegear.rating.rate`)."""
    from ....rating import rate  # lazy: heavy: scipy, which a refused input must not load
    cycles = [level.cycles for level in rating.spectrum.levels]
    out = rate(stresses, cycles, z, rating.material, rating.hours)
    rows = []
    for level, s in zip(rating.spectrum.levels, stresses):
        rows.append({"torque_Nm": level.torque,
                     "solved_torque_Nm": level.torque * rating.KA * rating.KV,
                     "cycles": level.cycles,
                     **{f"{key}_MPa": max(s[key].values(), default=0.0) for key in s}})
    m = rating.material
    material = {"name": m.name, "treatment": m.treatment, "sigma_Hlim_MPa": m.sigma_Hlim,
                "sigma_FE_MPa": m.sigma_FE, "source": m.source}
    return json_ready({"material": material, "KA": rating.KA, "KV": rating.KV,
                       "speed_rpm": rating.speed_rpm, "every_tooth": every_tooth,
                       "levels": rows, **out})


def json_ready(value):
    """``value`` with every infinite float as the string "inf" (JSON has no infinity: an
    unlimited life, a damage that breaks a tooth at once)."""
    if isinstance(value, dict):
        return {k: json_ready(v) for k, v in value.items()}
    if isinstance(value, list):
        return [json_ready(v) for v in value]
    if isinstance(value, float) and math.isinf(value):
        return "inf"
    return value


def _keep(table: dict, tooth, value: float) -> None:
    if math.isfinite(value):
        table[tooth] = max(table.get(tooth, 0.0), value)

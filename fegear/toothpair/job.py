"""One ``fegear solve`` job: its inputs checked (:func:`prepare_job`), and the solve, the
estimate, the summary and each analysis the job asks for (:func:`solve_job`); the files are
the presentation's (:func:`~.present.output.run_job`, :func:`~.present.output.write_job`).

The command line and the study runner share this module, so a study case is exactly a
``fegear solve`` call: the same inputs under the same names (:data:`~.inputs.JOB_INPUTS`),
the same checks, the same JSON summary. It is the one module of the core that runs the
analyses, and it reaches them only through their registry (:func:`~.analyses.asked`, each
handed a :class:`~.analyses.Run`).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from .. import progress
from ..errors import ParameterError
from ..fe import Allowables, import_libraries
from ..geometry import (
    Helix,
    RoundedProfile,
    admissible_pair,
    default_round,
    gear1_profile,
    read_leads,
    tooth_deviations,
)
from ..rating import material, read_spectrum
from ..running import SERIAL, Executor
from ..timing import Stopwatch
from ..tolerance import Draw
from . import estimate
from .analyses import Run, asked
from .case import SolveCase, cycle_positions, revolution_positions
from .case_file import case_record
from .class_draw import class_draw
from .estimate import second_level_estimate, second_quality, tooth_estimates
from .face import SECTIONS, Face, deepest_lead_um
from .face_room import room_of
from .inputs import FACE_INPUTS, JOB_INPUTS, PAIR_INPUTS, REQUIRES, TIP_ROUND, check_tip_round
from .safety import DEFAULT_ALLOWABLES, allowables_of
from .summary import add_tooth_estimates, cycle_rows, cycle_summary, pair_summary
from .teeth import INTERFERENCE_UM

if TYPE_CHECKING:   # a Rating's parts: a user error answers before scipy loads
    from ..rating import GearMaterial, Spectrum
    from .case import PairSolution

PAIR_NAMES = {row.name for row in PAIR_INPUTS}
#: the positions per pitch of a revolution where none are given
PER_PITCH = 24
#: what a rating solves where neither --positions nor --revolution is given (a tooth's
#: largest stress is over its pass through the mesh, which one pitch's positions cover)
RATING_CYCLE = (f"{PER_PITCH} positions over one pitch, the default cycle for a rating "
                "(--positions N or --revolution sets another)")


@dataclass(frozen=True)
class Rating:
    """What a life rating takes besides the solve (``--spectrum``, solved by
    :mod:`.analyses.rating`): the ``spectrum``, the ``material``, the application and dynamic
    factors (every level's torque is solved times ``KA``·``KV``) and gear 1's ``speed_rpm``
    against gear 2 (None: the life as repeats of the spectrum)."""

    spectrum: Spectrum
    material: GearMaterial
    KA: float = 1.0
    KV: float = 1.0
    speed_rpm: float | None = None
    source: str = ""

    def check(self, case: SolveCase) -> None:
        """Every level's solved torque within what a solve takes, refused by name."""
        limit = case.torque_limit
        for k, level in enumerate(self.spectrum.levels, 1):
            if level.torque * self.KA * self.KV > limit:
                raise ParameterError("spectrum", self.source, f"torques whose KA·KV·torque "
                                     f"is at most {limit:.4g} N·m, the most the pair takes "
                                     f"(level {k}: {level.torque:g} N·m)")

    @property
    def hours(self) -> float | None:
        """The spectrum's duration (h): given, or its revolutions at the speed."""
        if self.spectrum.hours is not None:
            return self.spectrum.hours
        if self.speed_rpm is None:
            return None
        return self.spectrum.cycles / (self.speed_rpm * 60.0)


@dataclass(frozen=True)
class Job:
    """A checked solve: the case, the rolling angles (rad) to solve it at, whether to
    estimate the discretisation error with a second mesh level, the allowable stresses the
    safety factors divide (they change no number of the solve), whether the angles are a
    whole revolution of gear 1 (:mod:`.revolution`), and the pairs of a tolerance class
    solved beside the exact one (``draw``, :mod:`.samples`) with the share of them the
    verdict's safety factors hold for (``quantile``), and whether the headlines' rates with
    the deviations are formed (``sensitivities``, :mod:`.ring.sensitivity`), what varies across
    the face (``face``: solved across it, :mod:`.analyses.face`), and every input by
    name as the job runs it, the derived defaults at their values (``record``:
    :func:`~.case_file.case_record`, what ``--save-case`` writes)."""

    case: SolveCase
    betas: tuple[float, ...]
    estimate: bool
    allowables: Allowables = DEFAULT_ALLOWABLES
    revolution: bool = False
    draw: Draw | None = None
    quantile: float = 0.95
    sensitivities: bool = False
    rating: Rating | None = None
    record: Mapping[str, object] = field(default_factory=dict)
    cycle_default: str | None = None   # what the output says of a cycle it was not given
    face: Face | None = None


def prepare_job(values: Mapping[str, object]) -> Job:
    """Check every input of a solve, given by name (missing ones at their defaults); raises
    :class:`~fegear.errors.ParameterError` or :class:`~fegear.errors.GeometryError`. No
    meshing, no output."""
    v = JOB_INPUTS.with_defaults(values)
    for name, row in JOB_INPUTS.items():   # every static range first: they answer at once
        if name not in PAIR_NAMES and not row.limits:   # those with limits: at the others'
            row.check(v[name])                          # values, by the case they build
    params = admissible_pair(v, given=values)
    v["tip-round"] = tip_round_of(params, v["tip-round"])
    position = JOB_INPUTS["position"].check(v["position"])
    positions = JOB_INPUTS["positions"].check(v["positions"])
    revolution = JOB_INPUTS["revolution"].check(v["revolution"])
    cycle_default = None
    if v["spectrum"] is not None and positions is None and not revolution:
        positions, cycle_default = PER_PITCH, RATING_CYCLE
    n = 1 if positions is None else positions
    deviations, helix = tooth_deviations(v, params.z1, params.z2)
    case = SolveCase(params, torque=v["torque"], beta=math.radians(position),
                     thickness=v["face-width"], E=v["E"], nu=v["nu"], quality=v["quality"],
                     rim1=v["rim1"], rim2=v["rim2"], extra_pairs=v["extra-pairs"],
                     tip_round=v["tip-round"],
                     deviations=deviations)
    if revolution:
        betas = revolution_positions(case.beta, positions or PER_PITCH, params.z1, params.z2)
    else:
        betas = (case.beta,) if n == 1 else cycle_positions(case.beta, n, case.params.z2)
    draw = class_draw(v, given=values, case=case)
    rating = _rating(v, given=values, case=case, revolution=revolution, draw=draw)
    return Job(case, tuple(betas), not v["no-estimate"], allowables_of(v), revolution, draw,
               JOB_INPUTS["quantile"].check(v["quantile"]),
               JOB_INPUTS["sensitivities"].check(v["sensitivities"]), rating,
               case_record(values, _derived(case, len(betas), revolution)),
               cycle_default=cycle_default, face=_face(v, values, case, draw, helix))


def _derived(case: SolveCase, n: int, revolution: bool) -> dict[str, object]:
    """The inputs whose defaults follow from the others (None in the schema), at the values
    ``case`` took, and the positions solved per pitch (``n`` rolling angles in all)."""
    p = case.params
    per_pitch = n // p.z1 if revolution else n
    return {"shift": p.shift, "rotation": p.rotation, "tip-clearance": p.tip_clearance,
            "relief-extent": p.relief_extent if p.relief > 0 else None,
            "tip-round": case.edge_radius, "rim1": case.rims[0], "rim2": case.rims[1],
            "positions": per_pitch if revolution or n > 1 else None}


def _face(v: dict, given: Mapping[str, object], case: SolveCase, draw: Draw | None,
          helix: Helix) -> Face | None:
    """What varies across the face (any of :data:`~.inputs.FACE_INPUTS` given), refused by
    name: an end relief longer than half the face, a crowning and end relief deeper together
    than the tooth takes (:func:`~.face.deepest_lead_um`), or a tooth's own helix
    deviations with a tolerance class (the class draws them); None where none is given."""
    p = case.params
    if all(v[row.name] is None for row in FACE_INPUTS) and not helix:
        return None
    leads = read_leads(v["lead"], p.z1, p.z2, case.thickness) if v["lead"] else Helix()
    if draw is not None and (helix or v["lead"]):   # a class draws its teeth's helix
        name = next((n for n in ("helix-slope-deviation", "helix-form-deviation", "lead")
                     if v[n] is not None), "deviations")
        raise ParameterError(name, v[name], "without --grade (the class draws each tooth's "
                             "helix deviations)")
    for name in ("crowning", "end-relief", "end-length"):   # their values first, then
        JOB_INPUTS[name].check(v[name])                      # whether they are read
    if v["end-length"] is not None and v["end-relief"] is None:
        raise ParameterError("end-length", given.get("end-length"), "with --end-relief only "
                             "(the length of an end relief)")
    length = v["end-length"] if v["end-length"] is not None else 0.2 * case.thickness
    if length > 0.5 * case.thickness:
        raise ParameterError("end-length", length, f"0 < end-length <= half the face width "
                             f"({0.5 * case.thickness:g} mm)")
    depth, deepest = (v["crowning"] or 0.0) + (v["end-relief"] or 0.0), deepest_lead_um(p.m)
    if depth > deepest:
        name = "crowning" if v["crowning"] else "end-relief"
        raise ParameterError(name, v[name], f"crowning + end-relief <= 50 m = {deepest:g} µm "
                             "(the deepest lead modification the tooth takes, as its tip "
                             "relief)")
    face = Face(v["face-sections"] or SECTIONS, v["misalignment"] or 0.0, v["tilt"] or 0.0,
                v["crowning"] or 0.0, v["end-relief"] or 0.0,
                length if v["end-relief"] else 0.0, helix.gear1, helix.gear2,
                leads.gear1, leads.gear2)
    if face.misalignment or face.tilt or face.helix1 or face.helix2 or leads:
        _refuse_jammed(face, v, case)
    return face


def _refuse_jammed(face: Face, v: dict, case: SolveCase) -> None:
    """A face whose inputs close gear 1's loaded flanks at one section and its coast flanks at
    another by more than the pair's backlash jams the pair (:func:`~.face_room.room_of`): refused
    naming the first of its closing inputs given, with the largest value the others leave."""
    room = room_of(face, case)
    if room.um >= -INTERFERENCE_UM:
        return
    name = next(n for n in ("misalignment", "tilt", "helix-slope-deviation",
                            "helix-form-deviation", "lead", "deviations") if v.get(n))
    given = ",".join(v[name]) if isinstance(v[name], (list, tuple)) else v[name]
    if isinstance(given, str) and given.count(",") > 3:   # a tooth each: the first few
        given = ",".join(given.split(",")[:3]) + f",… ({given.count(',') + 1} entries)"
    if name in ("misalignment", "tilt"):
        admissible = (f"|{name}| <= {abs(given) * room.scale:.3g} µm with the face's other "
                      "inputs as given")
    else:
        admissible = (f"helix deviations at most {room.scale:.3g} times as given, with the "
                      "face's other inputs")
    raise ParameterError(name, given, admissible, f"the pair jams at β = "
                         f"{math.degrees(room.beta):.3g}°: gear 1's loaded flanks close at one "
                         f"section of the face and its coast flanks at another, "
                         f"{-room.um:.3g} µm of arc at r0 beyond its backlash")


def _rating(v: dict, given: Mapping[str, object], case: SolveCase, revolution: bool,
            draw: Draw | None) -> Rating | None:
    """The life rating's inputs (``--spectrum``: the file read and every level checked; its
    positions a cycle, :data:`RATING_CYCLE` where none is given), refused by name: the
    rating's options without a spectrum, a deviated pair's over less than a revolution (its
    teeth differ: each is rated over its whole pass) or with a tolerance class; None without
    a spectrum."""
    path = v["spectrum"]
    if path is None:
        for name in (name for name, switch in REQUIRES.items() if switch == "spectrum"):
            if given.get(name) is not None:
                raise ParameterError(name, given[name], "with --spectrum only (the options "
                                     "of a life rating)")
        return None
    if case.deviations and not revolution:
        raise ParameterError("spectrum", path, "with --revolution for a pair with deviations "
                             "(its teeth differ: each is rated over its whole pass)")
    if draw is not None:
        raise ParameterError("spectrum", path, "without --grade (a class's life rating is "
                             "not built)")
    speed = JOB_INPUTS["speed"].check(v["speed"])
    life = JOB_INPUTS["life"].check(v["life"])
    rating = Rating(read_spectrum(path, speed, life), material(v["material"]),
                    JOB_INPUTS["KA"].check(v["KA"]), JOB_INPUTS["KV"].check(v["KV"]), speed,
                    str(path))
    rating.check(case)
    return rating


def tip_round_of(params, given: float | None) -> float | None:
    """The tip round a solve takes: the one given, refused by name with the largest that fits
    if it does not; else the default :data:`~.inputs.TIP_ROUND` m, or half the largest that
    fits where that does not (``None``: the default as it is)."""
    nominal = TIP_ROUND * params.m
    profile = gear1_profile(params)          # built by the admissibility check, kept
    if given is not None:
        if check_tip_round(given, params.m) > 0:
            RoundedProfile(profile, given)   # a round that does not fit is refused by name
        return given
    chosen = default_round(profile, nominal)
    return None if chosen == nominal else chosen


@dataclass(frozen=True)
class Solved:
    """A solved job before any file is written: the solutions at every position, the one the
    pictures, VTUs and the error estimate take (the largest gear-1 root stress), the JSON
    summary (``fegear solve --json``), the cycle rows (None for one position), the time of
    the solve (s) and what the analysis that drove the positions kept for its files (None
    where none did)."""

    job: Job
    solutions: tuple
    solution: object
    summary: dict
    rows: list[dict] | None
    solve_s: float
    driven: object = None


def solve_job(job: Job, executor: Executor = SERIAL,
              meanwhile: Callable[[PairSolution, dict], object] | None = None) -> Solved:
    """Solve ``job`` at its positions, with its error estimate, then each analysis it asks
    for (:mod:`.analyses`); no file written. The job hands ``executor`` the work that can run
    in parallel: the estimate's second solve of one position (submitted before the first
    starts: on a one-off command's second core it is solved in a forked copy of this process
    meanwhile, the libraries imported once for both), and a cycle's chains of positions
    (:func:`~.positions.drive`), and a cycle's estimate, at its worst position (the largest
    gear-1 root stress, which the submodels do not change), while this process solves the
    submodels where the cycle peaks. ``meanwhile(solution, summary)`` is called once the
    pictured position is solved, before its submodels are: the position and its summary
    without the estimate, for what the caller can start from them while this process solves
    the submodels (a one-off command's charts, on its second core)."""
    watch = Stopwatch()
    second = None
    if job.estimate and len(job.betas) == 1:
        import_libraries()
        second = executor.submit(estimate.second_headline, job.case)
    progress.stage("gear 1's profile")
    gear1_profile(job.case.params)
    analyses = asked(job)
    solver, sols, driven = _drive(job, analyses, executor)
    sols = solver.with_pictured(sols)
    if job.estimate and len(job.betas) > 1:   # while the peaks' submodels are solved here
        second = executor.submit(estimate.second_headline, _pictured(sols).case)
    if meanwhile is not None:
        early = _pictured(sols)
        meanwhile(early, pair_summary(early, allowables=job.allowables))
    sols = solver.at_peaks(sols)
    cycle_s = watch.s
    sol = _pictured(sols)
    summary = _core_summary(job, sols, sol, second, watch)
    rows = None
    if len(sols) > 1:
        rows = cycle_rows(sols, job.allowables)
        summary["cycle"] = {"positions": len(sols), "solve_s": cycle_s,
                            **cycle_summary(rows), "rows": rows}
        if job.cycle_default:
            summary["cycle"]["default"] = job.cycle_default
    run = Run(job, solver, tuple(sols), sol, executor, summary, driven)
    for analysis in analyses:
        entry = analysis.solve(run)
        if entry is not None:
            summary[analysis.key] = entry
    return Solved(job, tuple(sols), sol, summary, rows, watch.s, driven)


def _drive(job: Job, analyses, executor: Executor):
    """The positions solved: by the analysis that drives them (a class's samples), else by
    the one driver; ``(solver, solutions, what the driving analysis kept)``."""
    from .positions import positions_of  # lazy: heavy: scipy
    from .ring.solver import RingSolver, SolverModes  # lazy: heavy: scikit-fem

    for analysis in analyses:
        driven = analysis.drive(job, executor)
        if driven is not None:
            return driven
    solver = RingSolver(None, SolverModes(keep_phases=job.revolution, read_kept=job.revolution))
    return solver, positions_of(solver, job.revolution)(job.case, job.betas, executor), None


def _core_summary(job: Job, sols, sol, second, watch: Stopwatch) -> dict:
    """The pictured position's summary (:func:`~.report.pair_summary`) with the error
    estimate of the second mesh level (``second``: its future; None without an estimate)
    and every input as run."""
    errors, other, estimate_s, teeth = None, None, None, None
    if second is not None:
        after = Stopwatch()
        progress.stage("error estimate: the same case again at quality "
                       f"{second_quality(job.case.quality)}")
        with progress.reporting(None):  # one stage, however the second solve goes
            again = second.result()     # a SecondSolve
            errors, other = second_level_estimate(sol, second=again.headline)
            teeth = tooth_estimates(sol, again.teeth)
        estimate_s = after.s
    summary = pair_summary(sol, errors, watch.s, other, job.allowables)
    summary["estimate_s"] = estimate_s
    summary["case"] = dict(job.record)
    add_tooth_estimates(summary, teeth)
    return summary


def solve_command(inputs: Mapping) -> str:
    """The ``fegear solve`` line of ``inputs`` (by name): what gives their numbers again."""
    import shlex

    parts = ["fegear", "solve"]
    for k, v in inputs.items():
        if v is None or v is False:
            continue
        parts += [f"--{k}"] if v is True else [f"--{k}", f"{v:.6g}" if isinstance(v, float)
                                              else str(v)]
    return shlex.join(parts)


def _pictured(sols):
    """The position the pictures, VTUs and the error estimate are of: the largest gear-1 root
    stress (which a position's submodels do not change)."""
    return max(sols, key=lambda s: s.root_stress[0])

"""One design of a search: the worst of its headline stresses over a mesh cycle (across the
face where the search gives a misalignment or varies a crowning: each at its worst section),
its safety factors and what limits them, and how far it is from each constraint.

A design the solve refuses (outside the admissible region: the pair cannot be built) or
cannot solve (its contact does not settle) is not an error here: it comes back with its
reason and a violation of the ``buildable`` constraint, so that the sampler learns where the
admissible region ends (a trial that raises is FAILED and teaches it nothing).
"""

from __future__ import annotations

import math
from collections.abc import Mapping

from ..errors import FegearError
from ..quantities import FACTORS, HELD, QUANTITIES
from ..timing import Stopwatch
from ..toothpair import JOB_INPUTS

#: the safety factors the default objective takes the smallest of, each under its name in a
#: trial's record (:attr:`~fegear.quantities.Factor.name`): S_F of each gear from its root
#: σ1, S_H from the flank pressure (a load on a tip round is a constraint of its own)
LIMITS = {f.name: f for f in (FACTORS[k] for k in ("safety_bending_gear1",
                                                   "safety_bending_gear2",
                                                   "safety_contact_flank"))}
#: what a design is measured by, and which way is better
OBJECTIVES = {"safety": "maximize", "te": "minimize", "stiffness": "maximize"}


def outer_diameter(values: Mapping) -> float:
    """Gear 2's outer diameter (mm): its root circle r0 + 2 e1 and the rim beyond it
    (``rim2``, default 3 m), the size the pair takes in a housing."""
    v = JOB_INPUTS.with_defaults(values)
    m, z2, h1 = float(v["m"]), int(v["z2"]), float(v["h1"])
    rim2 = v["rim2"]
    rim2 = 3.0 * m if rim2 is None else float(rim2)
    return 2.0 * (0.5 * m * z2 + 2.0 * m * h1 + rim2)


def centre_distance(values: Mapping) -> float:
    """The pair's centre distance e = m (z2 − z1) / 2 (mm): with the ratio fixed, the module's
    size."""
    v = JOB_INPUTS.with_defaults(values)
    return 0.5 * float(v["m"]) * (int(v["z2"]) - int(v["z1"]))


def evaluate(values: Mapping, positions: int, constraints: Mapping,
             bar: float | None = None) -> dict:
    """Solve ``values`` (``fegear solve`` inputs by name) over ``positions`` rolling angles
    and measure it against ``constraints`` (``max_outer_diameter`` and ``max_centre_distance``
    mm, ``min_backlash``/``max_backlash`` µm, each optional); ``bar``: on a class's pairs, the
    objective the design must reach to be kept (:mod:`.bar`; None: none). Returns a flat
    record: ``status`` (``ok``, ``refused``, ``failed``, or ``pruned`` where its pairs showed
    it below the bar), ``reason``, the worst headline stresses over the cycle with the
    rolling angle (°) and tooth of each, the safety factors, ``objective_*``, the constraint
    values (``violation_*``, > 0 violated) and the solve's time."""
    from ..toothpair import (  # lazy: heavy: numpy; `fegear --help` imports this module
        allowables_of,
        prepare_job,
        solve_job_positions,
    )

    watch = Stopwatch()
    rec: dict = {"status": "ok", "reason": ""}
    rec["outer_diameter_mm"] = outer_diameter(values)
    over = constraints.get("max_outer_diameter")
    rec["violation_outer_diameter"] = (rec["outer_diameter_mm"] - over) if over else 0.0
    rec["centre_distance_mm"] = centre_distance(values)
    far = constraints.get("max_centre_distance")
    rec["violation_centre_distance"] = (rec["centre_distance_mm"] - far) if far else 0.0
    try:
        job = prepare_job({**values, "positions": positions, "no-estimate": True})
    except FegearError as exc:       # outside the admissible region, named (ParameterError)
        return _infeasible(rec, "refused", str(exc), watch)
    # the force the torque puts on gear 1's pitch circle: what a load on the rounds is read
    # against (:func:`~.search.sampler_violation`)
    rec["pitch_force_N"] = 1000.0 * job.case.torque / job.case.params.r1
    if constraints.get("min_backlash") is not None or constraints.get("max_backlash") is not None:
        from ..geometry import (  # lazy: heavy: numpy; `fegear --help` imports this module
            ToothContact,
            gear1_profile,
        )

        b = ToothContact(job.case.params, gear1_profile(job.case.params)).backlash()
        rec["backlash_um"] = b.plus_um + b.minus_um
        lo, hi = constraints.get("min_backlash"), constraints.get("max_backlash")
        rec["violation_backlash"] = max(0.0 if lo is None else lo - rec["backlash_um"],
                                        0.0 if hi is None else rec["backlash_um"] - hi)
    try:
        # the objective reads root stresses and contact pressures: no contact submodels
        sols, worst = (_across(job) if job.face is not None else
                       (solve_job_positions(job, submodels="none"), None))
    except FegearError as exc:
        return _infeasible(rec, "failed", str(exc), watch)
    allow = allowables_of(values)
    for key in (q.key for q in HELD):
        if worst is None:   # the 2D pair's largest over the positions
            i = max(range(len(sols)), key=lambda k: sols[k].headline()[key])
            rec[key] = sols[i].headline()[key]
        else:   # across the face: the worst section's, at its position
            i = min(range(len(sols)), key=lambda k: abs(math.degrees(sols[k].case.beta)
                                                        - worst[key]["position_deg"]))
            rec[key] = worst[key]["value"]
        rec[key.replace("_MPa", "_beta_deg")] = math.degrees(sols[i].case.beta)
        rec[key.replace("_MPa", "_tooth")] = carrying_tooth(sols[i], key)
    if worst is not None:
        rec["K_Hbeta"] = worst["K_Hbeta"]
    for name, f in LIMITS.items():
        stress = rec[f.stress.key]
        rec[name] = getattr(allow, f.stress.allowable) / stress if stress > 0 else math.inf
    rec["S_H"] = allow.contact / rec["contact_pressure_MPa"]
    limit = min(LIMITS, key=lambda n: rec[n])
    rec["limited_by"] = limit
    edge = max(sum(t.edge_load_N for t in s.teeth) for s in sols)
    rec["edge_load_N"] = edge
    rec["violation_edge_load"] = edge          # any load on a tip round violates
    te = [1e6 * (s.rotation - s.first_touch) for s in sols]
    rec["te_p2p_urad"] = max(te) - min(te)
    rec["stiffness_Nm_per_rad"] = sum(s.mesh_stiffness for s in sols) / len(sols)
    rec["objective_safety"] = rec[limit]
    if job.draw is not None:   # a class's pairs: the factors their quantile meets decide
        try:
            rec.update(_graded(job, allow, bar))
        except FegearError as exc:
            return _infeasible(rec, "failed", str(exc), watch)
    rec["objective_te"] = rec["te_p2p_urad"]
    rec["objective_stiffness"] = rec["stiffness_Nm_per_rad"]
    rec["violation_buildable"] = 0.0
    rec["time_s"] = watch.s
    return rec


def _across(job) -> tuple[tuple, dict]:
    """A design solved across the face (a search with a misalignment or a crowning: docs/
    optimize.md): its 2D solutions at the positions, and each headline at its worst section
    over them with that position (``summary["face"]["worst"]``) and K_Hβ."""
    from ..toothpair import solve_job  # lazy: heavy: scikit-fem

    solved = solve_job(job)
    face = solved.summary["face"]
    return solved.solutions, {**face["worst"], "K_Hbeta": face["K_Hbeta"]}


def _graded(job, allow, bar: float | None = None) -> dict:
    """A design measured on a tolerance class's pairs (``job.draw``, the same pairs for every
    design of a search: common random numbers): each limiting factor at the ``job.quantile``
    of the pairs (0 where more of them jam), the smallest the objective; the jam constraint
    violated where more of the pairs jam than the quantile leaves (by the share beyond it:
    the design cannot be built to turn at that class), and the tip rounds' constraint where
    more of the pairs that turn load a round (by the largest such load, N). Its pairs are
    not solved where too many jam, and solved no further once too many have loaded a round
    (the constraint is broken whatever the rest give), nor once they bound its objective
    below ``bar`` (:class:`~.bar.Beaten`: ``status`` "pruned", that bound in
    ``objective_bound``; not across the face). The factors are then not known (None), the
    objective 0 (pruned: None), and the shares and load are those it saw (a sampler ranks a
    design that breaks a constraint by how far, not by its objective)."""
    import numpy as np  # lazy: heavy: `fegear --help` imports this module

    from ..toothpair import (  # lazy: heavy: scikit-fem; `fegear --help` imports this module
        ClassReading,
        class_samples,
        cycle_rows,
        samples_summary,
    )
    from .bar import Beaten, bound_of  # lazy: heavy: the samples' Enough

    draw, q = job.draw, job.quantile
    allowable = np.array([getattr(allow, f.stress.allowable) for f in LIMITS.values()])
    # across the face a pair's worst sections decide, which its reading (the 2D pair's) does
    # not bound: no bar there
    bar = bar if job.face is None else None
    sampled = class_samples(job, allow, read=_reading, enough=Beaten(q, allowable, bar))
    turning = sampled.turning
    loads = [max(r[0] for r in sampled.readings.get(k, [(0.0,)])) for k in turning]
    loaded = [x for x in loads if x > 0]
    out = {"edge_share": len(loaded) / max(len(turning), 1),
           "jammed_share": sampled.jammed_share,
           "violation_jam": sampled.jammed_share - (1.0 - q)}
    out["violation_edge_load"] = (max(loaded) if out["edge_share"] > 1.0 - q else 0.0)
    if sampled.stopped:
        out.update({"objective_safety": 0.0, **{f"{n}_P{100 * q:g}": None for n in LIMITS}})
        jammed = round(sampled.jammed_share * draw.count)
        if out["violation_jam"] > 0:
            out["reason"] = (f"{jammed} of its {draw.count} pairs jam, more than the "
                             f"{100 * (1.0 - q):g} % the quantile leaves: its pairs not solved")
        elif out["violation_edge_load"] > 0:
            out["reason"] = (f"its pairs solved no further once {len(loaded)} of the "
                             f"{len(turning)} that turn had loaded a tip round")
        else:
            bound = bound_of(sampled.readings, turning, jammed, q, allowable)
            out.update(status="pruned", objective_bound=bound, objective_safety=None,
                       reason=f"its pairs solved no further once they put its objective at "
                              f"{bound:.3g} at most, below {bar:.3g}, the last of the best "
                              "designs kept")
        return out
    summary = samples_summary(sampled.rows, cycle_rows(sampled.nominal, allow),
                              ClassReading(draw=draw, quantile=q, allowables=allow))
    for name, f in LIMITS.items():
        out[f"{name}_P{100 * q:g}"] = summary["safety"][f.key]["at_quantile"] or 0.0
    out["objective_safety"] = min(out[f"{n}_P{100 * q:g}"] for n in LIMITS)
    return out


def _reading(sol) -> tuple:
    """What a design's class reads of a pair's solution at a position: the load on its tip
    rounds (N) and each limiting factor's stress (MPa, :data:`LIMITS`' order)."""
    import numpy as np  # lazy: heavy: `fegear --help` imports this module

    head = sol.headline()
    return (sum(t.edge_load_N for t in sol.teeth),
            np.array([head[f.stress.key] for f in LIMITS.values()]))


def carrying_tooth(sol, key: str) -> int:
    """The gear-1 tooth of the position ``sol`` that carries the headline stress ``key``."""
    attr = QUANTITIES[key].attribute
    return max(sol.teeth, key=lambda t: getattr(t, attr) or 0.0).tooth


def _infeasible(rec: dict, status: str, reason: str, watch: Stopwatch) -> dict:
    """A design that could not be built or solved: the ``buildable`` constraint violated
    (``watch``: started with the design's evaluation)."""
    rec.update(status=status, reason=reason, violation_buildable=1.0,
               violation_edge_load=0.0, time_s=watch.s)
    return rec

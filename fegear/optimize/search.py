"""The design search: Optuna asks for designs, a local pool of worker processes solves each
over a mesh cycle (:func:`~.design.evaluate`), and the answers go back as objective values
and constraint values.

* **Constraints, not exceptions.** A design the solve refuses or cannot solve, one whose
  tolerance class jams in more pairs than its quantile leaves, one that loads a tip round,
  one too large for its housing or outside its backlash bounds comes back with
  its constraint values > 0 (Optuna's ``constraints_func``): the sampler learns where the
  feasible region ends. A trial that raised would be FAILED and teach it nothing.
* **A journal that survives a kill.** Trials are stored in Optuna's journal file
  (``search.journal``, one file several processes can append to; SQLite is fragile with
  several writers). Only this process writes it: it asks, the workers solve, it tells. A
  stop by SIGTERM or Ctrl-C finishes no trial half-way: the trials under way are marked
  failed and queued again with the same design. So are those a killed worker (or a killed
  search, SIGKILL, found RUNNING at the next start) leaves behind. The queued copy keeps
  why (``cut_by``), and the trials table says it for both: the one cut short and its copy.
  A search started again on the same directory resumes: finished trials count toward its
  budget and are never solved again, queued ones are solved first.
* **Cheap levels first.** Trials are screened at ``coarse``; the best are solved again at
  ``standard`` with the error estimate (:mod:`.report`).
* **A design that cannot be kept is not finished.** On a class's pairs, with the safety
  factor the one objective, a trial is given the objective of the last of the ``keep`` best
  feasible designs so far (the bar) and ends once its pairs bound its own below it
  (:mod:`.bar`): Optuna's PRUNED, with that bound as its last intermediate value.
"""

from __future__ import annotations

import json
import math
import signal
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from ..errors import FegearError
from ..files import write_csv, write_json
from ..running import Supervisor, WorkerFailed, connect
from ..timing import Stopwatch
from .design import OBJECTIVES, evaluate
from .space import SAMPLERS, Space

STUDY = "fegear-optimize"
JOURNAL = "search.journal"
#: the constraints every trial reports (> 0: violated), in this order
CONSTRAINTS = ("buildable", "jam", "edge_load", "outer_diameter", "centre_distance",
               "backlash")
STARTUP = 40    # trials spread by a scrambled Sobol sequence before TPE models the objective
                # (with TPE's own 10 random ones, its median best over three seeds did not
                # beat a random search's: docs/optimize.md)


class SearchInterrupted(FegearError):
    """SIGTERM or SIGINT stopped the search; its finished trials are in the journal."""

    def __init__(self, signum: int, done: int, total: int) -> None:
        self.signum = signum
        name = signal.Signals(signum).name
        super().__init__(f"stopped by {name} after {done} of {total} trials; the trials under "
                         "way were queued again: run the same command to resume")


@dataclass(frozen=True)
class SearchReport:
    """A finished search: its directory, the Optuna study, the trials table, how many trials
    were found finished and how many were solved now, and its wall time (s)."""

    out: Path
    study: object
    table: Path
    found: int
    solved: int
    wall_s: float


def _constraints(trial) -> list[float]:
    """A finished trial's constraint values as the sampler has them, in :data:`CONSTRAINTS`'
    order (> 0: violated; :func:`sampler_violation`)."""
    return [float(trial.constraints.get(c, 1.0)) for c in CONSTRAINTS]


def _violations(trial) -> list[float | None]:
    """A finished trial's constraint values in their own units, as its record has them
    (``violation_*``), in :data:`CONSTRAINTS`' order; the sampler's where the record has
    none (a trial of an older search)."""
    return [trial.user_attrs.get(f"violation_{c}", v)
            for c, v in zip(CONSTRAINTS, _constraints(trial))]


def sampler_violation(rec: dict, c: str, constraints: dict) -> float:
    """Constraint ``c``'s value of the record ``rec`` (``violation_c``, > 0 violated) on the
    scale the sampler ranks infeasible designs by, the sum of their violations: each as a
    share of what it is measured against, so that none outweighs the others by its unit. A
    load on the rounds (N) as a share of the force the torque puts on gear 1's pitch circle
    (``pitch_force_N``), a size over its bound (mm, µm) as a share of that bound; the jammed
    share beyond the quantile and ``buildable`` (1) as they are."""
    v = float(rec.get(f"violation_{c}", 0.0))
    if c == "edge_load":
        return v / rec["pitch_force_N"] if "pitch_force_N" in rec else v
    if c in ("outer_diameter", "centre_distance"):
        bound = constraints.get(f"max_{c}")
        return v / bound if bound else v
    if c == "backlash":
        lo, hi = constraints.get("min_backlash"), constraints.get("max_backlash")
        below = lo is not None and rec.get("backlash_um", lo) < lo
        bound = lo if below else hi
        return v / bound if bound else v
    return v


def _sampler(kind: str, seed: int, objectives: int):
    """The samplers of the search's first :data:`STARTUP` trials and of the rest."""
    import warnings

    import optuna

    # QMC is marked experimental in Optuna 5; its scrambled Sobol points are what is used
    warnings.filterwarnings("ignore", category=optuna.exceptions.ExperimentalWarning)

    if kind not in SAMPLERS:
        raise FegearError(f"unknown sampler {kind!r}: one of {', '.join(SAMPLERS)}")
    if kind == "random":
        return optuna.samplers.RandomSampler(seed=seed), optuna.samplers.RandomSampler(seed=seed)
    # constraints reach TPE through each trial's set_constraint (Optuna 5's way)
    return (optuna.samplers.QMCSampler(qmc_type="sobol", scramble=True, seed=seed,
                                       warn_asynchronous_seeding=False),
            optuna.samplers.TPESampler(seed=seed, n_startup_trials=STARTUP, multivariate=True))


def open_study(space: Space, out: Path, sampler: str = "tpe", seed: int = 0):
    """The search's Optuna study in ``out`` (made if new; resumed if it holds the same search,
    refused if it holds another)."""
    import optuna
    from optuna.storages import JournalStorage
    from optuna.storages.journal import JournalFileBackend

    optuna.logging.set_verbosity(optuna.logging.WARNING)
    storage = JournalStorage(JournalFileBackend(str(out / JOURNAL)))
    study = optuna.create_study(
        study_name=STUDY, storage=storage, load_if_exists=True,
        directions=[OBJECTIVES[o] for o in space.objectives])

    settings = {**space.settings(), "sampler": sampler, "seed": seed}
    kept = study.user_attrs.get("settings")
    if kept is None:
        study.set_user_attr("settings", json.loads(json.dumps(settings)))
    elif kept != json.loads(json.dumps(settings)):
        differ = sorted(k for k in settings if kept.get(k) != json.loads(json.dumps(settings[k])))
        raise FegearError(f"{out} holds a search with other settings ({', '.join(differ)}): "
                          "give a new --out, or the same settings to resume it")
    return study


def run_search(space: Space, out: Path, trials: int, workers: int = 2, sampler: str = "tpe",
               seed: int = 0, report: Callable[[str], None] | None = None,
               scheduler: str | None = None, keep: int = 3) -> SearchReport:
    """Search ``space`` for ``trials`` finished trials in all (those of an earlier run in
    ``out`` included) on ``workers`` local processes, or on the Dask cluster whose scheduler
    is at ``scheduler`` (as many at once as it has worker threads; its workers need fegear
    installed); the trials table is written at the end and at a stop. ``report`` is told
    after each trial (a line: done, best, time left); ``keep``: the best designs the caller
    reads, which a trial on a class's pairs must be able to join (module docstring)."""
    from optuna.trial import TrialState

    watch = Stopwatch()
    client = connect(scheduler) if scheduler else None
    if client is not None:
        workers = max(1, sum(client.nthreads().values()))
    study = open_study(space, out, sampler, seed)
    # a resumed search's samplers are seeded past its trials (seeded as at its start, they
    # drew the first designs again)
    stages = _sampler(sampler, seed + len(study.get_trials(deepcopy=False)),
                      len(space.objectives))
    stale = study.get_trials(deepcopy=False, states=(TrialState.RUNNING,))
    for t in stale:                      # a search killed outright left these running
        _requeue(study, t.number, _whole_design(study, space, t),
                 "the search ended while it ran (killed outright)")
    found = sum(t.state.name in FINISHED for t in study.get_trials(deepcopy=False))
    done, solved, stop = found, 0, None
    running: dict[str, tuple] = {}     # a trial's task → the trial and its design
    try:
        # a worker's death cuts short every trial under way: each is queued again as a new
        # trial (retries=0), which the trials table tells as cut
        with Supervisor(workers, client) as tasks:
            while (done < trials or running) and not tasks.stopped:
                while (len(running) < workers and done + len(running) < trials
                       and not tasks.stopped):
                    startup = len(study.get_trials(deepcopy=False)) < STARTUP
                    study.sampler = stages[0 if startup else 1]
                    trial = study.ask()
                    params = {v.name: trial.suggest_float(v.name, v.low, v.high)
                              for v in space.variables}
                    name = f"trial {trial.number}"
                    running[name] = (trial, params)
                    tasks.submit(name, evaluate, space.values(params), space.positions,
                                 dict(space.constraints), bar_of(study, space, keep))
                for o in tasks.ended():
                    trial, params = running.pop(o.name)
                    if o.lost is not None:
                        why = ("a worker process of the pool died"
                               if isinstance(o.lost, WorkerFailed)
                               else f"the cluster lost it ({type(o.lost).__name__})")
                        _requeue(study, trial.number, params, why)
                        continue
                    _tell(study, trial, o.value, space)
                    done += 1
                    solved += 1
                    if report:
                        report(_progress(study, space, done, trials, solved, watch.s))
            stop = tasks.stopped
            if stop:
                for t, p in running.values():
                    _requeue(study, t.number, p, f"stopped by {signal.Signals(stop).name}")
                running.clear()
    finally:
        if client is not None:
            client.close()
        table = write_trials(study, space, out)
    if stop:
        raise SearchInterrupted(stop, done, trials)
    return SearchReport(out, study, table, found, solved, watch.s)


def _whole_design(study, space: Space, t) -> dict:
    """The design of ``t``, a trial a kill left running, every variable drawn: a kill between
    its variables' draws (each a line of the journal) left some undrawn, and the trial, never
    solved, is drawn whole now, so that the copy queued again solves its design."""
    params = dict(t.params)
    missing = [v for v in space.variables if v.name not in params]
    if missing:
        from optuna.trial import Trial

        live = Trial(study, t._trial_id)   # Optuna names a trial in its storage by this id
        params.update({v.name: live.suggest_float(v.name, v.low, v.high) for v in missing})
    return params


def _requeue(study, number: int, params: dict, why: str) -> None:
    """Mark trial ``number`` failed (it did not finish) and queue its design again; the copy
    keeps which trial it redoes and ``why`` that one was cut short."""
    from optuna.trial import TrialState

    study.tell(number, state=TrialState.FAIL)
    study.enqueue_trial(params, user_attrs={"requeued_from": number, "cut_by": why})


def _clean(value):
    """A record's value as JSON takes it (inf and NaN as None)."""
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def bar_of(study, space: Space, keep: int) -> float | None:
    """The objective a new trial must reach to join the ``keep`` best feasible designs so
    far, where the search prunes (a class's pairs, the safety factor its one objective); None
    before there are that many, or where it does not."""
    if tuple(space.objectives) != ("safety",) or space.fixed.get("grade") is None:
        return None
    best = best_trials(study, space, keep)
    return best[-1].values[0] if len(best) == keep else None


def _tell(study, trial, rec: dict, space: Space) -> None:
    from optuna.trial import TrialState

    for k, v in rec.items():
        trial.set_user_attr(k, _clean(v))
    for c in CONSTRAINTS:
        trial.set_constraint(c, sampler_violation(rec, c, space.constraints))
    if rec.get("status") == "pruned":   # its bound, as Optuna keeps a pruned trial's value
        trial.report(rec["objective_bound"], 0)
        study.tell(trial, state=TrialState.PRUNED)
        return
    values = []
    for o in space.objectives:
        v = rec.get(f"objective_{o}")
        if v is None or not math.isfinite(v):      # not solved, or nothing limits it
            v = 0.0 if OBJECTIVES[o] == "maximize" else 1e9
        values.append(float(v))
    study.tell(trial, values if len(values) > 1 else values[0])


#: the states (names) of a trial that finished: solved, or ended once it could not be kept
FINISHED = ("COMPLETE", "PRUNED")


def feasible(t) -> bool:
    """A finished trial that meets every constraint."""
    return t.state.name == "COMPLETE" and all(c <= 0 for c in _constraints(t))


def best_trials(study, space: Space, count: int = 3) -> list:
    """The best feasible trials: by the objective (single), or the Pareto front's."""
    ok = [t for t in study.get_trials(deepcopy=False) if feasible(t)]
    if len(space.objectives) > 1:
        front = {t.number for t in study.best_trials}
        return [t for t in ok if t.number in front]
    sign = -1.0 if OBJECTIVES[space.objectives[0]] == "maximize" else 1.0
    return sorted(ok, key=lambda t: sign * t.values[0])[:count]


def binding(study) -> str:
    """Which constraint keeps the finished trials out (none feasible): the one violated by
    the most, with how many."""
    counts = {c: 0 for c in CONSTRAINTS}
    done = [t for t in study.get_trials(deepcopy=False) if t.state.name == "COMPLETE"]
    for t in done:
        for c, v in zip(CONSTRAINTS, _constraints(t)):
            counts[c] += v > 0
    worst = max(counts, key=counts.get)
    return f"{worst} (violated by {counts[worst]} of {len(done)} trials)"


def _progress(study, space: Space, done: int, total: int, solved: int, wall: float) -> str:
    best = best_trials(study, space, 1)
    o = space.objectives[0]
    text = (f"best {o} {best[0].values[0]:.4g} (trial {best[0].number})" if best
            else "no feasible design yet")
    left = wall / max(solved, 1) * (total - done)
    return f"trial {done} of {total}, {text}, about {left / 60:.1f} min left"


TABLE_COLUMNS = ("status", "objective_safety", "objective_bound", "objective_te",
                 "objective_stiffness",
                 "limited_by", "S_F1", "S_F2", "S_H_flank", "S_H",
                 "root_stress_gear1_MPa", "root_stress_gear1_beta_deg",
                 "root_stress_gear1_tooth", "root_stress_gear2_MPa",
                 "root_stress_gear2_beta_deg", "root_stress_gear2_tooth",
                 "contact_pressure_MPa", "flank_contact_pressure_MPa",
                 "flank_contact_pressure_beta_deg", "flank_contact_pressure_tooth",
                 "edge_load_N", "te_p2p_urad", "stiffness_Nm_per_rad", "outer_diameter_mm",
                 "centre_distance_mm",
                 "backlash_um", "time_s", "reason")


def write_trials(study, space: Space, out: Path) -> Path:
    """``trials.csv``: a row a trial (every state), its design, state, feasibility, the
    constraint values and :data:`TABLE_COLUMNS`; and ``search.json``, the settings and the
    best trials."""
    names = [v.name for v in space.variables]
    trials = study.get_trials(deepcopy=False)
    # a class's pairs add their columns (the jammed share, each factor at the quantile, the
    # share whose rounds carry load), as the trials have them
    graded = sorted({k for t in trials for k in t.user_attrs
                     if k in ("jammed_share", "edge_share")
                     or k.startswith(("S_F1_P", "S_F2_P", "S_H_flank_P"))})
    columns = [*TABLE_COLUMNS, *graded]
    header = ["trial", "state", "feasible", *names, *(f"violation_{c}" for c in CONSTRAINTS),
              *columns]
    copies = {t.user_attrs["requeued_from"]: t for t in trials
              if "requeued_from" in t.user_attrs}
    rows = []
    for t in trials:
        cut = _unfinished(t, copies)
        a = cut if cut.get("status") == "cut" else {**t.user_attrs, **cut}
        cons = _violations(t) if t.state.name in FINISHED else [None] * len(CONSTRAINTS)
        rows.append([t.number, t.state.name, feasible(t), *(t.params.get(n) for n in names),
                     *cons, *(a.get(c) for c in columns)])
    path = write_csv(out / "trials.csv", header,
                     (["" if v is None else v for v in row] for row in rows))
    best = best_trials(study, space)
    write_json(out / "search.json", {
        "settings": study.user_attrs.get("settings"),
        "trials": len(rows), "finished": sum(t.state.name in FINISHED for t in
                                             study.get_trials(deepcopy=False)),
        "pruned": sum(t.state.name == "PRUNED" for t in study.get_trials(deepcopy=False)),
        "feasible": sum(feasible(t) for t in study.get_trials(deepcopy=False)),
        "best": [{"trial": t.number, "params": t.params, "values": t.values,
                  **{k: _clean(t.user_attrs.get(k)) for k in TABLE_COLUMNS}} for t in best]})
    return path


def _unfinished(t, copies: dict) -> dict:
    """The status and reason of a trial that did not finish: one cut short (FAIL) and the
    queued copy that redoes it (WAITING, or RUNNING while solved). A trial with a copy was
    cut short whatever its record says: a kill between a record's attributes and the state
    that finishes it leaves part of a record on a trial that never finished."""
    if t.state.name == "FAIL" and (not t.user_attrs.get("status") or t.number in copies):
        copy = copies.get(t.number)
        if copy is None:
            return {"status": "cut", "reason": "did not finish"}
        why = copy.user_attrs.get("cut_by") or "cut short"
        return {"status": "cut", "reason": f"{why}; its design queued again as trial "
                                           f"{copy.number}"}
    if t.state.name in ("WAITING", "RUNNING") and "requeued_from" in t.user_attrs:
        why = t.user_attrs.get("cut_by") or "cut short"
        return {"status": "queued", "reason": f"the design of trial "
                f"{t.user_attrs['requeued_from']} ({why}), solved first when the search "
                "goes on"}
    return {}


def load_trials(out):
    """A search's trials as a pandas DataFrame (``trials.csv`` of its directory ``out``)."""
    import pandas as pd

    path = Path(out) / "trials.csv"
    if not path.is_file():
        raise FegearError(f"no trials.csv in {out}: not a search directory")
    return pd.read_csv(path)

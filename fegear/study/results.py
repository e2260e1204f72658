"""A study's results: one row per case in Parquet and CSV, a markdown table, and plots.

A row holds the case's inputs (every ``fegear solve`` input by name), its status and reason,
every value of the ``fegear solve --json`` summary (nested keys joined by dots, lists as JSON
text), the fegear and library versions, the code version and the times. The safety factors
are computed here, from the stored stresses at the allowables the study file gives now
(:func:`~fegear.toothpair.with_safety`): new allowables need no solve. A case with
``positions`` has its cycle's extremes as columns (``cycle.<stress>.max`` and
``cycle.<factor>.min``, each with its ``at_position_deg``; docs/studies.md), the factors
recomputed from every position's stored stresses. Cases not finished yet have no row; the
table is rebuilt from ``cases/*.json`` whenever the study stops. :func:`study_plot` gathers
what each plot shows.
"""

from __future__ import annotations

import csv
import io
import json
import math
from pathlib import Path

from ..files import write_atomic
from ..quantities import FACTORS, FLANK, QUANTITIES, ROOT1
from ..toothpair import (
    HEADLINE,
    JOB_INPUTS,
    allowables_of,
    damage_text,
    index_html,
    life_text,
    safety_text,
    shown,
    with_safety,
)
from .file import RefusedCase, Study
from .plot import Line, StudyPlot, study_png
from .records import finished

#: the smallest safety factors over the teeth in the study table's head, by their symbols
SAFETY_SHORT = {k: FACTORS[k].symbol for k in ("safety_bending_gear1", "safety_bending_gear2",
                                               "safety_contact")}

#: columns after the summary
_TRAILER = ("case_wall_s", "solve_s", "fegear", "code_version", "host", "pid", "finished_utc")


def rows(study: Study, out: Path) -> list[dict]:
    """One flat row per finished case, in the study's order, and one per refused case
    (``status`` "refused", ``error`` the refusal) once any case has finished."""
    done = finished(study, out)
    if not done:
        return []
    inputs = JOB_INPUTS
    table = []
    for case in sorted((*study.cases, *study.refused), key=lambda c: c.index):
        if isinstance(case, RefusedCase):
            table.append({"case": case.index, "key": None, "status": "refused",
                          "error": case.reason,
                          **{n: case.values.get(n, i.default) for n, i in inputs.items()}})
            continue
        rec = done.get(case.key)
        if rec is None:
            continue
        row = {"case": case.index, "key": case.key, "status": rec["status"],
               "error": rec.get("error")}
        row.update({n: case.values.get(n, i.default) for n, i in inputs.items()})
        summary = rec.get("summary")
        if summary:
            summary = with_safety(summary, allowables_of(row))
            # a class's pairs and the sensitivities in a few columns each: their rows stay
            # in the case's record
            summary = dict(summary)
            summary.pop("case", None)   # the inputs as run: the row's own input columns
            for analysis in shown(summary):
                columns = analysis.columns(summary[analysis.key])
                if columns is not None:
                    summary.pop(analysis.key)
                    row.update(columns)
        row.update(_flatten(summary or {}))
        row.update({k: rec.get(k) for k in _TRAILER})
        row.update({f"versions.{k}": v for k, v in (rec.get("versions") or {}).items()})
        table.append(row)
    return table


def _flatten(d: dict, prefix: str = "") -> dict:
    out = {}
    for k, v in d.items():
        name = f"{prefix}{k}"
        if isinstance(v, dict):
            out.update(_flatten(v, name + "."))
        elif isinstance(v, list):
            out[name] = json.dumps(v)
        else:
            out[name] = v
    return out


def columns(table: list[dict]) -> list[str]:
    """Every column that any row has, in first-seen order."""
    cols: dict[str, None] = {}
    for row in table:
        cols.update(dict.fromkeys(row))
    return list(cols)


def write_results(study: Study, out: Path) -> dict[str, Path]:
    """results.parquet, results.csv, results.md and one PNG per varied input but the
    allowables (in ``plots/``). With no finished case yet, nothing is written."""
    table = rows(study, out)
    if not table:
        return {}
    cols = columns(table)
    files = {"parquet": write_parquet(out / "results.parquet", table, cols),
             "csv": write_atomic(out / "results.csv", lambda t: t.write_text(to_csv(table,
                                                                                     cols))),
             "md": write_atomic(out / "results.md",
                                lambda t: t.write_text(markdown(study, table) + "\n"))}
    if study.outputs.report:
        files["report"] = write_index(study, table, out)
    plots = out / "plots"
    plots.mkdir(exist_ok=True)
    for x in study.varied:
        if JOB_INPUTS[x].post:  # no stress varies with an allowable
            continue
        png = plot_input(plots / f"{x}.png", study, table, x)
        if png is not None:
            files[f"plot_{x}"] = png
    return files


def write_index(study: Study, table: list[dict], out: Path) -> Path:
    """report.html: the study's index page, a row a case with its verdict and a link to its
    own page (``cases/<key>/report.html``)."""
    done = finished(study, out)
    cases = []
    for row in table:
        rec = done.get(row["key"]) if row["key"] else None
        page = out / "cases" / str(row["key"]) / "report.html"
        swept = next((c.swept for c in study.cases if c.key == row["key"]), {})
        cases.append({"case": row["case"], "values": swept, "status": row["status"],
                      "error": row.get("error"),
                      "summary": rec.get("summary") if rec else None,
                      "link": f"cases/{row['key']}/report.html" if page.exists() else None})
    return write_atomic(out / "report.html",
                        lambda tmp: tmp.write_text(index_html(study.name, cases),
                                                   encoding="utf-8"))


def plot_input(path: Path, study: Study, table: list[dict], x: str) -> Path | None:
    """The picture of input ``x`` (:func:`study_plot`); None where it has no line."""
    plot = study_plot(study, table, x)
    return None if plot is None else study_png(path, plot, HEADLINE)


def write_parquet(path: Path, table: list[dict], cols: list[str]) -> Path:
    import pyarrow as pa
    import pyarrow.parquet as pq

    kinds = {n: i.kind.__name__ for n, i in JOB_INPUTS.items()}
    arrays = {c: _arrow(pa, [r.get(c) for r in table], kinds.get(c)) for c in cols}
    return write_atomic(path, lambda tmp: pq.write_table(pa.table(arrays), tmp))


def _arrow(pa, values: list, kind: str | None = None):
    """An Arrow column with an explicit type: bool, int64, float64, else string; a column
    with no value has its input's type (``kind``), else Arrow's null type."""
    present = [v for v in values if v is not None]
    if not present:
        types = {"bool": pa.bool_(), "int": pa.int64(), "float": pa.float64(),
                 "str": pa.string()}
        return pa.array(values, types.get(kind, pa.null()))
    if present and all(isinstance(v, bool) for v in present):
        return pa.array(values, pa.bool_())
    if present and all(isinstance(v, int) and not isinstance(v, bool) for v in present):
        return pa.array(values, pa.int64())
    if present and all(isinstance(v, (int, float)) and not isinstance(v, bool)
                       for v in present):
        return pa.array([None if v is None else float(v) for v in values], pa.float64())
    return pa.array([None if v is None else str(v) for v in values], pa.string())


def to_csv(table: list[dict], cols: list[str]) -> str:
    """CSV text: floats at full precision, empty cells for missing values."""
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(cols)
    for r in table:
        w.writerow(["" if r.get(c) is None else repr(r[c]) if isinstance(r[c], float)
                    else r[c] for c in cols])
    return buf.getvalue()


def markdown(study: Study, table: list[dict]) -> str:
    """The study at a glance: varied inputs, headline stresses, safety factors, error
    estimate, status. A study with ``positions`` gets the cycle's largest stresses and
    smallest factors, each at its β, beside the values at the cycle's first position β0 (the
    study's ``position``) and a line under the table that says so."""
    cycled = any(r.get("cycle.positions") for r in table)
    sampled = any(r.get("samples.n") for r in table)
    rated = any(_modes(r) for r in table)
    head = (list(study.varied) + [QUANTITIES[k].short for k in HEADLINE]
            + list(SAFETY_SHORT.values()) + [QUANTITIES["edge_load_N"].head]
            + ([f"{QUANTITIES[k].short} cycle" for k in HEADLINE]
               + [f"{s} cycle" for s in SAFETY_SHORT.values()] if cycled else [])
            + (list(SAMPLES_SHORT) if sampled else [])
            + (list(RATING_SHORT) if rated else [])
            + ["est. error %", "teeth", "status", "time s"])
    lines = ["| " + " | ".join(head) + " |", "|" + "---:|" * len(head)]
    for r in table:
        ok = r["status"] == "ok"
        cells = [_cell(r.get(x)) for x in study.varied] + _position_cells(r)
        if cycled:
            cells += _cycle_cells(r)
        if sampled:
            cells += [_samples_cell(r, key) for key in SAMPLES_SHORT.values()]
        if rated:
            cells += _rating_cells(r)
        est = r.get("error_estimate_pct")
        status = {"ok": "ok", "refused": "refused (below)"}.get(r["status"],
                                                                 f"failed: {r['error']}")
        cells += [f"{est:.2f}" if ok and est is not None else "–", _teeth(r) if ok else "–",
                  status, f"{r['case_wall_s']:.1f}" if r.get("case_wall_s") is not None
                  else "–"]
        lines.append("| " + " | ".join(cells) + " |")
    refused = [r for r in table if r["status"] == "refused"]
    if refused:
        lines += ["", f"Not solved: `fegear solve` refuses the inputs of {len(refused)} "
                  f"case{'s' if len(refused) > 1 else ''}:", ""]
        lines += [f"* case {r['case']} ("
                  + ", ".join(f"{x} = {_cell(r.get(x))}" for x in study.varied)
                  + f"): {r['error']}" for r in refused]
    if sampled:
        lines += ["", "A class's pairs (`grade`, docs/tolerance.md): the share that jams, the "
                  "P95 of gear 1's root stress and of the flank pressure, and the safety "
                  "factors that the `quantile` share of the pairs meet (\"jams\" where the "
                  "jammed pairs reach past it)."]
    if rated:
        lines += ["", "Rated for a life (`spectrum`, docs/rating.md): the mode with the smallest "
                  "safety factor at the required life, that factor, its Miner's sum and its "
                  "life."]
    if cycled:
        lines += ["", "Stresses in MPa. With positions, the first columns are at the cycle's "
                  "first position β0 (the study's position); \"cycle\": the largest stress "
                  "and the smallest safety factor over the cycle, at its β. The error estimate "
                  "is at the position of the largest root σ1 of gear 1; teeth: fewest–most "
                  "in contact over the cycle."]
    return "\n".join(lines)


#: a class's samples in the table: header → the results' column
SAMPLES_SHORT = {"jammed %": "samples.jammed_share",
                 **{f"{q.short} P95": f"samples.{q.key}.P95" for q in (ROOT1, FLANK)},
                 **{f"{FACTORS[q.safety].symbol} at q": f"samples.{q.safety}.at_quantile"
                    for q in (ROOT1, FLANK)}}


#: a life rating in the table: its headers (the limiting mode's, :func:`_rating_cells`)
RATING_SHORT = ("limits for the life", "S at life", "Miner", "life")


def _modes(row: dict) -> list[str]:
    """The rated modes of a case's row (none without a spectrum)."""
    head, tail = "rating.modes.", ".safety"
    return [k[len(head):-len(tail)] for k in row if k.startswith(head) and k.endswith(tail)]


def _rating_cells(row: dict) -> list[str]:
    """The life rating's cells: the mode with the smallest safety factor at the required
    life, that factor, its Miner's sum and its life, as the solve's rating table writes them
    (:mod:`fegear.toothpair.analyses.rating.report`); dashes without a spectrum. The summary
    writes an infinity as "inf"."""
    modes = _modes(row)
    if row["status"] != "ok" or not modes:
        return ["–"] * len(RATING_SHORT)
    by_mode = {mode: {key: row.get(f"rating.modes.{mode}.{key}")
                      for key in ("safety", "miner", "life_h", "life_repeats")}
               for mode in modes}
    mode, m = min(by_mode.items(),
                  key=lambda kv: math.inf if kv[1]["safety"] == "inf" else kv[1]["safety"])
    return [mode, safety_text(m["safety"]), damage_text(m["miner"]), life_text(m)]


def _samples_cell(row: dict, key: str) -> str:
    """One samples cell: "–" without samples, "jams" where a quantile falls among the jammed
    pairs (a stress None, a factor 0), else the number."""
    if row["status"] != "ok" or row.get("samples.n") is None:
        return "–"
    v = row.get(key)
    if key == "samples.jammed_share":
        return f"{100 * v:.1f}"
    if v is None or (key.endswith("at_quantile") and v == 0.0):
        return "jams"
    return f"{v:.2f}" if key.endswith("at_quantile") else f"{v:.1f}"


def cycle_of(row: dict) -> list[dict] | None:
    """A table row's cycle, one dict per position from its first, β0 (the case's
    ``position``), on: ``cycle.rows``, with the safety factors at the study's allowables;
    None for a case without ``positions``."""
    text = row.get("cycle.rows")
    return json.loads(text) if text else None


def _position_cells(r: dict) -> list[str]:
    """The headline stresses, safety factors and load on the tip rounds of one position: the
    case's own, or with a cycle its first position's."""
    n = len(HEADLINE) + len(SAFETY_SHORT) + 1
    if r["status"] != "ok":
        return ["–"] * n
    cycle = cycle_of(r)
    at = cycle[0] if cycle else None
    values = at if at is not None else r
    edge = values.get("edge_load_N" if at is not None else "edge_contact.load_N")
    return ([f"{values[k]:.1f}" for k in HEADLINE] + [_factor(values.get(k))
                                                       for k in SAFETY_SHORT]
            + [f"{edge:.1f}" if edge is not None else "–"])


def _cycle_cells(r: dict) -> list[str]:
    """The cycle's largest headline stresses and smallest safety factors, each with the β
    (deg) where it occurs; dashes for a case without a cycle."""
    if r["status"] != "ok" or not r.get("cycle.positions"):
        return ["–"] * (len(HEADLINE) + len(SAFETY_SHORT))
    worst = [(r[f"cycle.{k}.max"], r[f"cycle.{k}.at_position_deg"], 1) for k in HEADLINE]
    worst += [(r.get(f"cycle.{k}.min"), r.get(f"cycle.{k}.at_position_deg"), 2)
              for k in SAFETY_SHORT]
    return [f"{v:.{digits}f} ({beta:.3g}°)" if v is not None else "–"
            for v, beta, digits in worst]


def _factor(s: float | None) -> str:
    return f"{s:.2f}" if s is not None else "–"


def _teeth(r: dict) -> str:
    """Teeth in contact: the case's, or over a cycle the fewest and the most."""
    low, high = r.get("cycle.teeth_in_contact.min"), r.get("cycle.teeth_in_contact.max")
    if low is None:
        return str(r.get("teeth_in_contact", "–"))
    return str(low) if low == high else f"{low}–{high}"


def _cell(v) -> str:
    return f"{v:g}" if isinstance(v, float) else str(v)


def study_plot(study: Study, table: list[dict], x: str) -> StudyPlot | None:
    """What the picture of input ``x`` shows: one :class:`Line` per level of the other
    varied inputs where ``x`` takes two or more values. An input a sweep block sets along
    with ``x`` as a function of it (a ``zip`` block: a relief sized per case) goes with ``x``
    and does not split the lines; an allowable splits none (it changes no stress: cases apart
    in allowables alone are one point). None if no such line exists."""
    ok = [r for r in table if r["status"] == "ok"]
    tied = tied_inputs(study, ok, x)
    others = [v for v in study.varied if v != x and v not in tied and not JOB_INPUTS[v].post]
    groups: dict[tuple, list[dict]] = {}
    for r in ok:
        groups.setdefault(tuple(r[o] for o in others), []).append(r)
    lines, keys = [], set()
    for level, rs in groups.items():
        if len({r[x] for r in rs}) < 2:
            continue
        rs = sorted({r["key"]: r for r in rs}.values(), key=_along(x, rs))
        label = ", ".join([f"{o} {_cell(v)}{_unit(o)}" for o, v in zip(others, level)]
                          + [f"{o} with {x}" for o in tied]) or "all"
        lines.append(_line(label, x, rs))
        keys.update(r["key"] for r in rs)
    if not lines:
        return None
    shown = [r for r in ok if r["key"] in keys]
    torques = {r["torque"] for r in shown}
    allowables = {(r["allowable-bending"], r["allowable-contact"]) for r in shown}
    unit = _unit(x).strip()
    return StudyPlot(study.name, x, f"{x} [{unit}]" if unit else x, tuple(lines),
                     torques.pop() if len(torques) == 1 else None,
                     allowables.pop() if len(allowables) == 1 else None,
                     tuple(sorted({r["cycle.positions"] for r in shown
                                   if r.get("cycle.positions")})))


def _along(x: str, rs: list[dict]):
    """The order of cases along ``x``: by value where every value is a number, else (a
    deviation's text, ``1:11=5``) as the study file lists them."""
    numbers = all(isinstance(r[x], (int, float)) and not isinstance(r[x], bool) for r in rs)
    return (lambda r: r[x]) if numbers else (lambda r: int(r["case"]))


def _line(label: str, x: str, rs: list[dict]) -> Line:
    """One line through the cases ``rs`` (sorted by ``x``)."""
    cycles = [cycle_of(r) for r in rs]
    stress, error = {}, {}
    for k in HEADLINE:
        stress[k] = tuple(r[f"cycle.{k}.max"] if c else r[k] for r, c in zip(rs, cycles))
        err = [r.get(f"error_estimate_by_stress_pct.{k}") for r in rs]
        error[k] = tuple(0.0 if e is None or not math.isfinite(e) else s * e / 100.0
                         for s, e in zip(stress[k], err))
    safety = {k: tuple(r.get(f"cycle.{k}.min") if c else r.get(k) for r, c in zip(rs, cycles))
              for k in SAFETY_SHORT}
    edge = tuple(max(p["edge_load_N"] for p in c) if c else r.get("edge_contact.load_N") or 0.0
                 for r, c in zip(rs, cycles))
    on_round = tuple(
        max(c, key=lambda p: p["contact_pressure_MPa"])["edge_load_N"] > 0 if c
        else bool(r.get("edge_contact.load_N") or r.get("contact_peak_on_tip_round"))
        for r, c in zip(rs, cycles))
    start = None
    if any(cycles):
        start = {k: tuple(c[0][k] if c else r[k] for r, c in zip(rs, cycles))
                 for k in HEADLINE}
    return Line(label, tuple(r[x] for r in rs), stress, error, safety, edge, on_round, start)


def tied_inputs(study: Study, rows: list[dict], x: str) -> list[str]:
    """The varied inputs that sweep blocks set together with ``x`` and that ``x`` determines
    in every such case."""
    tied = []
    swept = {c.index: c.swept for c in study.cases}
    for o in study.varied:
        if o == x:
            continue
        seen: dict = {}
        both = [swept[r["case"]] for r in rows]
        both = [s for s in both if x in s and o in s]
        if both and all(seen.setdefault(s[x], s[o]) == s[o] for s in both):
            tied.append(o)
    return tied


def _unit(name: str) -> str:
    unit = JOB_INPUTS[name].unit if name in JOB_INPUTS else ""
    return f" {unit}" if unit else ""

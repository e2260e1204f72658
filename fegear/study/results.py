"""A study's results: one row per case in Parquet and CSV, a markdown table, and plots.

A row holds the case's inputs (every ``fegear solve`` input by name), its status and reason,
every value of the ``fegear solve --json`` summary (nested keys joined by dots, lists as JSON
text), the fegear and library versions, the code version and the times. The safety factors
are computed here, from the stored stresses at the allowables the study file gives now
(:func:`~fegear.toothpair.with_safety`): new allowables need no solve. Cases not finished yet
have no row; the table is rebuilt from ``cases/*.json`` whenever the study stops.
"""

from __future__ import annotations

import csv
import io
import json
import math
from pathlib import Path

from ..files import write_atomic
from ..toothpair import HEADLINE, SOLVE_INPUTS, allowables_of, with_safety
from .file import Study

#: headline stresses in the study table's head
SHORT = {"root_stress_gear1_MPa": "root σ1 g1", "root_stress_gear2_MPa": "root σ1 g2",
         "contact_pressure_MPa": "p_max", "flank_contact_pressure_MPa": "p flank",
         "von_mises_max_MPa": "vM max"}

#: the smallest safety factors over the teeth in the study table's head
SAFETY_SHORT = {"safety_bending_gear1": "S_F g1", "safety_bending_gear2": "S_F g2",
                "safety_contact": "S_H"}

#: columns after the summary
_TRAILER = ("case_wall_s", "solve_s", "fegear", "code_version", "host", "pid", "finished_utc")


def rows(study: Study, out: Path) -> list[dict]:
    """One flat row per finished case, in the study's order."""
    from .records import finished

    done = finished(study, out)
    inputs = SOLVE_INPUTS
    table = []
    for case in study.cases:
        rec = done.get(case.key)
        if rec is None:
            continue
        row = {"case": case.index, "key": case.key, "status": rec["status"],
               "error": rec.get("error")}
        row.update({n: case.values.get(n, i.default) for n, i in inputs.items()})
        summary = rec.get("summary")
        if summary:
            summary = with_safety(summary, allowables_of(row))
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
    plots = out / "plots"
    plots.mkdir(exist_ok=True)
    for x in study.varied:
        if SOLVE_INPUTS[x].post:  # no stress varies with an allowable
            continue
        png = plot_input(plots / f"{x}.png", study, table, x)
        if png is not None:
            files[f"plot_{x}"] = png
    return files


def write_parquet(path: Path, table: list[dict], cols: list[str]) -> Path:
    import pyarrow as pa
    import pyarrow.parquet as pq

    kinds = {n: i.kind.__name__ for n, i in SOLVE_INPUTS.items()}
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
    """The study at a glance: varied inputs, headline stresses, error estimate, status."""
    head = (list(study.varied) + [SHORT[k] for k in HEADLINE] + list(SAFETY_SHORT.values())
            + ["edge N", "est. error %", "teeth", "status", "time s"])
    lines = ["| " + " | ".join(head) + " |", "|" + "---:|" * len(head)]
    for r in table:
        ok = r["status"] == "ok"
        cells = [_cell(r.get(x)) for x in study.varied]
        cells += [f"{r[k]:.1f}" if ok else "–" for k in HEADLINE]
        cells += [f"{r[k]:.2f}" if ok and r.get(k) is not None else "–" for k in SAFETY_SHORT]
        edge = r.get("edge_contact.load_N")
        cells.append(f"{edge:.1f}" if ok and edge is not None else "–")
        est = r.get("error_estimate_pct")
        cells += [f"{est:.2f}" if ok and est is not None else "–",
                  str(r.get("teeth_in_contact", "–")) if ok else "–",
                  "ok" if ok else f"failed: {r['error']}",
                  f"{r['case_wall_s']:.1f}" if r.get("case_wall_s") is not None else "–"]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def _cell(v) -> str:
    return f"{v:g}" if isinstance(v, float) else str(v)


def _tied(study: Study, rows: list[dict], x: str) -> list[str]:
    """The varied inputs that sweep blocks set together with ``x`` and that ``x`` determines
    in every such case."""
    tied = []
    for o in study.varied:
        if o == x:
            continue
        seen: dict = {}
        both = [study.cases[r["case"]].swept for r in rows]
        both = [s for s in both if x in s and o in s]
        if both and all(seen.setdefault(s[x], s[o]) == s[o] for s in both):
            tied.append(o)
    return tied


def plot_input(path: Path, study: Study, table: list[dict], x: str) -> Path | None:
    """Each headline stress against input ``x``, one line per level of the other varied
    inputs (only levels where ``x`` takes two or more values), error bars from the case's
    error estimate. An input a sweep block sets along with ``x`` as a function of it (a
    ``zip`` block: a relief sized per case) goes with ``x`` and does not split the lines.
    None if no such line exists."""
    from .plot import study_png

    ok = [r for r in table if r["status"] == "ok"]
    tied = _tied(study, ok, x)
    # an allowable changes no stress: cases apart in allowables alone are one point (one key)
    others = [v for v in study.varied if v != x and v not in tied and not SOLVE_INPUTS[v].post]
    groups: dict[tuple, list[dict]] = {}
    for r in ok:
        groups.setdefault(tuple(r[o] for o in others), []).append(r)
    lines = []
    for level, rs in groups.items():
        if len({r[x] for r in rs}) < 2:
            continue
        rs = sorted({r["key"]: r for r in rs}.values(), key=lambda r: r[x])
        label = ", ".join([f"{o} {_cell(v)}" for o, v in zip(others, level)]
                          + [f"{o} with {x}" for o in tied]) or "all"
        series = {}
        for k in HEADLINE:
            err = [r.get(f"error_estimate_by_stress_pct.{k}") for r in rs]
            series[k] = ([r[k] for r in rs],
                         [0.0 if e is None or not math.isfinite(e) else r[k] * e / 100.0
                          for r, e in zip(rs, err)])
        edge = [bool(r.get("edge_contact.load_N") or r.get("contact_peak_on_tip_round"))
                for r in rs]
        series["edge"] = ([100.0 * (r.get("edge_contact.load_fraction") or 0.0) for r in rs],
                          [0.0] * len(rs))
        lines.append((label, [r[x] for r in rs], series, edge))
    if not lines:
        return None
    title = f"{study.name}: headline stresses against {x}"
    unit = SOLVE_INPUTS[x].unit if x in SOLVE_INPUTS else ""
    return study_png(path, f"{x} [{unit}]" if unit else x, lines, HEADLINE, title)

"""The bench's history: its numbers, run after run, as data.

Every ``fegear bench`` run appends its numbers (times in s, memory in MB) to a history file,
one JSON line a run with the date, fegear's code version and the machine: ``--history FILE``,
by default ``bench_history.jsonl`` in its output folder (``make bench`` keeps the repository's,
docs/bench/history.jsonl). The next run prints the last one's numbers beside its own, with the
ratio, so a change to the code is judged against the run before it on the same machine; ``fegear
bench --show-history`` prints the history as a table. A folder from before the history existed
has its ``bench.json``: that run's numbers are read from it instead.
"""

from __future__ import annotations

import json
import time
from pathlib import Path

HISTORY = "bench_history.jsonl"


def bench_metrics(record: dict) -> dict[str, float]:
    """The numbers of a ``bench.json`` record that are worth comparing between runs, by a
    readable name: each rung's and level's time, each stage of each ring level, peak memory,
    the estimate, the cycle and its ratio, the model cache's rows, the growth with the teeth
    and the paper study."""
    out: dict[str, float] = {}
    for lad in record.get("ladders", []):
        for r in lad["rungs"]:
            out[f"{lad['name']} `{r['level']}` [s]"] = r["total_s"]
    ring = record.get("ring", {})
    for r in ring.get("ring", []):
        name = f"ring `{r['label']}`"
        out[f"{name}, one position [s]"] = r["total_s"]
        out.update({f"{name}, {k} [s]": v for k, v in r["timings_s"].items() if v})
        out[f"{name}, peak [MB]"] = r["peak_mb"]
        if r["extra"].get("output_s") is not None:
            out[f"{name}, --out [s]"] = r["extra"]["output_s"]
    extras = ring.get("extras") or {}
    if extras.get("extra", {}).get("estimate_s") is not None:
        out[f"ring `{extras['label']}` [s]"] = extras["extra"]["estimate_s"]
    cycle, default = ring.get("cycle"), ring.get("default")
    if cycle:
        out[f"ring `{cycle['label']}` [s]"] = cycle["extra"]["cycle_s"]
        if default:
            out["cycle / one position [×]"] = cycle["extra"]["cycle_s"] / default["total_s"]
    cached = ring.get("cache")
    if cached:
        out[f"ring `{cached['read']['label']}` [s]"] = cached["read"]["total_s"]
        both = cached["read_estimate"]
        out[f"ring `{both['label']}` [s]"] = both["extra"].get("estimate_s", both["total_s"])
        out.update({f"`fegear solve`, {k} [s]": v for k, v in cached["commands_s"].items()})
    for r in ring.get("scaling", []):
        out[f"{r['label']}, one position [s]"] = r["total_s"]
        out[f"{r['label']}, peak [MB]"] = r["peak_mb"]
    if ring.get("paper_study_s") is not None:
        out["studies/paper_trends.toml, 2 workers [s]"] = ring["paper_study_s"]
    if ring.get("tolerance_class") is not None:
        out["1000 class-6 pairs, 24 positions [s]"] = ring["tolerance_class"]["seconds"]
    if ring.get("spectrum") is not None:
        s = ring["spectrum"]
        out["4-level spectrum / its cycle, whole commands [×]"] = s["spectrum_s"] / s["cycle_s"]
    rev = ring.get("revolution")
    if rev is not None:
        out["one deviated pair's revolution [s]"] = rev["pair_s"]
        out["200 class-5 pairs over a revolution [s]"] = rev["class_s"]
    if ring.get("search") is not None:
        out["design search over a turn, 200 trials of 50 pairs [s]"] = ring["search"]["seconds"]
    for name, f in (ring.get("face") or {}).items():
        out[f"across the face / 2D, {name}, whole commands [×]"] = f["face_s"] / f["flat_s"]
    return out


def runs(history: Path) -> list[dict]:
    """The runs kept in the history file ``history``, oldest first (none if there is none)."""
    try:
        lines = history.read_text().splitlines()
    except OSError:
        return []
    return [json.loads(line) for line in lines if line.strip()]


def last_run(history: Path) -> dict | None:
    """The last run kept in the history file ``history``, else what the ``bench.json`` beside
    it (written before the history existed) says, dated by the file; None if neither is there
    or readable."""
    try:
        kept = runs(history)
        if kept:
            return kept[-1]
    except ValueError:
        pass
    try:
        path = history.parent / "bench.json"
        record = json.loads(path.read_text())
        date = time.strftime("%Y-%m-%d %H:%M", time.gmtime(path.stat().st_mtime))
    except (OSError, ValueError):
        return None
    return {"date": date, "code": None, "metrics": bench_metrics(record)}


def remember(history: Path, metrics: dict[str, float], code: str, machine: dict) -> dict:
    """Append this run (its ``metrics``, the date, ``code`` version and ``machine``) to the
    history file ``history``; returns the entry."""
    entry = {"date": time.strftime("%Y-%m-%d %H:%M", time.gmtime()), "code": code,
             "machine": {k: machine.get(k) for k in ("platform", "cpus", "memory_GiB")},
             "metrics": metrics}
    history.parent.mkdir(parents=True, exist_ok=True)
    with open(history, "a") as f:
        f.write(json.dumps(entry) + "\n")
    return entry


def beside_table(before: dict, now: dict[str, float]) -> str:
    """Markdown: every number of this run beside the last run's (``before``: an entry of the
    history) and the ratio; a number the last run did not measure shows –."""
    code = f", {before['code'].split(';')[0]}" if before.get("code") else ""
    lines = [f"| | last run ({before['date']} UTC{code}) | this run | this / last |",
             "|---|---:|---:|---:|"]
    old = before.get("metrics", {})
    for k, v in now.items():
        b = old.get(k)
        ratio = f"{v / b:.2f}" if b else "–"
        lines.append(f"| {k} | {'–' if b is None else f'{b:.3g}'} | {v:.3g} | {ratio} |")
    return "\n".join(lines)


def history_table(kept: list[dict], last: int = 8) -> str:
    """Markdown: the ``last`` runs of a history as columns (date, code version; a run's
    ``note`` beneath), one row per number any of them measured, in the order first seen."""
    shown = kept[-last:]
    names = list(dict.fromkeys(k for run in shown for k in run.get("metrics", {})))
    head = ["| | " + " | ".join(f"{r['date']}" + (f" {r['code'].split(';')[0][:12]}"
                                                     if r.get("code") else "")
                                  for r in shown) + " |",
            "|---|" + "---:|" * len(shown)]
    if any(r.get("note") for r in shown):
        head.append("| note | " + " | ".join(r.get("note", "") for r in shown) + " |")
    rows = [f"| {k} | " + " | ".join(_cell(r.get("metrics", {}).get(k)) for r in shown) + " |"
            for k in names]
    return "\n".join(head + rows)


def _cell(v) -> str:
    return "–" if v is None else f"{v:.3g}"

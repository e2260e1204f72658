"""The bench's earlier numbers beside its new ones.

Every ``fegear bench`` run appends its headline numbers (times in s, memory in MB) to
``bench_history.jsonl`` in its output folder, one JSON line a run with the date, fegear's code
version and the machine. The next run prints the last one's numbers beside its own, with the
ratio, so a change to the code is judged against the run before it on the same machine. A
folder from before the history existed has its ``bench.json``: that run's numbers are read
from it instead.
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
    return out


def last_run(folder: Path) -> dict | None:
    """The last run kept in ``folder``: its history's last line, else what its
    ``bench.json`` (written before the history existed) says, dated by the file; None if
    neither is there or readable."""
    history = folder / HISTORY
    try:
        lines = history.read_text().splitlines()
        return json.loads(lines[-1]) if lines else None
    except (OSError, ValueError):
        pass
    try:
        path = folder / "bench.json"
        record = json.loads(path.read_text())
        date = time.strftime("%Y-%m-%d %H:%M", time.gmtime(path.stat().st_mtime))
    except (OSError, ValueError):
        return None
    return {"date": date, "code": None, "metrics": bench_metrics(record)}


def remember(folder: Path, metrics: dict[str, float], code: str, machine: dict) -> dict:
    """Append this run (its ``metrics``, the date, ``code`` version and ``machine``) to the
    history in ``folder``; returns the entry."""
    entry = {"date": time.strftime("%Y-%m-%d %H:%M", time.gmtime()), "code": code,
             "machine": {k: machine.get(k) for k in ("platform", "cpus", "memory_GiB")},
             "metrics": metrics}
    with open(folder / HISTORY, "a") as f:
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

"""A study's records: one JSON file per finished case, written atomically after the case's kept
files, so that a record in the folder means a finished case."""

from __future__ import annotations

import json
from pathlib import Path

from ..files import write_atomic, write_json
from .file import Study, StudyCase


def record_path(out: Path, key: str) -> Path:
    return out / "cases" / f"{key}.json"


def finished(study: Study, out: Path, retry_failed: bool = False) -> dict[str, dict]:
    """The study's cases already stored in ``out`` (key → record), the failed ones too
    unless ``retry_failed``. A record that cannot be read counts as missing."""
    done = {}
    for case in study.cases:
        try:
            rec = json.loads(record_path(out, case.key).read_text())
        except (OSError, ValueError):
            continue
        if rec.get("key") == case.key and (rec.get("status") == "ok" or not retry_failed):
            done[case.key] = rec
    return done


def study_json(study: Study) -> dict:
    return {"name": study.name, "file": str(study.path), "description": study.description,
            "outputs": {"vtu": study.outputs.vtu, "png": study.outputs.png},
            "base": study.base, "varied": list(study.varied),
            "cases": [{"index": c.index, "key": c.key, "swept": c.swept, "values": c.values}
                      for c in study.cases],
            "refused": [{"index": c.index, "block": c.block, "swept": c.swept,
                         "values": c.values, "reason": c.reason} for c in study.refused]}


def store(out: Path, case: StudyCase, record: dict, files: dict[str, bytes]) -> None:
    """Write a finished case: its kept files first, then its record (which marks it done)."""
    if files:
        folder = out / "cases" / case.key
        folder.mkdir(exist_ok=True)
        for name, data in files.items():
            write_atomic(folder / name, lambda tmp, data=data: tmp.write_bytes(data))
        record["files"] = {name: str(folder / name) for name in files}
    write_json(record_path(out, case.key), {**record, "index": case.index,
                                            "swept": case.swept})

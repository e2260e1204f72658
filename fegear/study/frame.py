"""A study's results in pandas: one call from an output directory to a DataFrame
(docs/studies.md)."""

from __future__ import annotations

from pathlib import Path

from .file import StudyError


def load_results(path: str | Path):
    """The results table of a study as a :class:`pandas.DataFrame`: one row per finished
    case in the study's order, failed ones too, and one per case refused before anything ran
    (``status`` "ok", "failed" or "refused", ``error`` the reason; the result columns of the
    last two are empty). The columns are those of ``results.parquet``:
    ``case`` and ``key``, every ``fegear solve`` input by its option name (``torque``,
    ``tip-clearance``, ``allowable-bending``), every value of the solve's summary with its
    unit in the name (``root_stress_gear1_MPa``, ``transmission_error_urad``; nested keys
    joined by dots, lists as JSON text), the safety factors (``safety_bending_gear1``,
    ``safety_contact``), versions and times. ``path``: the study's output directory (``fegear
    study --out``, default ``out/study/NAME``) or its ``results.parquet``."""
    import pandas as pd

    path = Path(path)
    file = path / "results.parquet" if path.is_dir() else path
    if not file.is_file():
        raise StudyError(f"{path}: no study results there (results.parquet); run the study "
                         f"with --out {path} first")
    return pd.read_parquet(file)

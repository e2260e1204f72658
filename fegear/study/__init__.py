"""Study stage: parameter studies from TOML files, run resumably on a local pool or a Dask
cluster, with tables and plots.

A study file (:mod:`.file`) is a base case and sweeps over any ``fegear solve`` input; every
case is checked as ``fegear solve`` checks it before anything runs (one it refuses is set
aside with its reason, and the others run), and a case that two sweeps produce runs once.
:func:`run_study` (:mod:`.runner`) solves the missing cases, each stored as an atomic record
keyed by its inputs and the code version (:mod:`.records`), so a killed study resumes where it
stopped; :mod:`.results` writes the Parquet/CSV/markdown table and the plots, and
:func:`load_results` (:mod:`.frame`) reads the table back as a pandas DataFrame.

>>> from pathlib import Path
>>> from fegear.study import build_study
>>> doc = {"study": {"name": "demo"}, "base": {"quality": "coarse", "torque": 50.0},
...        "sweep": [{"m": [1.5, 2.0]}, {"h1": {"start": 0.2, "stop": 0.3, "step": 0.05}}]}
>>> study = build_study(doc, Path("demo.toml"))
>>> len(study.cases), study.varied      # h1 0.3 is the m 2.0 case (both at the defaults)
(4, ('m', 'h1'))
>>> [case.swept for case in study.cases]
[{'m': 1.5}, {'m': 2.0}, {'h1': 0.2}, {'h1': 0.25}]
>>> doc["sweep"].append({"h1": [0.35, 0.9]})     # h1 0.9: the gear-2 curve folds back
>>> study = build_study(doc, Path("demo.toml"))
>>> [(case.index, case.swept) for case in study.cases[-1:]], study.refused[0].where
([(4, {'h1': 0.35})], '[[sweep]] 3 (h1 = 0.9)')
"""

from ..exports import lazy

__getattr__, __dir__, __all__ = lazy(__name__, {
    "file": ("Study", "StudyCase", "RefusedCase", "StudyError", "Outputs", "load_study",
             "build_study", "case_key"),
    "records": ("finished", "record_path"),
    "runner": ("run_study", "run_case", "StudyReport", "StudyInterrupted"),
    "results": ("write_results", "rows", "study_plot"),
    "frame": ("load_results",),
    "plot": ("study_png", "StudyPlot", "Line"),
})

"""Study stage: parameter studies from TOML files, run resumably on a local pool or a Dask
cluster, with tables and plots.

TODO walkthrough
"""

from ..exports import lazy

__getattr__, __dir__, __all__ = lazy(__name__, {
    "file": ("Study", "StudyCase", "StudyError", "Outputs", "load_study", "build_study",
             "case_key"),
    "records": ("finished", "record_path"),
    "runner": ("run_study", "run_case", "StudyReport", "StudyInterrupted"),
    "results": ("write_results", "rows"),
    "plot": ("study_png",),
})

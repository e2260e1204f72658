"""Design search: which design carries the torque with the largest safety margin, over a mesh
cycle, inside the designer's bounds and constraints (``fegear optimize``, docs/optimize.md).

Optuna proposes designs (:mod:`.search`; TPE with constraints, or random for comparison), a
local pool solves each over a mesh cycle at ``coarse`` (:mod:`.design`), the journal keeps
every trial across a kill, and the best are solved again at ``standard`` with the error
estimate beside the baseline and the relieved baseline (:mod:`.report`, :mod:`.plot`);
:mod:`.job` is one ``fegear optimize`` from its settings to its report's lines.
:func:`load_trials` reads a search's trials into pandas.

>>> from fegear.optimize import Space, outer_diameter, parse_variables
>>> variables = parse_variables(["m=1:2.5", "h1=0.2:0.4", "relief=0:10"])
>>> [(v.name, v.low, v.high) for v in variables]
[('m', 1.0, 2.5), ('h1', 0.2, 0.4), ('relief', 0.0, 10.0)]
>>> round(outer_diameter({"m": 2.0, "h1": 0.3}), 1)   # mm: 2 (r0 + 2 e1 + rim 3 m)
104.4
>>> space = Space(variables, {"torque": 200.0}, constraints={"max_outer_diameter": 104.4})
>>> space.values({"m": 1.9, "h1": 0.27, "relief": 7.0})    # what one trial solves
{'torque': 200.0, 'quality': 'coarse', 'm': 1.9, 'h1': 0.27, 'relief': 7.0}
"""

from ..exports import lazy

__getattr__, __dir__, __all__ = lazy(__name__, {
    "space": ("Space", "Variable", "parse_variables", "check_space", "VARIABLES",
              "PAPER_RANGES", "DEFAULT_RANGES", "SAMPLERS"),
    "design": ("evaluate", "outer_diameter", "OBJECTIVES"),
    "search": ("run_search", "open_study", "load_trials", "best_trials", "binding",
               "SearchReport", "SearchInterrupted", "write_trials"),
    "report": ("resolve", "baselines", "final_table", "headline_table", "solve_command",
               "BASELINE_RELIEF"),
    "plot": ("search_pngs",),
    "job": ("SearchSettings", "SearchOutcome", "run_optimize"),
})

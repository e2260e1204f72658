"""What a search varies and what it must respect: design variables with bounds, the fixed
inputs, the constraints and the objectives, all checked before anything is solved or written.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

from ..checks import Input, number, require_range
from ..errors import FegearError, ParameterError
from ..toothpair import JOB_INPUTS
from .design import OBJECTIVES, centre_distance, outer_diameter

#: the solve inputs a search may vary: the pair's shape and modifications and the gears' size
#: (the tooth numbers are the ratio's, the torque and the material the requirement's)
VARIABLES = ("m", "h1", "f1", "shift", "rotation", "tip-clearance", "relief", "relief-extent",
             "relief-start", "tip-round", "face-width", "rim1", "rim2", "crowning",
             "end-relief")
#: the seed paper's ranges (§4): module, tooth height and tooth shape
PAPER_RANGES = {"m": (1.0, 2.5), "h1": (0.2, 0.4), "f1": (0.1, 0.2)}
#: a search's variables when none are given: the paper's ranges, and the tip relief (µm) and
#: tip clearance (mm) that keep the tip rounds unloaded (without them every design of these
#: ranges loads its rounds at the seed pair's torque, and none is feasible)
DEFAULT_RANGES = {**PAPER_RANGES, "relief": (0.0, 10.0), "tip-clearance": (0.01, 0.04)}
SAMPLERS = ("tpe", "random")
#: the constraints a search respects (``fegear optimize``'s options; None: no constraint)
CONSTRAINT_INPUTS = (
    Input("max-outer-diameter", float, None, "largest outer diameter of gear 2 (root circle "
          "and rim)", "mm", low=0.0, high=1e5, low_open=True,
          limits="the smallest gear 2 inside the bounds <= max-outer-diameter <= 100000 mm",
          rule="none"),
    Input("max-centre-distance", float, None, "largest centre distance m (z2 - z1) / 2",
          "mm", low=0.0, high=1e5, low_open=True,
          limits="the pair's at the least m <= max-centre-distance <= 100000 mm", rule="none"),
    Input("min-backlash", float, None, "smallest backlash over the cycle, both directions "
          "together (costs a backlash scan a trial, about 3 s)", "µm", low=0.0, high=1e4,
          rule="none"),
    Input("max-backlash", float, None, "largest backlash over the cycle (as --min-backlash)",
          "µm", low=0.0, high=1e4, limits="min-backlash < max-backlash <= 10000 µm",
          rule="none"),
)
_CONSTRAINT = {row.dest: row for row in CONSTRAINT_INPUTS}


@dataclass(frozen=True)
class Variable:
    """A design variable: a solve input and its bounds (its unit)."""

    name: str
    low: float
    high: float


@dataclass(frozen=True)
class Space:
    """A search's design space: ``variables``, the ``fixed`` solve inputs (by name), the rolling
    angles per cycle, the screening quality, the ``constraints`` (``max_outer_diameter`` and
    ``max_centre_distance`` mm, ``min_backlash``/``max_backlash`` µm) and the ``objectives``
    (:data:`~.design.OBJECTIVES`; the first is the one a single-objective search takes)."""

    variables: tuple[Variable, ...]
    fixed: Mapping = field(default_factory=dict)
    positions: int = 12
    quality: str = "coarse"
    constraints: Mapping = field(default_factory=dict)
    objectives: tuple[str, ...] = ("safety",)

    def values(self, params: Mapping[str, float]) -> dict:
        """The solve inputs of a design: the fixed ones with ``params`` (by variable name)."""
        return {**self.fixed, "quality": self.quality, **params}

    def settings(self) -> dict:
        """What identifies the search (a journal holds one search: resumed only with these)."""
        return {"variables": [[v.name, v.low, v.high] for v in self.variables],
                "fixed": dict(sorted(self.fixed.items())), "positions": self.positions,
                "quality": self.quality, "constraints": dict(sorted(self.constraints.items())),
                "objectives": list(self.objectives)}


def parse_variables(texts: Sequence[str]) -> tuple[Variable, ...]:
    """``name=low:high`` each (``--vary``), checked: a known variable, once, finite bounds
    with low < high, each inside the input's own range."""

    out: dict[str, Variable] = {}
    for text in texts:
        name, _, bounds = text.partition("=")
        name = name.strip().replace("_", "-")
        if name not in VARIABLES:
            raise ParameterError("vary", text, "name=low:high with name one of "
                                 + ", ".join(VARIABLES), f"unknown variable {name!r}")
        lo_text, sep, hi_text = bounds.partition(":")
        try:
            lo, hi = float(lo_text), float(hi_text)
        except ValueError:
            lo = hi = math.nan
        if not sep or not (math.isfinite(lo) and math.isfinite(hi)) or lo >= hi:
            raise ParameterError("vary", text, f"{name}=low:high with finite low < high")
        if name in out:
            raise ParameterError("vary", text, f"{name} once (it is given twice)")
        out[name] = check_variable(Variable(name, lo, hi))
    if not out:
        raise ParameterError("vary", "", "at least one name=low:high")
    return tuple(out.values())


def check_variable(v: Variable) -> Variable:
    """``v`` with its bounds checked: numbers (a bool is none), low < high, each inside the
    input's own range (refused by the input's name)."""
    if v.name not in VARIABLES:
        raise ParameterError("vary", v.name, "one of " + ", ".join(VARIABLES),
                             f"unknown variable {v.name!r}")
    lo, hi = number(v.low), number(v.high)
    if lo is None or hi is None or not (math.isfinite(lo) and math.isfinite(hi)) or lo >= hi:
        raise ParameterError("vary", f"{v.name}={v.low!r}:{v.high!r}",
                             f"{v.name}=low:high with finite numbers low < high")
    for bound in (lo, hi):
        JOB_INPUTS[v.name].check(bound)   # outside the input's range: refused by its name
    return Variable(v.name, lo, hi)


def check_space(space: Space) -> None:
    """Refuse, by name, a space no design of which can meet its constraints or be solved: the
    fixed inputs must be valid, a variable not also fixed, the objectives known, the outer
    diameter reachable inside the bounds, the backlash bounds in order."""
    JOB_INPUTS.with_defaults(space.fixed)    # an unknown input: refused by its name
    for name, value in space.fixed.items():   # those with limits: by prepare_job, below
        if value is not None and not JOB_INPUTS[name].limits:
            JOB_INPUTS[name].check(value)
    for v in space.variables:
        check_variable(v)
        if v.name in space.fixed and space.fixed[v.name] is not None:
            raise FegearError(f"--{v.name} is given and also varied (--vary {v.name}=...): "
                              "one or the other")
    for o in space.objectives:
        if o not in OBJECTIVES:
            raise ParameterError("objectives", o, "one or more of " + ", ".join(OBJECTIVES))
    for name in space.constraints:
        if name not in _CONSTRAINT:
            raise ParameterError(name, space.constraints[name], "one of "
                                 + ", ".join(_CONSTRAINT), "unknown constraint")
    lo, hi = space.constraints.get("min_backlash"), space.constraints.get("max_backlash")
    _CONSTRAINT["min_backlash"].check(lo)
    if hi is not None:
        require_range("max-backlash", hi, 0.0 if lo is None else number(lo), 1e4,
                      lo_open=lo is not None, unit="µm" if lo is None else "µm (above "
                      "min-backlash)")
    from ..toothpair import prepare_job  # lazy: heavy: numpy; `fegear --help` imports this module

    # the fixed pair itself (with the varied inputs at their defaults) must be one fegear
    # builds: a refusal names the fixed input (z2 <= z1, a tip clearance past e1, …)
    varied = {v.name for v in space.variables}
    prepare_job({**{k: v for k, v in space.fixed.items() if k not in varied},
                 "quality": space.quality, "no-estimate": True})
    bounds = {v.name: v for v in space.variables}
    most = space.constraints.get("max_outer_diameter")
    if most is not None:
        smallest = {n: bounds[n].low for n in ("m", "h1", "rim2") if n in bounds}
        least = outer_diameter({**space.fixed, **smallest})
        require_range("max-outer-diameter", most, least, 1e5, unit="mm (the smallest gear 2 "
                      "inside the bounds: its root circle and rim at the least m, h1, rim2)")
    far = space.constraints.get("max_centre_distance")
    if far is not None:
        least = centre_distance({**space.fixed, **({"m": bounds["m"].low} if "m" in bounds
                                                   else {})})
        require_range("max-centre-distance", far, least, 1e5,
                      unit="mm (the pair's at the least m)")

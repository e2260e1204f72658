"""Refusals: the input a refused design is blamed on and the interval it is told.

A refused design names one input the user set that fixes its defect (:mod:`.admissible`), with
the interval of that input, at the other inputs' values, in which the design is admissible, and
a second input that fixes it as an alternative. The interval is found from an admissible value
towards the given one and towards the end of the input's span, each default derived again at
every value tried (as the user would get it): by bisection, the cheap curve test first, or by
regula falsi where the clearance is continuous in the input, and then checked inside
(docs/geometry.md, "Admissible designs").
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping

import numpy as np

from ..checks import number
from ..errors import ParameterError
from .admissible import (
    _built,
    clearance_margin,
    curves_defect,
    defect,
    profile_defect,
    resolve,
)
from .parameters import H1_MIN, PAIR_INPUTS, PairParameters, built_modification, teeth_range

PAIR_ROWS = {row.name: row for row in PAIR_INPUTS}
BISECT = 60             # bisection steps at most


def _span(name: str, values: Mapping[str, object]) -> tuple[float, float] | None:
    """The static bounds of input ``name`` at the other inputs' values (``None`` for an input
    a refusal does not search, or where m, z or h1 are themselves out of range)."""
    p = _loose({k: v for k, v in values.items() if k != name})   # its own value may be bad
    if p is None:
        return None
    e1 = p.m * p.h1
    spans = {"h1": (H1_MIN, min(2.0, 0.999 * p.z2 / 4)), "f1": (0.0, 1.0),
             "shift": (0.0, 0.25 * e1), "rotation": (-0.25 * e1, 0.25 * e1),
             "tip-clearance": (0.0, e1),
             "relief": (0.0, 50.0 * p.m), "relief-extent": (1e-4 * p.m, 2.0 * p.m),
             "relief-start": (p.r1 - 2 * p.m, p.r1 + 2 * p.m)}
    return spans.get(name)


def _loose(values: Mapping[str, object]) -> PairParameters | None:
    """The pair at the given values with the modifications left unmodified, for spans."""
    v = {k: values[k] for k in ("m", "z2", "z1", "h1", "f1") if values.get(k) is not None}
    try:
        return PairParameters(**v)
    except ParameterError:
        return None


#: the inputs a refusal may name with an interval
SEARCHED = ("h1", "f1", "rotation", "shift", "tip-clearance", "relief", "relief-extent",
            "relief-start")
#: values of each input to start the search from, tried first (then a grid over its span)
ANCHORS = {"h1": (0.3, 0.2, 0.1, 0.5), "f1": (0.15, 0.1, 0.0, 0.3), "relief": (0.0,),
           "rotation": (0.0,), "tip-clearance": (0.016,), "shift": (0.016,)}
CHECKS = 2              # an input's interval is checked at this many designs inside it


_MARGINS: dict[tuple, float] = {}   # margin of each design asked for, in this process


def margin(values: Mapping[str, object]) -> float:
    """How far the design given by input values is inside the admissible set: its
    :func:`~.admissible.clearance_margin` (mm, continuous in the modifications), or ``-inf``
    for any other defect. Kept for the designs asked for before (a refusal's
    searches ask for many, and several refusals of one design for the same)."""
    key = tuple(sorted((k, v) for k, v in values.items() if v is not None))
    if key not in _MARGINS:
        if len(_MARGINS) > 50_000:
            _MARGINS.clear()
        _MARGINS[key] = _margin(values)
    return _MARGINS[key]


def _margin(values: Mapping[str, object]) -> float:
    try:
        p = resolve(values)
    except ParameterError:
        return -math.inf
    if curves_defect(p) is not None:
        return -math.inf
    g = _built(p)
    if g is None or profile_defect(g) is not None:
        return -math.inf
    return clearance_margin(g)


def _curves_ok(values: Mapping[str, object]) -> bool:
    """The cheap part of the test: the static ranges and the gear-2 curves (milliseconds)."""
    v = {row.name: values.get(row.name, row.default) for row in PAIR_INPUTS}
    try:
        m, h1 = float(v["m"]), float(v["h1"])
        for name in ("shift", "rotation"):
            if v[name] is None:
                v[name] = built_modification(name, m, h1)
        p = PairParameters(**{row.dest: v[row.name] for row in PAIR_INPUTS
                              if row.name != "tip-clearance"})
    except (ParameterError, TypeError, ValueError):
        return False
    return curves_defect(p) is None


def _edge(f, good: float, bad: float, tol: float) -> tuple[float, float]:
    """The last admissible value from ``good`` (f >= 0) towards ``bad`` (f < 0), to ``tol``,
    and the first refused value past it: regula falsi with the Illinois step where both ends
    have finite margins (the clearance is smooth in the modifications), a bisection elsewhere
    and after any step that did not halve the bracket (a margin can jump where a default's
    rule starts)."""
    fg, fb = f(good), f(bad)
    side, width = 0, abs(bad - good)
    for _ in range(BISECT):
        if abs(bad - good) <= tol:
            break
        x = 0.5 * (good + bad)
        interpolate = math.isfinite(fb) and math.isfinite(fg) and fg > fb
        if interpolate and abs(bad - good) <= 0.5 * width:
            x = bad - fb * (bad - good) / (fb - fg)
            if not min(good, bad) < x < max(good, bad):
                x = 0.5 * (good + bad)
        width = abs(bad - good)
        fx = f(x)
        if fx >= 0:
            good, fg = x, fx
            if side == +1 and math.isfinite(fb):
                fb *= 0.5       # Illinois: the end kept twice has its value halved
            side = +1
        else:
            bad, fb = x, fx
            if side == -1 and math.isfinite(fg):
                fg *= 0.5
            side = -1
    return good, bad


def _snapped(ok, good: float, bad: float, step: float) -> float:
    """The last value of the grid of ``step`` from ``good`` towards ``bad`` that is admissible
    (``ok``): the edge as it is printed, decided by the designs on the grid themselves, so
    that every search that brackets the edge to less than a step prints the same digits."""
    toward = 1.0 if bad > good else -1.0
    edge = (math.floor if toward > 0 else math.ceil)(good / step + 1e-9 * toward) * step
    while toward * (edge + toward * step - bad) < 0 and ok(edge + toward * step):
        edge += toward * step
    return edge


def interval(values: Mapping[str, object], name: str, checks: int = CHECKS
             ) -> tuple[float, float] | None:
    """The interval of input ``name``, at the other inputs' values, in which the design is
    admissible, nearest the value given (``None`` if there is none in the input's span), with
    its ends as they are printed (:func:`_snapped`, :func:`step_of`). From an admissible value,
    each end is found towards the given value (a known bad one) or the span's end: first with
    the cheap test alone, then with the whole one from where that stopped (the admissible
    values of one input are one interval, as the sweeps of docs/geometry.md and the map's test
    find them), to the printed step, and checked at ``checks`` designs inside."""
    span = _span(name, values)
    if span is None:
        return None
    lo, hi = span
    step = step_of(name)
    tol = step
    memo: dict[float, float] = {}

    def full(x: float) -> float:
        if x not in memo:
            memo[x] = margin({**values, name: x})
        return memo[x]

    def cheap(x: float) -> float:
        return math.inf if _curves_ok({**values, name: x}) else -math.inf

    def ok(x: float) -> bool:
        return cheap(x) >= 0 and full(x) >= 0

    def edge_towards(end: float) -> float:
        if cheap(end) >= 0:
            good, bad = end, end
        else:
            good, bad = _edge(cheap, anchor, end, tol)
        if full(good) < 0:
            good, bad = _edge(full, anchor, good, tol)
        return _snapped(ok, good, bad, step)

    target = number(values.get(name))
    if target is not None and not math.isfinite(target):
        target = None
    grid = sorted(np.linspace(lo, hi, 9), key=lambda a: abs(a - (target or 0.0)))
    first = [a * (values.get("m") or 2.0) / 2.0 if name in ("tip-clearance", "shift") else a
             for a in ANCHORS.get(name, ())]
    anchor = next((a for a in [*first, *grid] if lo <= a <= hi and ok(a)), None)
    if anchor is None:
        return None
    ends = []
    for end in (lo, hi):
        if target is not None and min(anchor, end) <= target <= max(anchor, end) and \
                not ok(target):
            ends.append(edge_towards(target))   # the given value is refused: the edge
        elif ok(end):                            # lies before it
            inward = math.ceil if end == lo else math.floor
            ends.append(inward(end / step - 1e-9 * (1 if end == lo else -1)) * step)
        else:
            ends.append(edge_towards(end))
    # the interval is checked at a few designs inside it; one that is refused (a pocket the
    # search stepped over) shortens it to the edge before that design
    for x in np.linspace(ends[0], ends[1], checks + 2)[1:-1]:
        if ends[0] < x < ends[1] and not ok(x):
            ends[0 if x < anchor else 1] = edge_towards(x)
    return ends[0], ends[1]


def step_of(name: str) -> float:
    """The step an interval of input ``name`` is printed to: 1e-4 of a coefficient, 10 nm of
    a modification that sets a clearance (shift, rotation, tip clearance, relief) and 0.1 µm
    of a length along the flank (the relief's extent or start)."""
    return _STEPS.get(name, 1e-4)


_UNITS = {"shift": " mm", "rotation": " mm", "tip-clearance": " mm", "relief": " µm",
          "relief-extent": " mm", "relief-start": " mm"}
_STEPS = {"shift": 1e-5, "rotation": 1e-5, "tip-clearance": 1e-5, "relief": 1e-2}


def _range_text(name: str, bounds: tuple[float, float], values: Mapping[str, object]) -> str:
    """``lo <= name <= hi unit``, the ends as :func:`interval` found them on the printed
    step."""
    digits = round(-math.log10(step_of(name)))
    lo, hi = bounds
    return f"{lo:.{digits}f} <= {name} <= {hi:.{digits}f}{_UNITS.get(name, '')}"


def _others(values: Mapping[str, object], name: str) -> str:
    p = _loose({k: v for k, v in values.items() if k != name})
    keys = [k for k in ("h1", "f1", "m", "z2", "z1") if k != name]
    text = ", ".join(f"{k}={getattr(p, k):g}" for k in keys) if p else ""
    relieved = bool(values.get("relief"))
    set_ = [k for k in ("shift", "rotation", "tip-clearance", "relief", "relief-extent",
                        "relief-start")
            if k != name and values.get(k) is not None
            and (relieved or not k.startswith("relief"))]
    return text + "".join(f", {k}={values[k]:g}" for k in set_)


def check_design(values: Mapping[str, object], given: Iterable[str] | None = None
                 ) -> PairParameters:
    """The pair of the inputs given by name, checked: raises :class:`ParameterError` naming
    the input the user changed (``given``; default: those in ``values`` not None) that fixes
    the defect, with its admissible interval at the other inputs' values and another input's
    as an alternative."""
    values = {k: v for k, v in values.items() if v is not None}
    given = set(values if given is None else given)
    try:
        p = resolve(values)
    except ParameterError as exc:   # a static range: told as the admissible interval
        _teeth_set(exc, values, given)
        bounds = interval(values, exc.name) if exc.name in ANCHORS else None
        if bounds is None:
            raise
        raise ParameterError(exc.name, exc.value, f"{_range_text(exc.name, bounds, values)} "
                             f"at {_others(values, exc.name)}", exc.reason) from None
    found = defect(p)
    if found is None:
        return p
    candidates = [f for f in found.fixes if f in given] or list(found.fixes)
    ranges = {}
    for name in found.fixes:   # the alternatives unchecked inside (their edges are exact)
        bounds = interval(values, name, CHECKS if name in candidates[:1] or found.kind in (
            "undercut", "no conjugate") else 0)
        if bounds is not None:
            ranges[name] = bounds
    usable = [c for c in candidates if c in ranges]
    if not usable:   # none of the usual fixes works here: another input the user set may
        for name in (n for n in SEARCHED if n in given and n not in ranges):
            bounds = interval(values, name)
            if bounds is not None:
                ranges[name], usable = bounds, [name]
                break
    if found.kind in ("undercut", "no conjugate") and len(usable) > 1:
        usable.sort(key=lambda c: _relative_change(getattr(p, c), ranges[c]))
    if not usable:
        name = candidates[0]
        raise ParameterError(name, _value(p, name), f"none at {_others(values, name)}",
                             found.reason)
    name = usable[0]
    alternatives = [f for f in found.fixes if f != name and f in ranges]
    extra = f" (or {_range_text(alternatives[0], ranges[alternatives[0]], values)})" if (
        alternatives) else ""
    raise ParameterError(name, _value(p, name), f"{_range_text(name, ranges[name], values)} "
                         f"at {_others(values, name)}{extra}", found.reason)


def _teeth_set(exc: ParameterError, values: Mapping[str, object], given: set[str]) -> None:
    """A pair refused for z2 <= z1 is refused as z2 (:class:`PairParameters`); where only z1
    was set, as z1, with its range at z2: raised here, else nothing."""
    if exc.name != "z2" or "z2" in given or "z1" not in given or not exc.reason:
        return
    z2 = values.get("z2", PAIR_ROWS["z2"].default)
    raise ParameterError("z1", values["z1"], teeth_range("z1", int(z2)), exc.reason) from None


def _value(p: PairParameters, name: str) -> float:
    return {"tip-clearance": p.radial_tip_clearance}.get(name, getattr(p, name.replace("-", "_"),
                                                                       None))


def _relative_change(value: float, bounds: tuple[float, float]) -> float:
    lo, hi = bounds
    if lo <= value <= hi:
        return 0.0
    edge = hi if value > hi else lo
    return abs(value - edge) / max(abs(value), 1e-12)


def admissible_pair(values: Mapping[str, object],
                    given: Iterable[str] | None = None) -> PairParameters:
    """The pair of the pair inputs given by name (missing ones at their defaults,
    :func:`resolve`), checked for an admissible geometry before any work starts: a refused
    design is blamed on an input the user set (:func:`check_design`)."""
    pair = {row.name: values.get(row.name) for row in PAIR_INPUTS}
    if given is None:
        given = (k for k, x in pair.items() if x is not None)
    return check_design(pair, {g for g in given if g in pair})

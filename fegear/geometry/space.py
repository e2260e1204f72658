"""The design space over two inputs: where a design is admissible and what bounds it.

A map is a grid of designs over two inputs (``x`` across, ``y`` up), the others at the values
given, each classified by :func:`~.admissible.design_defect` (admissible, or the kind of its
defect), and per grid row the edges of the admissible interval in ``x`` that a refusal states
(:func:`~.refusal.interval`), with the reason found just past each edge. ``fegear profile
--map h1,f1`` draws it (:func:`~.plot.map_png`) and writes its table.

>>> from fegear.geometry.space import map_row
>>> row = map_row({}, "h1", "f1", 0.15, [0.3, 0.9])
>>> row.kinds
('', 'loop')
>>> round(row.upper, 3), row.upper_reason          # the edge a refusal of h1 states
(0.831, 'loop')
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from .admissible import design_defect
from .refusal import _span, interval

#: the span a map takes for an input when none is given (the inputs' own spans are wider than
#: any design a designer draws: h1 up to 2, f1 up to 1)
MAP_SPANS = {"h1": (0.05, 1.0), "f1": (0.0, 0.6)}


@dataclass(frozen=True)
class MapRow:
    """One row of a map: the value of ``y``, the kind of defect at each ``x`` of the grid
    ('' where admissible), and the admissible interval of ``x`` nearest the given value with
    the kind of defect just past each end (``None``: the interval reaches the span's end or
    there is none)."""

    y: float
    kinds: tuple[str, ...]
    lower: float | None
    upper: float | None
    lower_reason: str | None
    upper_reason: str | None


@dataclass(frozen=True)
class DesignMap:
    """A design-space map: the two inputs, their grid values and the rows (bottom first)."""

    x: str
    y: str
    xs: tuple[float, ...]
    rows: tuple[MapRow, ...]
    values: dict

    @property
    def ys(self) -> tuple[float, ...]:
        return tuple(r.y for r in self.rows)

    def kinds(self) -> np.ndarray:
        """(len(ys), len(xs)) array of the defect kinds ('' admissible)."""
        return np.array([r.kinds for r in self.rows], dtype=object)


def map_span(name: str, values: Mapping[str, object]) -> tuple[float, float]:
    """The span a map takes for input ``name`` at the other inputs' values."""
    span = _span(name, values)
    if span is None:
        raise ValueError(f"no span for {name!r} at these values")
    lo, hi = MAP_SPANS.get(name, span)
    return max(lo, span[0]), min(hi, span[1])


def map_row(values: Mapping[str, object], x: str, y: str, y_value: float,
            xs: Sequence[float]) -> MapRow:
    """The row of a map at ``y = y_value`` over the grid ``xs`` of ``x``."""
    at = {k: v for k, v in values.items() if v is not None and k != x}
    at[y] = y_value
    kinds = []
    for xv in xs:
        found = design_defect({**at, x: float(xv)})
        kinds.append("" if found is None else found.kind)
    given = values.get(x)
    start = {**at, x: given} if given is not None else dict(at)
    bounds = interval(start, x)
    lo, hi = _span(x, at) or (min(xs), max(xs))
    if bounds is None:
        return MapRow(y_value, tuple(kinds), None, None, None, None)
    step = 1e-3 * (hi - lo)

    def past(edge: float, direction: int) -> str | None:
        beyond = edge + direction * step
        if not lo <= beyond <= hi:
            return None
        found = design_defect({**at, x: beyond})
        return None if found is None else found.kind

    return MapRow(y_value, tuple(kinds), bounds[0], bounds[1], past(bounds[0], -1),
                  past(bounds[1], +1))


def design_map(values: Mapping[str, object], x: str, y: str, size: int = 21,
               x_span: tuple[float, float] | None = None,
               y_span: tuple[float, float] | None = None, rows=map) -> DesignMap:
    """The map of inputs ``x`` and ``y`` over ``size`` × ``size`` designs, the others at
    ``values`` (missing ones at their defaults). ``rows``: a map function that computes the
    rows (the command line passes a process pool's)."""
    values = {k: v for k, v in values.items() if v is not None}
    xs = np.linspace(*(x_span or map_span(x, values)), size)
    ys = np.linspace(*(y_span or map_span(y, values)), size)
    args = [(values, x, y, float(yv), tuple(float(v) for v in xs)) for yv in ys]
    out = tuple(rows(_row_of, args))
    return DesignMap(x, y, tuple(float(v) for v in xs), out, dict(values))


def _row_of(args) -> MapRow:
    return map_row(*args)


def map_tables(dm: DesignMap) -> tuple[list[str], list[list], list[str], list[list]]:
    """The map as two tables (header, rows): every grid design with its defect kind, and every
    row's admissible interval of x with the reason past each end."""
    grid = [[r.y, xv, k or "admissible"] for r in dm.rows for xv, k in zip(dm.xs, r.kinds)]
    edges = [[r.y, "" if r.lower is None else r.lower, r.lower_reason or "",
              "" if r.upper is None else r.upper, r.upper_reason or ""] for r in dm.rows]
    return ([dm.y, dm.x, "design"], grid,
            [dm.y, f"{dm.x}_lower", "reason_below", f"{dm.x}_upper", "reason_above"], edges)

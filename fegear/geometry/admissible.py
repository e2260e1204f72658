"""Admissibility of the tooth geometry: which (h1, f1) give a usable pair.

Three ways a compound-cycloid pair fails, checked on one gear-2 tooth period (the curves are
periodic) with exact derivatives:

* ``loop``: the gear-2 curve (nominal or the Δ2 tool) is not star-shaped about its centre
  (``P × P' <= 0`` somewhere): it loops or folds back;
* ``no conjugate``: the gear-2 normal misses the instantaneous-centre circle for part of the
  flank (negative discriminant of the meshing equation), so that part has no conjugate point
  on gear 1;
* ``undercut``: the working (near-side) branch of gear 1 has a cusp below gear 1's tip radius.

Refusals name one parameter with its admissible interval at the other parameters' values,
found by bisection (the failure sets grow with h1 and with f1).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from dataclasses import replace

import numpy as np

from ..errors import ParameterError
from .envelope import NEAR, Branch
from .gear2 import gear2_curve
from .parameters import BUILT, PAIR_INPUTS, PairParameters, built_modification

SAMPLES = 2048


def defect(p: PairParameters) -> str | None:
    """Return a short reason if ``p`` is not an admissible geometry, else ``None``."""
    xi = np.linspace(-np.pi / p.z2, np.pi / p.z2, SAMPLES + 1)
    for tool in (False, True):
        if gear2_curve(p, tool).polar_rate(xi).min() <= 0.0:
            return "the gear-2 curve loops (it is not star-shaped about its centre)"
    near = Branch(gear2_curve(p, tool=True), p.e + p.shift, p.z2, p.z1, NEAR).evaluate(xi)
    if near.disc.min() <= 0.0:
        return ("part of the gear-2 flank has no conjugate point (its normal misses the pitch "
                "circle)")
    tip = p.r0 - 2 * p.e1 + p.e - p.radial_tip_clearance
    working = near.radius <= tip
    speed = near.speed[working]
    if speed.size and (np.any(np.sign(speed) != np.sign(speed[0])) or np.any(speed == 0)):
        return "gear 1 would be undercut (cusp on its working flank)"
    return None


def _defect_at(p: PairParameters, **change) -> str | None:
    """:func:`defect` of ``p`` with ``change`` made; a change the parameters refuse (a shift
    beyond m h1/4, say) is a defect too."""
    try:
        q = replace(p, **change)
    except ParameterError as exc:
        return str(exc)
    return defect(q)


def _limit(p: PairParameters, name: str, lo: float, hi: float) -> float:
    """Largest admissible value of ``name`` in ``[lo, hi]`` (``lo`` admissible), by bisection."""
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if _defect_at(p, **{name: mid}) is None else (lo, mid)
        if hi - lo < 1e-5:
            break
    return lo


def _h1_floor(p: PairParameters) -> float:
    """The smallest h1 the pair's modifications allow (shift, |rotation| <= m h1/4, tip
    clearance <= m h1), and above 0."""
    need = max(4.0 * p.shift, 4.0 * abs(p.rotation), p.tip_clearance or 0.0) / p.m
    return max(1e-3, need * (1.0 + 1e-9))


def check_admissible(p: PairParameters, given: frozenset[str] | set[str] = frozenset()
                     ) -> None:
    """Raise :class:`ParameterError` if the geometry is not admissible.

    The error names h1 or f1 with its interval at the other parameters' values and adds the
    other one's limit as an alternative. It names the one of the two the user changed
    (``given``: the names of the inputs set, not left at their defaults); if both or neither,
    the one that needs the smaller relative change (f1 if the curve loops).
    """
    reason = defect(p)
    if reason is None:
        return
    others = (f"m={p.m:g}, z2={p.z2}, z1={p.z1}, shift={p.shift:g}, rotation={p.rotation:g} "
              "mm")
    h1_lo = _h1_floor(p)
    f1_max = _limit(p, "f1", 0.0, p.f1) if _defect_at(p, f1=0.0) is None else None
    h1_max = (_limit(p, "h1", h1_lo, p.h1) if h1_lo < p.h1 and _defect_at(p, h1=h1_lo) is None
              else None)
    # the limits are rounded inwards, so the stated interval holds at its ends
    f1_text = None if f1_max is None else f"0 <= f1 <= {math.floor(f1_max * 1e4) / 1e4:.4f}"
    h1_text = None if h1_max is None else (f"{math.ceil(h1_lo * 1e4 - 1e-6) / 1e4:.4g} <= h1 <= "
                                           f"{math.floor(h1_max * 1e4) / 1e4:.4f}")
    over_f = p.f1 / f1_max if f1_max else np.inf
    over_h = p.h1 / h1_max if h1_max else np.inf
    changed = {"h1", "f1"} & set(given)
    if len(changed) == 1:
        blame_f1 = changed == {"f1"} and f1_text is not None or h1_text is None
    else:
        blame_f1 = f1_text is not None and ("loops" in reason or over_f < over_h)
    if blame_f1 and f1_text is not None:
        extra = f" (or {h1_text})" if h1_text else ""
        raise ParameterError("f1", p.f1, f"{f1_text} at h1={p.h1:g}, {others}{extra}", reason)
    if h1_text is None:
        raise ParameterError("h1", p.h1, f"none at f1={p.f1:g}, {others}", reason)
    extra = f" (or {f1_text})" if f1_text else ""
    raise ParameterError("h1", p.h1, f"{h1_text} at f1={p.f1:g}, {others}{extra}", reason)


def admissible_pair(values: Mapping[str, object],
                    given: Iterable[str] | None = None) -> PairParameters:
    """The pair of the pair inputs given by name (:data:`~.parameters.PAIR_INPUTS`, missing ones
    at their defaults; shift and rotation by :func:`~.parameters.built_modification`), checked
    for an admissible geometry before any work starts. A refused design is blamed on an input
    the user set (``given``, default: those in ``values``) where the choice is open
    (:func:`check_admissible`)."""
    v = {row.name: values.get(row.name, row.default) for row in PAIR_INPUTS}
    for name in BUILT:
        if v[name] is None:
            try:
                m, h1 = float(v["m"]), float(v["h1"])
            except (TypeError, ValueError):
                m, h1 = 0.0, 0.0   # the parameters refuse m or h1 first
            v[name] = built_modification(name, m, h1)
    p = PairParameters(**{row.dest: v[row.name] for row in PAIR_INPUTS})
    if given is None:
        given = (k for k, x in values.items() if x is not None)
    check_admissible(p, set(given))
    return p

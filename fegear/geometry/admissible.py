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

from collections.abc import Mapping
from dataclasses import replace

import numpy as np

from ..errors import ParameterError
from .envelope import NEAR, Branch
from .gear2 import gear2_curve
from .parameters import PAIR_INPUTS, PairParameters

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


def _limit(p: PairParameters, name: str, lo: float, hi: float) -> float:
    """Largest admissible value of ``name`` in ``[lo, hi]`` (``lo`` admissible), by bisection."""
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        try:
            ok = defect(replace(p, **{name: mid})) is None
        except ParameterError:
            ok = False
        lo, hi = (mid, hi) if ok else (lo, mid)
        if hi - lo < 1e-5:
            break
    return lo


def check_admissible(p: PairParameters) -> None:
    """Raise :class:`ParameterError` if the geometry is not admissible.

    The error names the parameter (h1 or f1) that needs the smaller relative change to become
    admissible, with its interval at the other parameters' values, and adds the other
    parameter's limit as an alternative.
    """
    reason = defect(p)
    if reason is None:
        return
    others = f"m={p.m:g}, z2={p.z2}, z1={p.z1}"
    h1_small = 1e-3
    f1_max = _limit(p, "f1", 0.0, p.f1) if defect(replace(p, f1=0.0)) is None else None
    h1_max = _limit(p, "h1", h1_small, p.h1) if defect(replace(p, h1=h1_small)) is None else None
    f1_text = None if f1_max is None else f"0 <= f1 <= {f1_max:.4f} at h1={p.h1:g}, {others}"
    h1_text = None if h1_max is None else f"0 < h1 <= {h1_max:.4f} at f1={p.f1:g}, {others}"
    over_f = p.f1 / f1_max if f1_max else np.inf
    over_h = p.h1 / h1_max if h1_max else np.inf
    blame_f1 = f1_text is not None and ("loops" in reason or over_f < over_h)
    if blame_f1:
        extra = f" (or {h1_text.split(' at ')[0]})" if h1_text else ""
        raise ParameterError("f1", p.f1, f1_text + extra, reason)
    if h1_text is None:
        raise ParameterError("h1", p.h1, f"none at f1={p.f1:g}, {others}", reason)
    extra = f" (or {f1_text.split(' at ')[0]})" if f1_text else ""
    raise ParameterError("h1", p.h1, h1_text + extra, reason)


def admissible_pair(values: Mapping[str, object]) -> PairParameters:
    """The pair of the pair inputs given by name (:data:`~.parameters.PAIR_INPUTS`, missing ones
    at their defaults), checked for an admissible geometry before any work starts."""
    given = {row.name: values.get(row.name, row.default) for row in PAIR_INPUTS}
    p = PairParameters(**{row.dest: given[row.name] for row in PAIR_INPUTS})
    check_admissible(p)
    return p

"""Miner's rule on an S-N line (ISO 6336-6:2019, the linear damage sum): a load spectrum's
damage, the life it gives and the safety factor it leaves (docs/rating.md, "Miner's sum").

Each level i is a stress σ_i met n_i times; the line gives N_i, the cycles σ_i alone would last
(:meth:`~.life.LifeCurve.cycles`), and the damage is D = Σ n_i / N_i: the spectrum wears the
flank or root out when D reaches 1. A level at or below the endurance limit does no damage (the
line is flat beyond its knee); one above the static value breaks the tooth at once (D = inf).
The safety factor at the required life is the factor on every level's stress that brings D to
exactly 1 over that life: what a static factor is to one stress, for a whole spectrum.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from scipy.optimize import brentq

from .life import LifeCurve


def damage(stresses: Sequence[float], cycles: Sequence[float], limit: float,
           curve: LifeCurve) -> float:
    """Miner's sum of the levels' ``stresses`` (MPa), each met ``cycles`` times, on ``curve``
    whose endurance limit is ``limit`` (MPa)."""
    total = 0.0
    for stress, n in zip(stresses, cycles):
        if n <= 0:
            continue
        lasts = curve.cycles(stress / limit)
        if lasts == 0.0:
            return math.inf
        total += n / lasts
    return total


def safety_at_life(stresses: Sequence[float], cycles: Sequence[float], limit: float,
                   curve: LifeCurve) -> float:
    """The factor x on every level's stress at which their damage over ``cycles`` is 1: inf
    where no level is loaded."""
    loaded = [(s, n) for s, n in zip(stresses, cycles) if n > 0 and s > 0]
    if not loaded:
        return math.inf
    peak = max(s for s, _ in loaded)
    # between the static value on the largest stress (x above: it breaks at once, D = inf)
    # and the endurance limit on it (x below: no level does damage, D = 0)
    lo, hi = limit / peak, curve.static * limit / peak
    ss, ns = [s for s, _ in loaded], [n for _, n in loaded]

    def excess(x: float) -> float:
        d = damage([x * s for s in ss], ns, limit, curve)
        return math.log(d) if 0 < d < math.inf else (-50.0 if d == 0 else 50.0)

    if excess(lo * (1 + 1e-12)) >= 0:   # the limit itself is exhausted: the largest alone
        return lo
    if excess(hi) < 0:
        return hi
    return math.exp(brentq(lambda logx: excess(math.exp(logx)), math.log(lo), math.log(hi),
                           xtol=1e-14, rtol=1e-13))

"""Quantiles of what sampled pairs carry, each with its statistical error (docs/tolerance.md,
"Reading the quantiles").

A quantile of N samples is itself a random number: another N pairs give another value. Its
standard error is estimated by the bootstrap (Efron): the N values drawn again with
replacement :data:`RESAMPLES` times, the quantile taken of each, and the spread of those taken
as the error (``scipy.stats.bootstrap``'s standard error). It needs no assumption about the
distribution, which for a root stress over deviated pairs is skewed and bounded by the class's
tolerances. The quantile is numpy's default (linear between order statistics). A value of
+inf (a pair that fails outright: it jams) counts as beyond every finite one: a quantile that
falls among them is +inf, its error too where any resample's does.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

#: the quantiles a designer reads beside the worst
QUANTILES = (0.5, 0.95, 0.99)
#: the bootstrap's resamples: their own scatter is then about 2 % of the error they estimate
RESAMPLES = 1000
#: where +inf stands, in multiples of beyond the largest finite value
_BEYOND = 1e6


@dataclass(frozen=True)
class Quantile:
    """The ``q`` quantile of ``n`` values and its bootstrap standard ``error`` (the values'
    unit)."""

    q: float
    value: float
    error: float
    n: int


def quantiles(values, qs=QUANTILES, resamples: int = RESAMPLES, seed: int = 0
              ) -> tuple[Quantile, ...]:
    """The quantiles ``qs`` of ``values`` (NaN where there are none) with their bootstrap
    errors (module docstring; ``seed``: the resampling's, so that a table is the same each
    time it is made)."""
    x = np.asarray(values, dtype=float)
    x = x[~np.isnan(x)]
    if not len(x):
        return tuple(Quantile(q, float("nan"), float("nan"), 0) for q in qs)
    # +inf as a finite stand-in beyond every value, so that the interpolation stays defined
    beyond = np.isposinf(x)
    top = 2.0 * np.abs(x[~beyond]).max() + 1.0 if (~beyond).any() else 1.0
    x = np.where(beyond, _BEYOND * top, x)
    from scipy.stats import bootstrap

    rng = np.random.default_rng(seed)
    out = []
    for q in qs:
        value = float(np.quantile(x, q))
        if len(x) > 1 and np.ptp(x) > 0:
            taken = bootstrap((x,), lambda s, axis, q=q: np.quantile(s, q, axis=axis),
                              n_resamples=resamples, vectorized=True, method="percentile",
                              rng=rng)
            error = float(taken.standard_error)
            jams = value > top or error > top
        else:   # one value, or all alike: nothing to resample
            error, jams = 0.0, value > top
        out.append(Quantile(q, math.inf if value > top else value,
                            math.inf if jams else error, len(x)))
    return tuple(out)

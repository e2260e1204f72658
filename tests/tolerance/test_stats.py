"""Quantiles and their bootstrap errors: the errors are the asymptotic ones of a normal
sample, the quantiles fall within two errors of the true ones as often as they should, and a
pair that fails outright (+inf) counts beyond every other."""

import math

import numpy as np
import pytest
from scipy.stats import norm

from fegear.tolerance import quantiles


def test_the_bootstrap_errors_are_the_asymptotic_ones_and_cover_the_truth():
    qs = (0.5, 0.95, 0.99)
    errors, hits = [], []
    for seed in range(30):
        found = quantiles(np.random.default_rng(seed).normal(0, 1, 1000), qs, seed=seed)
        errors.append([q.error for q in found])
        hits.append([abs(q.value - norm.ppf(q.q)) <= 2 * q.error for q in found])
    for i, q in enumerate(qs):
        asymptotic = math.sqrt(q * (1 - q) / 1000) / norm.pdf(norm.ppf(q))
        assert np.mean([e[i] for e in errors]) == pytest.approx(asymptotic, rel=0.12)
    assert np.mean(hits) >= 0.85          # 95 % expected; 30 × 3 draws


def test_failed_pairs_count_beyond_every_value():
    x = list(np.random.default_rng(1).normal(10, 1, 100)) + [math.inf] * 3
    p50, p95, p99 = quantiles(x, (0.5, 0.95, 0.99))
    assert math.isfinite(p50.value) and math.isfinite(p50.error) and p50.n == 103
    assert math.isfinite(p95.value)        # below the three failed pairs …
    assert p95.error == math.inf           # … but some resamples reach them
    assert p99.value == math.inf


def test_no_values_give_nan():
    (q,) = quantiles([math.nan], (0.5,))
    assert math.isnan(q.value) and q.n == 0

"""The runs of a generating branch: the stretches of one gear-2 pitch on which the branch's
polar angle about gear 1's centre is monotone, with no cusp, no jump and a conjugate point at
every parameter. Gear 1's lower envelope is made of pieces of runs (:mod:`.gear1`).

Where the meshing equation's discriminant is negative, the gear-2 normal misses the
instantaneous-centre circle: that stretch of gear 2 has no conjugate point, never touches the
envelope in the relative motion and so never shapes gear 1. It is left out, and its ends are
folds where the branch turns into the other one (docs/geometry.md, "Admissible designs").
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .envelope import Branch
from .roots import brentq

SAMPLES_PER_RUN = 1024


@dataclass(frozen=True)
class Run:
    """Cusp-free stretch ``[xi0, xi1]`` of a branch; φ is monotone on it."""

    branch: int
    xi0: float
    xi1: float
    increasing: bool  # φ increases with ξ


def split_runs(b: Branch, index: int, n: int = SAMPLES_PER_RUN) -> list[Run]:
    """Cut one gear-2 pitch of a branch into φ-monotone runs without jumps.

    Cuts are placed exactly at cusps (dφ/dξ = 0), where β leaves its 2π window (a jump of
    whole gear-1 pitches, harmless since gear 1 is periodic, but not continuous) and where
    the meshing equation's discriminant vanishes: a stretch of the gear-2 curve whose normal
    misses the instantaneous-centre circle has no point on this branch (it never shapes gear
    1: the envelope of a moving curve is made of its conjugate points alone), so it is left
    out, and its ends are folds where the branch turns into the other one.
    """
    half = np.pi / b.z2
    xi = np.linspace(-half, half, n + 1)
    pts = b.evaluate(xi)

    def disc(x: float) -> float:
        return float(b.evaluate(np.array([x])).disc[0])

    # the stretches with a conjugate point, ends at the discriminant's exact zeros
    folds = [brentq(disc, xi[i], xi[i + 1], xtol=1e-15)
             for i in np.nonzero(np.sign(pts.disc[:-1]) * np.sign(pts.disc[1:]) < 0)[0]]
    edges = np.concatenate([[xi[0]], folds, [xi[-1]]])
    stretches = [(a, c) for a, c in zip(edges[:-1], edges[1:])
                 if c - a > 1e-14 and disc(0.5 * (a + c)) > 0]
    runs = []
    for a, c in stretches:
        runs.extend(_monotone_runs(b, index, a, c, max(16, int(n * (c - a) / (2 * half)))))
    return runs


def _monotone_runs(b: Branch, index: int, lo: float, hi: float, n: int) -> list[Run]:
    """The φ-monotone runs of a branch on ``[lo, hi]``, where it has conjugate points."""
    # a fold's end point has an infinite speed: sample just inside it
    inset = 1e-12 * (hi - lo)
    xi = np.linspace(lo + inset, hi - inset, n + 1)
    pts = b.evaluate(xi)
    rate = pts.polar_rate

    def g(x: float) -> float:
        return float(b.evaluate(np.array([x])).polar_rate[0])

    def beta(x: float) -> float:
        return float(b.evaluate(np.array([x])).beta[0])

    cuts = [lo, hi]
    for i in np.nonzero(np.sign(rate[:-1]) * np.sign(rate[1:]) < 0)[0]:
        cuts.append(brentq(g, xi[i], xi[i + 1], xtol=1e-15))
    for i in np.nonzero(np.abs(np.diff(pts.beta)) > np.pi)[0]:
        a, c = xi[i], xi[i + 1]
        b_lo = beta(a)
        for _ in range(60):
            mid = 0.5 * (a + c)
            a, c = (mid, c) if abs(beta(mid) - b_lo) < np.pi else (a, mid)
        cuts.extend([a, c])
    cuts = np.sort(np.array(cuts))
    runs = []
    for a, c in zip(cuts[:-1], cuts[1:]):
        if c - a <= 1e-14:
            continue
        runs.append(Run(index, float(a), float(c), bool(g(0.5 * (a + c)) > 0)))
    return runs

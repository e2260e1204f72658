"""The S-N curves of ISO 6336 as life factors: how much more than its endurance limit a flank or
a root carries for a given number of load cycles (docs/rating.md, "Life factors").

ISO 6336-2:2019 (Table 2, Z_NT, pitting) and ISO 6336-3:2019 (Table 4, Y_NT, tooth root) give
each factor as straight lines on log-log axes through tabulated points: a static value up to a
first number of cycles, 1.0 at the knee, and 1.0 beyond it (the standard's value under optimum
conditions of material, manufacture and experience; it allows 0.85 at 10^10 otherwise, which
fegear does not take). The slope between is the curve's exponent: N·σ^k is constant on it, so
the stress that lasts N cycles is the limit times (N_knee / N)^(1/k).

The material's treatment picks the line: through-hardened (St, V: 42CrMo quenched and
tempered), case-hardened (Eh: 20CrMnTi, 18CrNiMo7-6) or nitrided (NT, NV).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

#: the treatments whose lines are tabulated
TREATMENTS = ("through-hardened", "case-hardened", "nitrided")


@dataclass(frozen=True)
class LifeCurve:
    """One S-N line as a life factor: ``static`` up to ``first`` load cycles, falling on a
    log-log line to 1.0 at the ``knee``, 1.0 beyond."""

    static: float
    first: float
    knee: float

    @property
    def exponent(self) -> float:
        """k of N·σ^k = const on the sloped part."""
        return math.log(self.knee / self.first) / math.log(self.static)

    def factor(self, cycles: float) -> float:
        """The life factor (Z_NT or Y_NT) at ``cycles`` load cycles."""
        if cycles <= self.first:
            return self.static
        if cycles >= self.knee:
            return 1.0
        return (self.knee / cycles) ** (1.0 / self.exponent)

    def cycles(self, ratio: float) -> float:
        """The load cycles a stress ``ratio`` times the endurance limit lasts: inf at or below
        the limit, 0 above the static value (it breaks at once), on the line between."""
        if ratio <= 1.0:
            return math.inf
        if ratio > self.static:
            return 0.0
        return self.knee * ratio ** (-self.exponent)


#: Z_NT, pitting, where no pitting is permitted (ISO 6336-2:2019 Table 2; where some is, the
#: standard's line runs longer, to 10^9: fegear takes the stricter one)
CONTACT = {"through-hardened": LifeCurve(1.6, 1e5, 5e7),
           "case-hardened": LifeCurve(1.6, 1e5, 5e7),
           "nitrided": LifeCurve(1.3, 1e5, 2e6)}
#: Y_NT, tooth root (ISO 6336-3:2019 Table 4)
BENDING = {"through-hardened": LifeCurve(2.5, 1e4, 3e6),
           "case-hardened": LifeCurve(2.5, 1e3, 3e6),
           "nitrided": LifeCurve(1.6, 1e3, 3e6)}

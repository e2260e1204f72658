"""Flank and edge pressure apart, per gear-1 tooth.

A tooth whose contact runs onto its tip round carries two contacts in one: the flank's (with its
relief), whose peak Hertz describes, and the edge's, a cylinder of the round's radius pressed
into gear 2, whose peak depends on that radius (docs/model.md, "Tip edges"). The edge pressure
is the largest pressure on the round; the edge load the force the round carries. The edge's
pressure spreads onto the flank and falls off over a few of its own Hertz half-widths
b_e = √(4 q ρ / (π E*)) (q the round's load per unit face width, ρ its radius): the flank
pressure is the largest pressure on the flank farther than ``EDGE_ZONE`` b_e from the round.
On the baseline at 200 N·m this reads 571 and 650 MPa on teeth 10 and 11 at `standard` (560
and 656 at `coarse`), beside a flank plateau of about 600 MPa; at 2 b_e tooth 11 would still
read the edge's tail (762 MPa).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

EDGE_ZONE = 3.0   # flank points within this many edge half-widths of the round are the edge's


@dataclass(frozen=True)
class FlankEdge:
    """One tooth's flank pressure, edge pressure (MPa) and the load on its round (N)."""

    flank_MPa: float
    edge_MPa: float
    edge_load_N: float

    @property
    def edge(self) -> bool:
        """Whether the round carries load."""
        return self.edge_load_N > 0


def flank_and_edge(s: np.ndarray, pressure: np.ndarray, on_round: np.ndarray,
                   thickness: float, radius: float, E_star: float) -> FlankEdge:
    """Split a tooth's pressure ``pressure`` (MPa) at arc positions ``s`` (mm, increasing,
    piecewise linear between them) into flank and edge, ``on_round`` marking the points on a
    tip round of ``radius`` (mm); face width ``thickness`` (mm), contact modulus ``E_star``."""
    s, p = np.asarray(s, dtype=float), np.maximum(np.asarray(pressure, dtype=float), 0.0)
    on_round = np.asarray(on_round, dtype=bool)
    if not on_round.any() or p[on_round].max() <= 0:
        return FlankEdge(float(p.max(initial=0.0)), 0.0, 0.0)
    q = _round_load(s, p, on_round)                  # N/mm
    b_edge = math.sqrt(4.0 * q * radius / (math.pi * E_star)) if radius > 0 else 0.0
    r = s[on_round]                                   # increasing with s
    j = np.searchsorted(r, s)
    distance = np.minimum(np.abs(s - r[np.maximum(j - 1, 0)]),
                          np.abs(s - r[np.minimum(j, len(r) - 1)]))
    flank = ~on_round & (distance > EDGE_ZONE * b_edge)
    return FlankEdge(float(p[flank].max(initial=0.0)), float(p[on_round].max()),
                     q * thickness)


def _round_load(s: np.ndarray, p: np.ndarray, on_round: np.ndarray) -> float:
    """∫ p ds (N/mm) over the stretches between consecutive points both on the round, and half
    of each stretch from a round point to a flank point."""
    mid = 0.5 * (p[1:] + p[:-1]) * np.diff(s)
    share = 0.5 * (on_round[1:].astype(float) + on_round[:-1].astype(float))
    return float(mid @ share)

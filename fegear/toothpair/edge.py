"""Flank and edge pressure apart, per gear-1 tooth.

A tooth whose contact runs onto its tip round carries two contacts in one: the flank's (with its
relief), whose peak Hertz describes, and the edge's, a cylinder of the round's radius pressed
into gear 2, whose peak depends on that radius (docs/model.md, "Tip edges"). The edge pressure
is the largest pressure on the round; the edge load the force the round carries. The edge's
pressure spreads onto the flank and falls off with the distance from the round, measured in
the edge's own Hertz half-width b_e = 2 ρ p_e / E* (p_e the round's largest pressure, ρ its
radius: :func:`edge_half_width`). On these near-conformal flanks it falls off slowly: on the
baseline's tooth 11 at 200 N·m (`standard`, b_e = 9.1 µm) the pressure reads 944, 755, 656,
619 and 596 MPa at 1, 3, 6, 10 and 20 b_e from the round. The flank pressure is the largest
pressure on the flank from ``EDGE_ZONE`` b_e on, the pressure at that distance included: 619
MPa there, the same within 1 % at `coarse`, `standard` and `fine` (614 / 619 / 620), and 4 %
above its value at 20 b_e. Tooth 10's flank carries its own peak (571 MPa) beyond its edge's
tail.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

EDGE_ZONE = 10.0  # flank points within this many edge half-widths of the round are the edge's


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
    b_edge = edge_half_width(float(p[on_round].max()), radius, E_star)
    r = s[on_round]                                   # increasing with s
    j = np.searchsorted(r, s)
    distance = np.minimum(np.abs(s - r[np.maximum(j - 1, 0)]),
                          np.abs(s - r[np.minimum(j, len(r) - 1)]))
    cut = EDGE_ZONE * b_edge
    flank = ~on_round & (distance > cut)
    # where the zone ends, the pressure interpolated there (p is linear between the points): the
    # flank value then moves continuously with the grid, not by whole intervals (it moved by
    # 2.3 % one gear-2 pitch later, where the points fall differently)
    ends = [e for e in (s[on_round][0] - cut, s[on_round][-1] + cut) if s[0] <= e <= s[-1]]
    at_ends = [float(np.interp(e, s, p)) for e in ends]
    return FlankEdge(max([float(p[flank].max(initial=0.0)), *at_ends]),
                     float(p[on_round].max()), q * thickness)


def edge_half_width(peak: float, radius: float, E_star: float) -> float:
    """The edge's Hertz half-width (mm) from the round's largest pressure ``peak`` (MPa):
    b_e = 2 ρ p₀ / E*, the cylinder's relation p₀ = E* b / (2ρ). From the round's load it would
    be the same for a Hertz edge, but the load is ill-conditioned where the contact peaks at
    the round's tangent point: the peak falls within µm on either side of it as the round is
    meshed, and moves a third of the tooth's load between round and flank with it, where the
    round's largest pressure moves by a tenth (module docstring)."""
    return 2.0 * radius * peak / E_star


def flank_centre(x: np.ndarray, pressure: np.ndarray, on_round: np.ndarray) -> float:
    """Where along ``x`` (any coordinate of the points) the flank carries its load: the mean of
    ``x`` weighted by the pressure off the round; the peak's ``x`` if the flank carries none."""
    w = np.where(on_round, 0.0, np.maximum(pressure, 0.0))
    return float(w @ x / w.sum()) if w.sum() > 0 else float(x[np.argmax(pressure)])


def _round_load(s: np.ndarray, p: np.ndarray, on_round: np.ndarray) -> float:
    """∫ p ds (N/mm) over the stretches between consecutive points both on the round, and half
    of each stretch from a round point to a flank point."""
    mid = 0.5 * (p[1:] + p[:-1]) * np.diff(s)
    share = 0.5 * (on_round[1:].astype(float) + on_round[:-1].astype(float))
    return float(mid @ share)

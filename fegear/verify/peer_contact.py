"""Contact pressure beside CalculiX, read alike (``fegear bench --contact-peer``).

CalculiX's own contact output is a pointwise penalty pressure (CSTR) at its slave integration
points. In these gear decks about 30 % of the contact area carries no contact spring and the
points scatter ±30 % within a facet, so its largest CSTR sits 1.9-3.2× above the pressure
the contact transmits. Here both codes are read the same way (docs/benchmark.md,
"CalculiX"): ccx's displacements times our stiffness give gear 1's nodal forces, averaged
over our contact nodes' hats (:func:`~fegear.verify.penalty.forces_from_body`); ours are our
own node forces; both are then read per facet
(:func:`~fegear.verify.calculix_pair.facet_reading`).

Two cases on the baseline pair (shift 0.016, rotation 0.002), at ``coarse`` and ``fast``: an
edge case (200 N·m, β = 0, no relief: the first-touching teeth press on gear 1's tip round) and
a flank-only case (50 N·m, β = 2°). The comparison is per loaded tooth: the peak facet
pressure, the half-width and the round's load, with the CSTR maximum beside them.
"""

from __future__ import annotations

import math
import tempfile
from dataclasses import dataclass

from ..geometry import PairParameters
from .sector import SectorCase

#: (name, torque N·m, β rad): where the peak sits on the tip round, and where none touches it
CASES = (("edge", 200.0, 0.0), ("flank", 50.0, math.radians(2.0)))
LEVELS = ("coarse", "fast")
#: the agreement asked for: peak facet pressure and half-width per loaded tooth (%)
PRESSURE_TOL_PCT, WIDTH_TOL_PCT = 3.0, 2.0


@dataclass(frozen=True)
class ToothPeer:
    """One loaded tooth: ours and ccx's peak facet pressure (MPa), half-width (mm), the round's
    load (N); ours as reported (nodal peak, MPa); ccx's largest CSTR (MPa); the tooth's load
    (N, ours), the elements across its half-width and whether that resolves it (as the tooth
    table gives them)."""

    tooth: int
    load_N: float
    ours_p: float
    ccx_p: float
    ours_b: float
    ccx_b: float
    ours_edge_N: float
    ccx_edge_N: float
    reported_p: float
    cstr_max: float
    facets_per_b: float
    resolved: bool

    @property
    def p_err_pct(self) -> float:
        return 100.0 * (self.ccx_p / self.ours_p - 1.0)

    @property
    def b_err_pct(self) -> float:
        return 100.0 * (self.ccx_b / self.ours_b - 1.0)

    @property
    def agrees(self) -> bool:
        return (abs(self.p_err_pct) <= PRESSURE_TOL_PCT
                and abs(self.b_err_pct) <= WIDTH_TOL_PCT)


@dataclass(frozen=True)
class CasePeer:
    """One case at one level: its name, torque (N·m), β (rad), loaded teeth, our solve's and
    CalculiX's wall times (s)."""

    name: str
    level: str
    torque: float
    beta: float
    teeth: tuple[ToothPeer, ...]
    ours_s: float
    ccx_s: float


def baseline_pair() -> PairParameters:
    return PairParameters(shift=0.016, rotation=0.002)


def contact_peer(name: str, torque: float, beta: float, level: str,
                 params: PairParameters | None = None,
                 timeout: float | None = None) -> CasePeer:
    """Solve one case with fegear (sector model) and CalculiX on the same meshes and compare
    the loaded teeth; ccx is killed after ``timeout`` s."""
    from .calculix_pair import (  # lazy: heavy: scikit-fem, off `fegear bench`'s check
        ccx_pair,
        facet_reading,
    )

    case = SectorCase(params or baseline_pair(), torque=torque, beta=beta, quality=level)
    with tempfile.TemporaryDirectory() as tmp:
        ours, c = ccx_pair(case, tmp, timeout=timeout)
    mine = facet_reading(ours, ours.detail.contact.force)
    teeth = []
    for k, t in enumerate(ours.teeth):
        if t.load_N <= 0:
            continue
        teeth.append(ToothPeer(
            tooth=t.tooth, load_N=t.load_N, ours_p=mine[k]["pressure"],
            ccx_p=c.tooth_pressure[k], ours_b=mine[k]["half_width"],
            ccx_b=c.tooth_half_width[k], ours_edge_N=mine[k]["edge_load"],
            ccx_edge_N=c.tooth_edge_load[k], reported_p=t.p_max_MPa,
            cstr_max=c.tooth_cstr_max[k], facets_per_b=t.per_half_width,
            resolved=t.resolved))
    return CasePeer(name, level, torque, beta, tuple(teeth),
                    sum(ours.timings_s.values()), c.wall_s)


def peer_table(results: list[CasePeer]) -> str:
    """Markdown: per case, level and loaded tooth, ours and ccx's peak facet pressure and
    half-width with their differences, the round's load, our reported peak and ccx's CSTR."""
    head = ["case", "level", "tooth", "load [N]", "p ours", "p ccx", "Δp %", "b ours [mm]",
            "b ccx [mm]", "Δb %", "round N ours / ccx", "reported p", "CSTR max",
            "CSTR / p", "el./b", "agrees"]
    lines = ["| " + " | ".join(head) + " |", "|---|---|" + "---:|" * (len(head) - 2)]
    for r in results:
        for t in r.teeth:
            lines.append("| " + " | ".join([
                r.name, r.level, str(t.tooth), f"{t.load_N:.1f}", f"{t.ours_p:.1f}",
                f"{t.ccx_p:.1f}", f"{t.p_err_pct:+.2f}", f"{t.ours_b:.4f}", f"{t.ccx_b:.4f}",
                f"{t.b_err_pct:+.2f}", f"{t.ours_edge_N:.1f} / {t.ccx_edge_N:.1f}",
                f"{t.reported_p:.1f}", f"{t.cstr_max:.1f}", f"{t.cstr_max / t.ours_p:.2f}",
                f"{t.facets_per_b:.1f}{'' if t.resolved else ' u'}",
                "yes" if t.agrees else "NO"]) + " |")
    lines += ["", "p: the largest facet-mean pressure (MPa), ccx's from its displacements times "
              "our stiffness; b: half-width from the facet loads' second moment; reported p: "
              "our nodal peak as the tables give it; CSTR max: ccx's largest integration-point "
              "penalty pressure (not a transmitted pressure); el./b: elements across the "
              "half-width, u: flagged under-resolved. Agreement asked: |Δp| <= "
              f"{PRESSURE_TOL_PCT:g} %, |Δb| <= {WIDTH_TOL_PCT:g} %."]
    lines += [f"{r.name} at `{r.level}`: ours {r.ours_s:.1f} s, ccx {r.ccx_s:.0f} s"
              for r in results]
    return "\n".join(lines)

"""How a solved position's headline stresses move with each deviation of the teeth in mesh:
d(headline)/d(deviation), MPa per µm, the derivative of the contact solve with its active set
kept (docs/tolerance.md, "Sensitivities").

At the solution the active points' gaps are closed and the torque balanced:

    g0_i(θ; δ) + Σ_j A_ij p_j = 0,        −Σ_i w_i a_i(θ; δ) p_i = T,

g0 the rigid gap, a its rate with gear 1's turn θ. A deviation δ moves g0 and a; with the
active set kept, the pressures and the rotation move by the solution of the same bordered
system the solve and the tangent stiffness solve (:func:`~.tangent.tangent_stiffness`),

    A_aa dp + a_a dθ = −∂g0_a/∂δ,     Σ w a dp + (Σ w ∂a/∂θ p) dθ = −Σ w (∂a/∂δ) p,

its matrix factorised once for every deviation. The rigid gap's rates with a deviation are
the exact geometry's, by central differences over :data:`STEP_UM` (the gap is smooth in it:
the second-order term is 1e-9 of the first). The headlines are then read at the pressures
moved a little along dp (the root stresses are linear in the pressures, σ1 and the largest
over the nodes smooth where one node carries it; the flank pressure is the flank/edge split's):
a derivative of the pressures' functions, not a solve again.

The deviations are each tooth's pitch, profile slope and form, for every gear-1 tooth with a
loaded grid and every gear-2 tooth that a loaded point faces, the centre distance, and each
gear's runout: its eccentricity's two components, reported as the largest rate over the high
point's phase, per µm of F_r (twice the eccentricity).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
from scipy.linalg import lu_factor, lu_solve

from ...fe import contact_modulus
from ...geometry import Deviations, Placed, Runout, ToothDeviation, gear2_tooth
from ...quantities import HELD
from ..edge import flank_and_edge
from .contact import RingContactSolution, rigid_gap
from .influence import ColumnRule, RingContact, assemble_contact
from .model import RingModel
from .stresses import ring_stresses
from .tangent import solved_system

#: the deviation (µm) of the rigid gap's central differences
STEP_UM = 0.01
#: the pressures are moved along dp by this share of their largest to read the headlines'
#: derivatives (central differences of functions linear or smooth in the pressures)
NUDGE = 1e-4
#: the headlines whose derivatives are formed: those held against an allowable, each a
#: function of the pressures alone (the von Mises maximum needs the submodels)
HEADLINES = tuple(q.key for q in HELD)


@dataclass(frozen=True)
class Sensitivity:
    """One deviation's rate: ``kind`` ("pitch", "slope", "form", "centre distance",
    "runout"), its ``gear`` and ``tooth`` (None for the pair's), each headline's derivative
    (MPa/µm; a runout's the largest over the high point's phase, per µm of F_r: a size, and
    ``phase_deg`` from tooth 0's centre the phase where gear 1's root stress rises most)."""

    kind: str
    gear: int | None
    tooth: int | None
    per_um: dict
    phase_deg: float | None = None

    @property
    def name(self) -> str:
        """As a table names it: "gear 1 tooth 11 pitch", "gear 2 runout", "centre distance"."""
        where = f"gear {self.gear}" + (f" tooth {self.tooth}" if self.tooth is not None else "")
        return self.kind if self.gear is None else f"{where} {self.kind}"


def sensitivities(model: RingModel, contact: RingContact, sol: RingContactSolution,
                  deviations: Deviations) -> tuple[Sensitivity, ...]:
    """Every headline's derivative with every deviation of the teeth in mesh (module
    docstring) at the solved position ``sol`` on ``contact`` (with its influence matrix),
    about the pair's own ``deviations``."""
    p = model.case.params
    turn = p.ratio * contact.beta + sol.rotation
    pressure = sol.pressure
    w = contact.weight * model.case.thickness
    idx, system = solved_system(model, contact, sol)
    factors = lu_factor(system)
    base = pressure_headlines(model, contact, pressure)

    def rate(moved: Deviations, other: Deviations) -> dict:
        """The headlines' derivative between two deviation sets 2 STEP_UM apart."""
        up = rigid_gap(model, replace(contact, placed=Placed(moved, p, contact.beta)), turn,
                       contact.feet.copy())
        down = rigid_gap(model, replace(contact, placed=Placed(other, p, contact.beta)),
                         turn, contact.feet.copy())
        dg, da = (up[0] - down[0]) / (2 * STEP_UM), (up[1] - down[1]) / (2 * STEP_UM)
        rhs = np.concatenate([-dg[idx], [-(w[idx] * da[idx]) @ pressure[idx]]])
        dp = np.zeros(len(pressure))
        dp[idx] = lu_solve(factors, rhs)[:-1]
        if not np.abs(dp).max() > 0:
            return dict.fromkeys(HEADLINES, 0.0)
        eps = NUDGE * pressure.max() / np.abs(dp).max()
        hi = pressure_headlines(model, contact, pressure + eps * dp)
        lo = pressure_headlines(model, contact, pressure - eps * dp)
        return {k: (hi[k] - lo[k]) / (2 * eps) for k in base}

    out = []
    for gear, teeth in ((1, _loaded_teeth(contact, pressure)),
                        (2, _faced_teeth(contact, pressure, p.z2))):
        for tooth in teeth:
            for kind in ("pitch", "slope", "form"):
                out.append(Sensitivity(kind, gear, tooth, rate(
                    _nudged(deviations, gear, tooth, kind, STEP_UM),
                    _nudged(deviations, gear, tooth, kind, -STEP_UM))))
    cd = deviations.centre_distance
    out.append(Sensitivity("centre distance", None, None, rate(
        replace(deviations, centre_distance=cd + STEP_UM),
        replace(deviations, centre_distance=cd - STEP_UM))))
    for gear in (1, 2):
        parts = [rate(_eccentric(deviations, gear, axis, STEP_UM),
                      _eccentric(deviations, gear, axis, -STEP_UM)) for axis in (0, 1)]
        # per µm of eccentricity along each axis; F_r is twice the eccentricity: the largest
        # rate over the high point's phase is half the gradient's length, at its direction
        # (the phase given: gear 1's root stress's)
        per = {k: 0.5 * math.hypot(parts[0][k], parts[1][k]) for k in HEADLINES}
        phase = math.degrees(math.atan2(parts[1][HEADLINES[0]], parts[0][HEADLINES[0]]))
        out.append(Sensitivity("runout", gear, None, per, phase))
    return tuple(out)


def pressure_headlines(model: RingModel, contact: RingContact, pressure: np.ndarray) -> dict:
    """The headlines that the pressures alone set: each gear's largest root σ1, the largest
    contact pressure and the largest flank pressure (the flank/edge split's) (MPa)."""
    stresses = ring_stresses(model, contact, pressure, submodels=False)
    case = model.case
    E_star = contact_modulus(case.E, case.E)
    peak = flank = 0.0
    for k, grid in enumerate(contact.grids):
        pk = pressure[contact.block(k)]
        if pk.max() <= 0:
            continue
        peak = max(peak, float(pk.max()))
        flank = max(flank, flank_and_edge(grid.s, pk, grid.on_round, case.thickness,
                                          model.shape.radius_mm, E_star).flank_MPa)
    return {"root_stress_gear1_MPa": stresses.roots[0].max,
            "root_stress_gear2_MPa": stresses.roots[1].max,
            "contact_pressure_MPa": peak, "flank_contact_pressure_MPa": flank}


def _loaded_teeth(contact: RingContact, pressure: np.ndarray) -> list[int]:
    """Gear 1's teeth whose grids carry pressure."""
    return sorted({g.tooth for k, g in enumerate(contact.grids)
                   if pressure[contact.block(k)].max() > 0})


def _faced_teeth(contact: RingContact, pressure: np.ndarray, z2: int) -> list[int]:
    """Gear 2's teeth that the loaded points face (the tooth under each one's foot)."""
    feet = contact.feet[pressure > 0]
    return sorted({int(t) for t in gear2_tooth(feet, z2)})


def _nudged(deviations: Deviations, gear: int, tooth: int, kind: str, um: float) -> Deviations:
    """``deviations`` with ``um`` more of ``kind`` on ``gear``'s ``tooth``."""
    table = deviations.teeth(gear)
    d = table.get(tooth, ToothDeviation())
    table[tooth] = replace(d, **{kind: getattr(d, kind) + um})
    return replace(deviations, **{f"gear{gear}": table})


def _eccentric(deviations: Deviations, gear: int, axis: int, um: float) -> Deviations:
    """``deviations`` with ``gear``'s eccentricity moved ``um`` along ``axis`` (0: towards
    tooth 0's centre, 1: a quarter turn on), in its own frame."""
    r = getattr(deviations, f"runout{gear}")
    e = 0.5 * r.fr * np.array([math.cos(math.radians(r.phase)),
                               math.sin(math.radians(r.phase))])
    e[axis] += um
    moved = Runout(2.0 * math.hypot(*e), math.degrees(math.atan2(e[1], e[0])))
    return replace(deviations, **{f"runout{gear}": moved})


def solved_sensitivities(sol) -> tuple[Sensitivity, ...]:
    """:func:`sensitivities` of a position the ring model solved (a
    :class:`~fegear.toothpair.case.PairSolution`): its contact assembled again on its grids
    for the influence matrix a solved record does not keep."""
    d = sol.detail
    contact = assemble_contact(d.model, d.contact.grids, d.contact.beta, d.contact.turn,
                               ColumnRule(), d.contact.placed)
    return sensitivities(d.model, contact, d.solution, d.case.deviations)

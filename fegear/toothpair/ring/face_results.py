"""A position solved across the face (:mod:`.face_contact`) read as results: each section's
pair, the teeth's line loads along the face, and the face load factor.

A section's pair is what the 2D pair would be under that section's loads across the whole face:
its teeth's loads and pressures from the section's own pressures, its root stresses (and
the surface von Mises estimate) from the pressures spread as the tooth's and rim's fields take
them (a root's bending under a load at one end reaches along the face as the approach does).
So the sections' headlines read as the 2D pair's do, and an even face gives the 2D pair's
numbers in every section.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ...planar import rotate
from ..case import HEADLINE, ContactChecks, PairSolution, SolveCase
from ..face import Face
from .contact import RingContactSolution, rigid_gap
from .face import FaceCoupling
from .face_contact import FaceSolution, FaceStart, solve_face_contact
from .phases import Phases
from .readout import brief_stresses
from .results import RingDetail, tooth_results


@dataclass(frozen=True)
class FaceSections:
    """One position across the face: the sections' places and coupling, the contact's
    solution over them, each gear-1 tooth's line load (N/mm) at each section (teeth ×
    sections; the teeth with a grid, in ``teeth``) and each section's pair; the face's
    offsets of the rigid gaps (mm, points × sections), the rigid gap's rate with the turn at
    the solution (mm/rad, by point), each point's grid and where each point is (fixed frame,
    mm: gear 1 turned to the solution and placed at its centre)."""

    coupling: FaceCoupling
    solution: FaceSolution
    teeth: tuple[int, ...]
    line_loads: np.ndarray
    sections: tuple[PairSolution, ...]
    offsets: np.ndarray
    rate: np.ndarray
    grid: np.ndarray
    xy: np.ndarray

    @property
    def load_factor(self) -> float:
        """K_Hβ: the largest line load of any tooth at any section over the largest mean
        line load of a tooth across the face (the most loaded tooth's, which the 2D pair
        spreads evenly): ISO 6336-1's face load factor for a mesh whose load several teeth
        share. A tooth barely touching at one end does not set it, as its own ratio would."""
        mean = self.line_loads @ self.coupling.share
        return float(self.line_loads.max() / mean.max())

    def headline(self, s: int) -> dict[str, float]:
        """Section ``s``'s headlines (:meth:`PairSolution.headline`); where the face's offsets
        lift the section off every tooth its pressures are zero, its roots still bent by the
        loads beside it."""
        section = self.sections[s]
        if any(t.load_N > 0 for t in section.teeth):
            return section.headline()
        return {"root_stress_gear1_MPa": section.root_stress[0],
                "root_stress_gear2_MPa": section.root_stress[1],
                "contact_pressure_MPa": 0.0, "flank_contact_pressure_MPa": 0.0,
                "von_mises_max_MPa": section.von_mises_max}

    def worst_headlines(self) -> dict[str, tuple[int, float]]:
        """Each headline's worst section (where it is largest) and its value there, by
        :meth:`PairSolution.headline` key, every section's headlines read once."""
        heads = [self.headline(s) for s in range(len(self.sections))]
        out = {}
        for key in HEADLINE:
            s = int(np.argmax([head[key] for head in heads]))
            out[key] = (s, heads[s][key])
        return out


def face_sections(model, phases: Phases, case: SolveCase, state, face: Face,
                  coupling: FaceCoupling) -> FaceSections | None:
    """``case`` (its clearance ``state``) solved across the face on the contact ``phases``
    kept for its phase; None where none is kept there."""
    found = phases.contact_at(model, case)
    if found is None:
        return None
    contact, kept = found
    turn = case.params.ratio * contact.beta + kept.rotation
    offsets = face.offsets(contact, turn, coupling.zeta, case.thickness, case.params.z2)
    solved = solve_face_contact(model, contact, FaceStart(kept.rotation, kept.active,
                                                          1e-3 * kept.elastic_um),
                                case.torque_Nmm, offsets, coupling)
    strains = phases.strains(model, case.beta)
    g2, rate = rigid_gap(model, contact, case.params.ratio * contact.beta + solved.rotation,
                         contact.feet.copy())
    bare = replace(contact, A=None, former=None)

    def section(s: int) -> PairSolution:
        """Section ``s``'s pair (module docstring)."""
        p = solved.pressure[:, s]
        loaded = p > 0
        overlap = float(max(0.0, -solved.gap[loaded, s].min())) if loaded.any() else 0.0
        sol = RingContactSolution(p, solved.gap[:, s], solved.rotation, solved.iterations,
                                  solved.turns, 0.0, overlap)
        stresses = brief_stresses(model, bare, solved.spread_pressure[:, s], strains)
        detail = RingDetail(model, case, bare, sol, stresses)
        teeth = tooth_results(detail, state, (), (g2 + offsets[:, s], rate), references=False)
        return PairSolution(
            case=case, teeth=teeth,
            root_stress=(stresses.roots[0].max, stresses.roots[1].max),
            von_mises_max=stresses.von_mises_max, rotation=solved.rotation,
            first_touch=math.nan, dofs=model.dofs,
            checks=ContactChecks(0.0, overlap, solved.iterations, (), contact.npoints),
            timings_s={}, detail=detail, von_mises_estimated=True)

    return FaceSections(coupling, solved, tuple(g.tooth for g in contact.grids),
                        solved.line_loads(contact),
                        tuple(section(s) for s in range(coupling.sections)), offsets, rate,
                        contact.grid_index,
                        rotate(contact.x, case.params.ratio * contact.beta + solved.rotation)
                        + np.array([0.0, case.params.e]))

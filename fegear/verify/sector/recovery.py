"""What a designer reads off a solved position: root stresses per gear and per tooth, the
contact of each paired tooth beside Hertz, and whether its peak sits on the tip-edge round.

Root stress is the largest first principal stress on profile nodes in the lower ``ROOT_BAND``
of the tooth height (by radius), whichever mesh zone they are in; per tooth, within half a pitch
of the tooth (gear 2: the tooth it meshes with). Hertz p0 and b use gear 1's curvature at the
tooth's contact point and gear 2's where that point lands once the clearance is closed.
"""

from __future__ import annotations

import math

import numpy as np

from ...fe import Body, StressField, contact_modulus, facet_nodes
from ...planar import wrap
from ...toothpair import Candidate, ToothResult, flank_and_edge, tension_fillets
from ..penalty import ContactModel, ContactSolution
from .case import SectorCase
from .scene import SECTOR_LEVELS, Scene

#: nodes across the round's Hertz half-width an edge pressure needs: at `coarse`, 200 N·m,
#: tooth 10's round has 2.6 and its nodal pressures zig-zag (1517 / 789 / 1470 MPa), tooth
#: 11's 4.3 and reads 2.3 % over the converged value; at `fast`, 5.0 and 8.2, within 1.1 %
EDGE_PER_B = 4.5


def root_nodes(body: Body, names: tuple[str, ...], band: tuple[float, float]) -> np.ndarray:
    """Profile nodes (on boundaries ``names``) whose radius lies in ``band`` (mm, body frame):
    the root zone, whichever segment (root, flank or contact window) the nodes belong to."""
    nodes = np.unique(np.concatenate([facet_nodes(body.mesh, body.mesh.boundaries[n]).ravel()
                                      for n in names]))
    r = np.linalg.norm(body.mesh.doflocs[:, nodes], axis=0)
    return nodes[(r >= band[0] - 1e-9) & (r <= band[1] + 1e-9)]


def root_stresses(stresses: tuple[StressField, ...],
                  zones: tuple[np.ndarray, np.ndarray]) -> tuple[float, float]:
    """Largest σ1 (MPa) on each gear's root zone."""
    return (float(stresses[0].max_principal[zones[0]].max()),
            float(stresses[1].max_principal[zones[1]].max()))


def tooth_results(case: SectorCase, scene: Scene, bodies: tuple[Body, Body],
                  contact: ContactModel, sol: ContactSolution,
                  stresses: tuple[StressField, ...], zones: tuple[np.ndarray, np.ndarray],
                  cands: tuple[Candidate, ...]) -> tuple[ToothResult, ...]:
    """One :class:`ToothResult` per paired tooth (in ``scene.paired`` order)."""
    p = case.params
    g1, g2 = bodies
    pitch1, pitch2 = scene.shape.pitch, 2 * math.pi / p.z2
    torque = case.torque_Nmm
    contact_zones = {z.pair: z for z in sol.zones}
    a = contact.gap0(sol.link_value)[1]
    by_tooth = {c.tooth: c for c in cands}
    results = []
    for k, tooth in enumerate(scene.paired):
        c = by_tooth.get(tooth)
        sel = contact.pair_index == k
        cz = contact_zones.get(contact.pairs[k].name)
        load = cz.load if cz else 0.0
        hz = (c.hertz(load, case.thickness, case.E, case.nu)
              if load > 0 and c is not None else None)
        fillets = tension_fillets(scene.shape.tooth_center + tooth * pitch1, pitch1,
                                  c.theta2 if c is not None else 0.0, pitch2)
        root2 = _sector_max(g2, stresses[1], zones[1], fillets[1], pitch2) if c is not None \
            else 0.0
        results.append(ToothResult(
            tooth=tooth, clearance_um=c.clearance_um if c is not None else None, load_N=load,
            load_share=float(-(a[sel] @ sol.force[sel]) / torque),
            p_max_MPa=cz.p_max if cz else 0.0,
            half_width_mm=cz.half_width if cz else 0.0,
            hertz_p0_MPa=hz.p0 if hz else None, hertz_b_mm=hz.b if hz else None,
            b_over_R=hz.b_over_R if hz else None,
            root1_MPa=_sector_max(g1, stresses[0], zones[0], fillets[0], pitch1),
            root2_MPa=root2,
            peak_on_round=_peak_on_round(scene.shape, contact.x[sel], sol.pressure[sel]),
            **contact_split(scene.shape, contact.x[sel], sol.pressure[sel], case,
                          cz.half_width if cz else 0.0)))
    return tuple(results)


def contact_split(shape, x: np.ndarray, pressure: np.ndarray, case: SectorCase,
                  half_width: float) -> dict:
    """Flank and edge pressure (``flank_p_MPa``, ``edge_p_MPa``, ``edge_load_N``) of one
    tooth's contact points ``x`` (gear 1's frame), taken in the order of their polar angle; the
    elements across the contact's ``half_width`` (mm) at its peak, and whether they are as many
    as the quality gives a contact (on a tip round: across the round's own Hertz half-width, at
    least ``EDGE_PER_B``)."""
    if not len(pressure):
        return {}
    phi = np.arctan2(x[:, 1], x[:, 0])
    phi = phi[0] + wrap(phi - phi[0])
    order = np.argsort(phi)
    xs = x[order]
    s = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(xs, axis=0).T))])
    split = flank_and_edge(s, pressure[order], shape.on_round(phi[order]), case.thickness,
                           shape.radius_mm, contact_modulus(case.E, case.E))
    out = {"flank_p_MPa": split.flank_MPa, "edge_p_MPa": split.edge_MPa,
           "edge_load_N": split.edge_load_N}
    if half_width > 0 and len(s) > 1:
        j = int(np.argmax(pressure[order]))
        spacing = 0.5 * (s[min(j + 1, len(s) - 1)] - s[max(j - 1, 0)])
        if split.edge_load_N > 0 and split.edge_MPa >= split.flank_MPa:   # the peak's own width
            b = math.sqrt(4.0 * split.edge_load_N / case.thickness * shape.radius_mm
                          / (math.pi * contact_modulus(case.E, case.E)))
            out["per_half_width"] = float(b / spacing)
            out["resolved"] = bool(out["per_half_width"] >= EDGE_PER_B)
        else:
            out["per_half_width"] = float(half_width / spacing)
            out["resolved"] = bool(out["per_half_width"] >= SECTOR_LEVELS[case.quality][0])
    return out


def _peak_on_round(shape, x: np.ndarray, pressure: np.ndarray) -> bool:
    """Whether the largest traction at the points ``x`` (gear 1's frame) sits on a tip round."""
    if not len(pressure) or pressure.max() <= 0:
        return False
    i = int(np.argmax(pressure))
    return bool(shape.on_round(np.arctan2(x[i:i + 1, 1], x[i:i + 1, 0]))[0])


def _sector_max(body: Body, stress: StressField, nodes: np.ndarray, centre: float,
                pitch: float) -> float:
    """Largest σ1 among ``nodes`` within half a pitch of the polar angle ``centre``."""
    x = body.mesh.doflocs[:, nodes]
    near = np.abs(wrap(np.arctan2(x[1], x[0]) - centre)) <= 0.5 * pitch
    return float(stress.max_principal[nodes[near]].max()) if near.any() else 0.0

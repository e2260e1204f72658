"""A position's headline stresses read straight off the ring's condensed unknowns, without its
fields: for the many deviation sets solved on one kept contact (a tolerance class's samples).

A sector's template field is its cut motions carried inside by Ψ plus, where it is loaded, the
clamped field of its own loads (:meth:`~fegear.fe.cyclic.CyclicBody.displacement`); both are
linear, and so is the L2 projection that gives the nodal stresses. So the root zone's nodal
stresses are a fixed matrix times the sector's cut motions (2 n_f numbers) plus, for a loaded
sector, a matrix per loaded template dof times its load: both formed once per template (the
latter a column per dof, when a load first reaches it, as the side's responses are), where a
field costs a solve and a product over the whole template a sector, and its projection a
solve of the template's mass matrix. The strain along the surface at the contacts (the von
Mises estimate's) is read the same way, through the sparse rows of the points' elements.

The numbers are the full path's (:func:`~.stresses.ring_stresses` without submodels) to
rounding; what it leaves out is the largest von Mises stress away from the contacts over the
whole templates (:func:`~.stresses._bulk_von_mises`), which needs the fields: here that is the
root zones' (a sample's von Mises peak is at a contact, five times the root's on the baseline).
"""

from __future__ import annotations

import numpy as np

from ...fe import projector, stress_field
from .influence import RingContact
from .model import RingModel
from .side import GearSide
from .stresses import (
    RingStresses,
    loaded_sectors,
    root_zone,
    side_root_nodes,
    surface_tangent,
    surface_von_mises,
)


class RootReadout:
    """One gear side's root-zone nodal stresses (:func:`~.stresses.side_root_nodes`, the three
    in-plane components stacked: (3 n,)) as linear maps: ``through_cuts`` (3 n, 2 n_f) of a
    sector's cut motions, and :meth:`clamped` of the loads at template dofs."""

    def __init__(self, side: GearSide) -> None:
        body = side.body
        self.nodes = side_root_nodes(side)
        factor, parts = projector(body)
        unit = np.zeros((body.mesh.doflocs.shape[1], len(self.nodes)))
        unit[self.nodes, np.arange(len(self.nodes))] = 1.0
        inverse = factor.solve(unit)   # the mass matrix's inverse, at the nodes' rows
        rows = np.vstack([np.asarray((C.T @ inverse).T) for C in parts])   # (3 n, ndofs)
        self.through_cuts = rows[:, body.interior] @ body.psi + rows[:, body.interface]
        self._inner = np.ascontiguousarray(rows[:, body.interior])
        self._column = np.full(body.ndofs, -1, dtype=np.int64)
        self._formed = np.zeros((rows.shape[0], 0))

    def clamped(self, side: GearSide, dofs: np.ndarray) -> np.ndarray:
        """The root zone's stresses (3 n, len(dofs)) of a unit load at each template dof of
        ``dofs`` with both cuts held, formed for the dofs not met before."""
        new = np.unique(dofs[self._column[dofs] < 0])
        if len(new):
            self._column[new] = self._formed.shape[1] + np.arange(len(new))
            self._formed = np.hstack([self._formed, side.clamped_product(self._inner, new)])
        return self._formed[:, self._column[dofs]]


def readout(side: GearSide) -> RootReadout:
    """``side``'s :class:`RootReadout`, made the first time it is asked for (kept on the side,
    with its responses, for every position after)."""
    if side.readout is None:
        side.readout = RootReadout(side)
    return side.readout


class SurfaceStrains:
    """A kept contact's matching points' strain along the surface (the von Mises estimate's,
    :func:`~.stresses.surface_von_mises`) as linear maps, per gear: ``through_cuts`` (points,
    2 n_f) of the cut motions of the point's sector, and per load block (a sector's loads,
    which a contact turned by whole pitches shares) its points and the map of its loads
    (points, dofs). Made once for a contact kept for a phase, and read by every solve on it,
    whatever pitch it is turned to."""

    def __init__(self, model: RingModel, contact: RingContact) -> None:
        self.through_cuts, self.by_block = [], []
        for side, loads, m in zip(model.gears, contact.loads, contact.matching):
            body = side.body
            rows = side.rows_at(m.cells, surface_tangent(m), strain=True).tocsc()
            self.through_cuts.append(np.asarray(rows[:, body.interior] @ body.psi
                                                + rows[:, body.interface]))
            place = np.full(contact.npoints, -1)
            blocks = {}
            for t, b in loads.items():
                points = np.flatnonzero(m.at.sector == t)
                if len(points):
                    place[points] = np.arange(len(points))
                    blocks[id(b)] = (b, side.clamped_rows(rows[points], b.dofs))
            self.by_block.append((place, blocks))

    def strain(self, g: int, block, cuts: np.ndarray, load: np.ndarray | None,
               points: np.ndarray) -> np.ndarray:
        """Gear ``g``'s strain at ``points`` of one sector, whose cut motions are ``cuts`` and
        whose loads ``load`` on the template dofs of its load ``block`` (None: unloaded)."""
        out = self.through_cuts[g][points] @ cuts
        if load is not None:
            place, blocks = self.by_block[g]
            out += blocks[id(block)][1][place[points]] @ load   # (the block kept: its id)
        return out


def brief_stresses(model: RingModel, contact: RingContact, pressure: np.ndarray,
                   strains: SurfaceStrains | None) -> RingStresses:
    """The root zones and the surface von Mises estimate of ``pressure`` on ``contact`` (the
    ``strains`` of the contact it was turned from), read off the cut motions and loads
    (module docstring); the largest von Mises stress away from the contacts is the root
    zones'. No fields, no submodels. Without ``strains``, the root zones alone: the surface
    estimate is NaN (a caller that reads the roots and the pressures)."""
    roots, motions = [], []
    for side, loads in zip(model.gears, contact.loads):
        reading = readout(side)
        f = {t: b.matrix @ pressure[b.columns] for t, b in loads.items()
             if pressure[b.columns].any()}   # (a kept contact's wide grids: most unloaded)
        f = {t: v for t, v in f.items() if np.any(v)}
        sectors = loaded_sectors(side, loads, pressure)
        rho = {t: side.cut_loads(loads[t].dofs) @ v for t, v in f.items()}
        cuts = side.body.cut_motions(rho, sectors)
        motions.append((dict(zip(sectors, cuts.T)), f))
        at = reading.through_cuts @ cuts
        for j, s in enumerate(sectors):
            if s in f:
                at[:, j] += reading.clamped(side, loads[s].dofs) @ f[s]
        n = len(reading.nodes)
        roots.append({s: stress_field(at[:n, j], at[n:2 * n, j], at[2 * n:, j],
                                      side.body.material) for j, s in enumerate(sectors)})

    def strain(g: int, k: int, points: np.ndarray) -> np.ndarray:
        cuts, f = motions[g]
        if k not in cuts:
            return np.zeros(len(points))
        return strains.strain(g, contact.loads[g].get(k), cuts[k], f.get(k), points)

    surface = (np.full((2, contact.npoints), np.nan) if strains is None else
               surface_von_mises(model, contact, pressure, strain))
    zones = tuple(root_zone(side, readout(side).nodes,
                            {k: s.max_principal for k, s in r.items()})
                  for side, r in zip(model.gears, roots))
    bulk = max((float(s.von_mises.max()) for r in roots for s in r.values()), default=0.0)
    return RingStresses(({}, {}), zones, surface, (), bulk)

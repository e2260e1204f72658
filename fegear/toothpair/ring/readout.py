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

from dataclasses import dataclass

import numpy as np

from ...contact import strain_matrix
from ...fe import projector, stress_field
from .influence import RingContact
from .model import RingModel
from .side import GearSide
from .stresses import (
    RingStresses,
    root_zone,
    side_root_nodes,
    surface_stress,
    surface_tangent,
    with_neighbours,
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
    which a contact turned by whole pitches shares) the map of its loads at its points
    (:meth:`loaded`: points, dofs), formed the first time a solve loads that block (the
    kept contact's wide grids: most of its sectors no solve loads). Made once for a contact
    kept for a phase, and read by every solve on it, whatever pitch it is turned to."""

    def __init__(self, model: RingModel, contact: RingContact) -> None:
        self.through_cuts, self._rows, self._place = [], [], []
        self._contact, self._moduli, self._near = contact, (model.case.E, model.case.nu), {}
        self._sides = model.gears
        self._sector: dict[int, tuple] = {}   # id of a load block → (its sector, the block)
        self._loaded: dict[int, np.ndarray] = {}   # … → its map, where formed
        for side, loads, m in zip(model.gears, contact.loads, contact.matching):
            body = side.body
            rows = side.rows_at(m.cells, surface_tangent(m), strain=True).tocsc()
            self.through_cuts.append(np.asarray(rows[:, body.interior] @ body.psi
                                                + rows[:, body.interface]))
            place = np.full(contact.npoints, -1)
            for t, b in loads.items():
                points = np.flatnonzero(m.at.sector == t)
                place[points] = np.arange(len(points))
                self._sector[id(b)] = (t, b)   # (the block kept: its id stays its own)
            self._rows.append(rows)
            self._place.append(place)

    def loaded(self, g: int, block, points: np.ndarray) -> np.ndarray:
        """Gear ``g``'s strain at ``points`` (of one sector) per unit load at each template
        dof of the load ``block`` there (points, dofs): the block's clamped fields read at its
        sector's points, formed the first time."""
        key = id(block)
        if key not in self._loaded:
            t, b = self._sector[key]
            at = np.flatnonzero(self._contact.matching[g].at.sector == t)
            self._loaded[key] = self._sides[g].clamped_rows(self._rows[g][at], b.dofs)
        return self._loaded[key][self._place[g][points]]

    def near(self, g: int, k: int) -> np.ndarray:
        """The half-plane's strain along gear ``g``'s surface at grid ``k``'s matching points
        per unit pressure of each of its hats (:func:`~fegear.contact.strain_matrix`: points,
        hats), formed the first time it is asked for."""
        if (g, k) not in self._near:
            contact = self._contact
            s, depth = contact.grids[k].s, contact.matching[g].depth[contact.block(k)]
            self._near[g, k] = strain_matrix(s, depth, s, *self._moduli)
        return self._near[g, k]


def brief_stresses(model: RingModel, contact: RingContact, pressure: np.ndarray,
                   strains: SurfaceStrains | None) -> RingStresses:
    """The root zones and the surface von Mises estimate of ``pressure`` on ``contact`` (the
    ``strains`` of the contact it was turned from), read off the cut motions and loads
    (module docstring); the largest von Mises stress away from the contacts is the root
    zones'. No fields, no submodels. Without ``strains``, the root zones alone: the surface
    estimate is NaN (a caller that reads the roots and the pressures). One column of
    :func:`brief_stresses_of`."""
    return brief_stresses_of(model, contact, pressure[:, None], strains)[0]


def brief_stresses_of(model: RingModel, contact: RingContact, pressures: np.ndarray,
                      strains: SurfaceStrains | None) -> list[RingStresses]:
    """:func:`brief_stresses` of each column of ``pressures`` (points, samples) on
    ``contact``, read together: the loads, cut motions and root stresses of every sample as
    one product a sector (the deviation sets solved on one kept contact, its numbering the
    same: a class's samples at a position), each sample's then taken on its own loaded sectors
    and one either side, as alone."""
    reads = [_read_gear(side, loads, pressures) for side, loads in zip(model.gears,
                                                                       contact.loads)]
    samples = pressures.shape[1]
    own = [[(r, r.sectors_of(i)) for r in reads] for i in range(samples)]
    surfaces = (np.full((samples, 2, contact.npoints), np.nan) if strains is None else
                _surfaces(model, contact, pressures, strains, reads, own))
    out = []
    for i in range(samples):
        zones = tuple(root_zone(side, readout(side).nodes,
                                {k: r.s1[k][:, i] for k in sectors})
                      for side, (r, sectors) in zip(model.gears, own[i]))
        bulk = max((float(r.von_mises[k][:, i].max()) for r, sectors in own[i]
                    for k in sectors), default=0.0)
        out.append(RingStresses(({}, {}), zones, surfaces[i], (), bulk))
    return out


def _surfaces(model: RingModel, contact: RingContact, pressures: np.ndarray,
              strains: SurfaceStrains, reads: list, own: list) -> np.ndarray:
    """The surface von Mises estimate (:func:`~.stresses.surface_von_mises`) of each sample
    (samples, 2, points): the template's strain along the surface at depth, a sector's
    points for every sample at once (zero where the sample reads no field there), less the
    half-plane's part there, each grid's hats for every sample at once
    (:meth:`SurfaceStrains.near`), plus its surface value."""
    E, loaded = model.case.E, pressures > 0
    out = np.zeros((pressures.shape[1], 2, contact.npoints))
    for g, read in enumerate(reads):
        m = contact.matching[g]
        eps = np.zeros(pressures.shape)
        for k in np.unique(m.at.sector[loaded.any(axis=1)]):
            k = int(k)
            if k not in read.cuts:
                continue
            rows = np.flatnonzero(m.at.sector == k)
            eps[rows] = strains.through_cuts[g][rows] @ read.cuts[k]
            if k in read.loads:
                eps[rows] += strains.loaded(g, contact.loads[g][k], rows) @ read.loads[k]
            eps[np.ix_(rows, [k not in sectors for _, sectors in
                              (o[g] for o in own)])] = 0.0
        for k in range(len(contact.grids)):
            blk = contact.block(k)
            if loaded[blk].any():
                eps[blk] -= strains.near(g, k) @ pressures[blk]
        out[:, g] = surface_stress(E * eps, pressures).T
    return out


@dataclass(frozen=True)
class _GearRead:
    """One gear's readout of many samples' pressures (:func:`brief_stresses_of`), over the
    sectors any sample reads: the loaded sectors' template loads (dofs, samples; a sample's
    column zero where it loads none there), which samples press each sector's points
    (``pressed``, as :func:`~.stresses.loaded_sectors` counts them), and each sector's cut
    motions (2 n_f, samples) and root nodes' σ1 and von Mises (nodes, samples)."""

    count: int
    loads: dict
    pressed: dict
    cuts: dict
    s1: dict
    von_mises: dict

    def sectors_of(self, i: int) -> list[int]:
        """The sectors sample ``i``'s stresses read: those it presses and one either side."""
        return with_neighbours([t for t, on in self.pressed.items() if on[i]], self.count)


def _read_gear(side: GearSide, loads: dict, pressures: np.ndarray) -> _GearRead:
    """:class:`_GearRead` of ``pressures`` (points, samples) through ``side``'s ``loads``."""
    reading = readout(side)
    f, pressed = {}, {}
    for t, b in loads.items():
        on = pressures[b.columns]
        pressed[t] = (on > 0).any(axis=0)
        if on.any():   # (a kept contact's wide grids: most sectors unloaded)
            v = b.matrix @ on
            if v.any():
                f[t] = v
    sectors = with_neighbours([t for t, on in pressed.items() if on.any()], side.count)
    rho = {t: side.cut_loads(loads[t].dofs) @ v for t, v in f.items()}
    cuts = side.body.cut_motions(rho, sectors)          # (2 n_f, sectors, samples)
    n = len(reading.nodes)
    s1, vm, by = {}, {}, {}
    for j, s in enumerate(sectors):
        at = reading.through_cuts @ cuts[:, j]
        if s in f:
            at += reading.clamped(side, loads[s].dofs) @ f[s]
        field = stress_field(at[:n], at[n:2 * n], at[2 * n:], side.body.material)
        s1[s], vm[s], by[s] = field.max_principal, field.von_mises, cuts[:, j]
    return _GearRead(side.count, f, pressed, by, s1, vm)

"""Stresses of a solved position of the ring model: the fields of the loaded sectors, the root
stresses, and the contact stresses from a submodel at each contact peak.

Root stress is the largest first principal stress on profile nodes in the lower ``ROOT_BAND``
of the tooth height, from the loaded sectors' template fields (nodal stresses by L2 projection,
as the sector model reads them). At a contact, σ_nn = −p on the surface and the tangential
stress is E (ε_tt,FE(y) − ε_tt,half-plane(y)) − p at the matching depth: the template's strain
with the half-plane's part replaced by its exact surface value. That estimate picks the peak;
the von Mises stress there is read from a submodel (:mod:`fegear.fe.submodel`), a patch about the
peak meshed at a fraction of the local contact width, held at the template field on its cut and
loaded by the grid pressure: it resolves the stress under and beside a contact µm wide
(the L2-projected template stress cannot), subsurface included.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from ...contact import strain_matrix
from ...fe import (
    StarCurve,
    Submodel,
    SubmodelProblem,
    facet_nodes,
    recover_many,
    solve_submodels,
)
from ...planar import rotate, wrap
from ..segments import gear2_polar
from .influence import RingContact, loaded_hats
from .model import RingModel
from .side import GearSide

SUB_FACETS = 6.0       # a submodel reaches this many template facets from the peak …
SUB_WIDTHS = 4.0       # … and this many local contact half-widths
SUB_FLOOR = 1e-4       # its smallest element, in modules (0.2 µm at m = 2)
SUB_FOCUS = 3.0        # its elements are finest within this many half-widths of the peak
SUB_CANDIDATES = 0.97  # peaks whose estimate comes within this fraction of the highest get one
BULK_BLOCK = 256       # nodes tried at once for the largest von Mises stress away from the contacts


@dataclass(frozen=True)
class RootZone:
    """One gear's root-zone nodes over the computed sectors: polar angle (rad, gear frame),
    σ1 (MPa)."""

    angle: np.ndarray
    s1: np.ndarray

    @property
    def max(self) -> float:
        return float(self.s1.max()) if len(self.s1) else 0.0

    def near(self, centre: float, pitch: float) -> float:
        """Largest σ1 within half a ``pitch`` of the polar angle ``centre``."""
        sel = np.abs(wrap(self.angle - centre)) <= 0.5 * pitch
        return float(self.s1[sel].max()) if sel.any() else 0.0


@dataclass(eq=False)
class RingStresses:
    """The fields (sector → template-frame displacement, per gear), the root zones, the
    surface von Mises estimate per grid point (2, n) and the submodels. (The fields' nodal
    stresses are not kept: the root zones and the bulk von Mises stress are read from them,
    and a picture or VTU recovers them again, for one position; kept, they were 5 MB a
    position of a cycle.)"""

    fields: tuple[dict, dict] = field(repr=False)
    roots: tuple[RootZone, RootZone]
    surface: np.ndarray = field(repr=False)
    submodels: tuple[tuple[int, float, Submodel], ...] = field(repr=False)  # gear, turn
    bulk_von_mises: float       # the templates' largest, away from the contacts

    @property
    def von_mises_max(self) -> float:
        """Largest von Mises stress: the submodels' at the contacts, the templates' elsewhere;
        where no submodel was solved (no contact, or left out: :func:`ring_stresses`), the
        surface estimate at the contacts."""
        sub = [sm.peak(sm.stress.von_mises)[0] for _, _, sm in self.submodels]
        return max((sub or [float(self.surface.max())]) + [self.bulk_von_mises])


def ring_stresses(model: RingModel, contact: RingContact, pressure: np.ndarray,
                  submodels: bool = True, clamped: tuple | None = None) -> RingStresses:
    """Fields of the loaded sectors and one on each side, their stresses, root zones, the
    surface estimate and (``submodels``) the submodels at the contact peaks: without them
    the von Mises stress at a contact is the surface estimate, for a caller that reads only
    contact pressures and root stresses (the tip-relief search). ``clamped``: each gear's
    clamped fields of its loaded sectors under ``pressure``, formed before (the contact's
    check), else solved here."""
    fields = tuple(_fields(side, loads, pressure, c)
                   for side, loads, c in zip(model.gears, contact.loads, clamped or ({}, {})))
    stresses = tuple(dict(zip(f, recover_many(side.body, np.column_stack(list(f.values())),
                                              reused=True)))
                     if f else {} for side, f in zip(model.gears, fields))
    roots = []
    for side, by in zip(model.gears, stresses):
        nodes = side_root_nodes(side)
        roots.append(root_zone(side, nodes,
                               {k: s.max_principal[nodes] for k, s in by.items()}))

    def strain(g: int, k: int, points: np.ndarray) -> np.ndarray:
        u, m = fields[g].get(k), contact.matching[g]
        if u is None:
            return np.zeros(len(points))
        return model.gears[g].rows_at(m.cells.take(points), surface_tangent(m)[points],
                                      strain=True) @ u

    surface = surface_von_mises(model, contact, pressure, strain)
    loaded = pressure > 0
    bulk = max(_bulk_von_mises(side, s, pts[loaded], m.facet[loaded])
               for side, s, pts, m in zip(model.gears, stresses, (contact.x, contact.facing[0]),
                                          contact.matching))
    out = RingStresses(fields, tuple(roots), surface, (), bulk)
    return with_submodels(model, contact, pressure, out) if submodels else out


def with_submodels(model: RingModel, contact: RingContact, pressure: np.ndarray,
                   stresses: RingStresses) -> RingStresses:
    """``stresses`` with the submodels at the contact peaks solved (a mesh cycle adds them
    only where its von Mises peak is: :meth:`~.solver.RingSolver.at_peaks`)."""
    peaks = _peaks(contact, pressure, stresses.surface)
    problems = submodel_problems(model, contact, pressure, stresses)
    solved = solve_submodels([pb for pb, _ in problems], model.case.material, model.submodels)
    subs = tuple((g, turn, sm) for (g, _), (_, turn), sm in zip(peaks, problems, solved))
    return replace(stresses, submodels=subs)


def submodel_problems(model: RingModel, contact: RingContact, pressure: np.ndarray,
                      stresses: RingStresses) -> list[tuple[SubmodelProblem, float]]:
    """The submodels (:func:`contact_submodel`: each problem and its turn) that
    :func:`with_submodels` solves, one a contact peak."""
    return [contact_submodel(model, contact, pressure, stresses.fields, g, i)
            for g, i in _peaks(contact, pressure, stresses.surface)]


def _bulk_von_mises(side: GearSide, stresses: dict, loaded: np.ndarray,
                    facets: np.ndarray) -> float:
    """The template's largest von Mises stress farther than SUB_FACETS of its largest facet
    under the ``loaded`` points (gear frame; ``facets``: the facets' lengths there) from them:
    nearer, the contact is not resolved (the submodels cover it). The nodes are tried from the
    most stressed down, a block at a time, until one lies far enough (the first far one is the
    largest)."""
    from scipy.spatial import cKDTree

    x = side.body.mesh.doflocs.T
    reach = SUB_FACETS * float(facets.max()) if len(loaded) else 0.0
    tree = cKDTree(loaded) if len(loaded) else None
    out = 0.0
    for k, s in stresses.items():
        vm = s.von_mises
        if tree is None:
            out = max(out, float(vm.max()))
            continue
        order = np.argsort(-vm)
        for start in range(0, len(order), BULK_BLOCK):
            nodes = order[start:start + BULK_BLOCK]
            if vm[nodes[0]] <= out:
                break
            far = tree.query(rotate(x[nodes], k * side.pitch))[0] > reach
            if far.any():
                out = max(out, float(vm[nodes[np.argmax(far)]]))
                break
    return out


def _fields(side: GearSide, loads, pressure: np.ndarray,
            clamped: dict) -> dict[int, np.ndarray]:
    return side.fields(loads, pressure, loaded_sectors(side, loads, pressure), clamped)


def loaded_sectors(side: GearSide, loads, pressure: np.ndarray) -> list[int]:
    """The sectors whose fields a position's stresses read: those the ``pressure`` loads
    through ``loads`` and one either side."""
    return with_neighbours([t for t, b in loads.items() if np.any(pressure[b.columns] > 0)],
                           side.count)


def with_neighbours(loaded, count: int) -> list[int]:
    """The sectors ``loaded`` and one either side of each, of a ring of ``count``, in order."""
    return sorted({(t + k) % count for t in loaded for k in (-1, 0, 1)})


def root_zone(side: GearSide, nodes: np.ndarray, max_principal: dict) -> RootZone:
    """The :class:`RootZone` of ``side``'s sectors from the largest principal stress of each
    (sector → its values at the template's root ``nodes``, :func:`side_root_nodes`)."""
    x = side.body.mesh.doflocs[:, nodes].T
    angle, s1 = [], []
    for k, s in max_principal.items():
        angle.append(np.arctan2(x[:, 1], x[:, 0]) + k * side.pitch)
        s1.append(s)
    return RootZone(np.concatenate(angle) if angle else np.zeros(0),
                    np.concatenate(s1) if s1 else np.zeros(0))


def side_root_nodes(side: GearSide) -> np.ndarray:
    """Template profile nodes whose radius lies in the template's root band."""
    m = side.body.mesh
    nodes = np.unique(np.concatenate([facet_nodes(m, m.boundaries[n]).ravel()
                                      for n in side.template.profile]))
    r = np.linalg.norm(m.doflocs[:, nodes], axis=0)
    lo, hi = side.template.root_band
    return nodes[(r >= lo - 1e-9) & (r <= hi + 1e-9)]


def surface_von_mises(model: RingModel, contact: RingContact, pressure: np.ndarray,
                      strain) -> np.ndarray:
    """Von Mises (MPa) at the contact surface of each gear per grid point, (2, n): plane
    stress, σ_nn = −p, σ_nt = 0, σ_tt from the template strain at depth with the half-plane's
    part replaced by its surface value (zero where no pressure acts). ``strain(g, k,
    points)``: the template's strain along the surface (:func:`surface_tangent`) at gear
    ``g``'s matching ``points`` (indices) in its sector ``k`` (zero where it has no field)."""
    E, nu = model.case.E, model.case.nu
    out = np.zeros((2, contact.npoints))
    loaded = pressure > 0
    for g in range(len(model.gears)):
        m = contact.matching[g]
        eps_fe = np.zeros(contact.npoints)
        for k in np.unique(m.at.sector[loaded]):
            rows = np.flatnonzero((m.at.sector == k) & loaded)
            eps_fe[rows] = strain(g, int(k), rows)
        eps_hp = np.zeros(contact.npoints)
        for k, grid in enumerate(contact.grids):
            blk = contact.block(k)
            on = np.flatnonzero(loaded[blk])    # only these are read
            if len(on):
                a, b = loaded_hats(on, len(grid))
                eps_hp[blk.start + on] = strain_matrix(grid.s[on], m.depth[blk][on],
                                                       grid.s[a:b], E, nu) @ pressure[blk][a:b]
        out[g] = surface_stress(E * (eps_fe - eps_hp), pressure)
    return out


def surface_stress(stretch: np.ndarray, pressure: np.ndarray) -> np.ndarray:
    """Von Mises (MPa) at a contact surface, plane stress, of the ``pressure`` (σ_nn = −p,
    σ_nt = 0) and the stress along the surface its strain gives (``stretch``: E ε_tt, the
    template's at depth less the half-plane's there, MPa); zero where no pressure acts."""
    sig_t = stretch - pressure
    return np.where(pressure > 0, np.sqrt(pressure ** 2 + sig_t ** 2 + pressure * sig_t), 0.0)


def surface_tangent(matching) -> np.ndarray:
    """The direction along the surface (n, 2, template frame) at ``matching``'s points, in
    which :func:`surface_von_mises` reads the template's strain."""
    return np.column_stack([-matching.direction[:, 1], matching.direction[:, 0]])


def _peaks(contact: RingContact, pressure: np.ndarray, surface: np.ndarray):
    """(gear, grid point) of the peaks that get a submodel: per gear, each tooth's highest
    surface estimate if it comes within SUB_CANDIDATES of that gear's highest."""
    out = []
    for g in (0, 1):
        top = surface[g].max()
        if top <= 0:
            continue
        for k in range(len(contact.grids)):
            blk = contact.block(k)
            i = blk.start + int(np.argmax(surface[g, blk]))
            if surface[g, i] >= SUB_CANDIDATES * top:
                out.append((g, i))
    return out


def local_half_width(contact: RingContact, pressure: np.ndarray, i: int) -> float:
    """Contact half-width (mm) about grid point ``i`` from the width where the pressure stays
    above half its value there (√3/2 of b for Hertz), within the point's grid."""
    k = int(contact.grid_index[i])
    blk = contact.block(k)
    s, p = contact.grids[k].s, pressure[blk]
    j = i - blk.start
    lo = hi = j
    while lo > 0 and p[lo - 1] >= 0.5 * p[j]:
        lo -= 1
    while hi < len(p) - 1 and p[hi + 1] >= 0.5 * p[j]:
        hi += 1
    lo_s = s[lo] - (s[lo] - s[lo - 1]) * (p[lo] - 0.5 * p[j]) / max(p[lo] - p[lo - 1], 1e-300) \
        if lo > 0 else s[lo]
    hi_s = s[hi] + (s[hi + 1] - s[hi]) * (p[hi] - 0.5 * p[j]) / max(p[hi] - p[hi + 1], 1e-300) \
        if hi < len(p) - 1 else s[hi]
    return max(hi_s - lo_s, s[min(j + 1, len(s) - 1)] - s[max(j - 1, 0)]) / np.sqrt(3.0)


def contact_submodel(model: RingModel, contact: RingContact, pressure: np.ndarray,
                     fields: tuple[dict, dict], gear: int, i: int
                     ) -> tuple[SubmodelProblem, float]:
    """The submodel of ``gear`` about grid point ``i``'s contact (see module docstring), set
    in the frame of the gear's tooth 0 so that a later position or torque with its peak at the
    same place of a tooth reuses its mesh and factorisation; and the turn (rad) from that frame
    to the gear's. Its radius and element size are rounded to quarter powers of two and its
    centre to a quarter of its finest zone, which keeps the peak inside that zone."""
    side = model.gears[gear]
    k = int(contact.grid_index[i])
    blk = contact.block(k)
    p = pressure[blk]
    b = local_half_width(contact, pressure, i)
    foot = None
    if gear == 0:
        point = model.shape.point
        x = contact.x[i]
        angles = contact.grids[k].phi
    else:   # the template's own: along the normal (a near-radial flank, h1 0.2, f1 0.6,
        # inverted along the polar angle), no table (a mesh's input: Cycloid.xi_at_angle)
        polar = gear2_polar(model.curve2)
        point, foot = polar.point, polar.project
        x = contact.facing[0][i]
        angles = np.unwrap(np.arctan2(contact.facing[0][blk, 1], contact.facing[0][blk, 0]))
    centre = float(np.arctan2(x[1], x[0]))
    turn = float(np.floor(centre / side.pitch) * side.pitch)
    order = np.argsort(angles)
    ang, pr = angles[order] - turn, p[order]

    def pressure_at(y):   # tooth-0 frame
        a = ang[0] + wrap(np.arctan2(y[:, 1], y[:, 0]) - ang[0])
        return np.interp(a, ang, pr, left=0.0, right=0.0)

    def held(y):          # tooth-0 frame in, tooth-0 frame out
        return rotate(side.displacement_at(rotate(y, turn), fields[gear]), -turn)

    facet = float(side.facet_size(side.locate(x[None]).local)[0])
    radius = _quarter_power(max(SUB_FACETS * facet, SUB_WIDTHS * b))
    size = _quarter_power(max(b / model.level.sub_per_b, SUB_FLOOR * model.case.params.m))
    focus = _quarter_power(SUB_FOCUS * b)
    # the angle's step from the key's numbers alone (not from the point's own radius): a key
    # names one patch, whichever peak asked for it first
    step = 0.25 * min(focus, 0.5 * radius) / model.case.params.r0
    local = round((centre - turn) / step)
    key = (gear, local, radius, size, focus)
    curve = StarCurve(point, inside=gear == 0, foot=foot)
    return SubmodelProblem(curve, local * step, radius, size, focus, pressure_at, held,
                           name=f"gear{gear + 1}_contact", key=key), turn


def _quarter_power(x: float) -> float:
    """``x`` rounded to the nearest quarter power of two."""
    return float(2.0 ** (round(4.0 * np.log2(x)) / 4.0))

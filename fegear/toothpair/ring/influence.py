"""The contact at one rolling position: the pressure grids' points, their loads on both gears and
the influence matrix A, how far each grid point approaches gear 2 per unit pressure of each
pressure hat.

For each gear, A_ij = n · u_FE(y_i; hat j) + Δ(x_i − y_i; hat j): the finite-element
displacement at the point y_i a few local elements below the surface point x_i (the coarse
template is accurate there under loads spread on its facets) plus the half-plane's approach of
the surface relative to that depth (:mod:`fegear.contact.halfplane`), so the mesh need not
resolve the contact width at any load. The finite-element part is the clamped field of the
loaded sector plus the ring's response through the cut faces (:class:`~fegear.fe.cyclic
.CyclicBody`); every sector's loads reach only its own few hats and template dofs, and the
products are formed on those alone. A is formed only between the points that can carry
pressure (``formed``: its rows and columns); whether a point left out closes is read from the
fields under the solved pressure at its matching points (:func:`approach_open`: one load, not
a column a hat), the same numbers as its row of A times the pressure.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field, replace

import numpy as np

from ...contact import approach_matrix, hat_columns
from ...fe import Cells
from ...geometry import Placed
from ...planar import rotate
from .contact_system import true_runs
from .grid import ToothGrid
from .master import Gear2Master
from .model import RingModel
from .side import GearSide, LoadBlock, Located

GAUSS = 2   # Gauss points per grid interval for the hats' loads on the templates: exact for
            # the hat (linear) times a quadratic facet's shape (to cubic) within one facet


@dataclass(frozen=True)
class Matching:
    """Where one gear's finite elements are read for each grid point: the point at depth
    (located in the template, and the template element holding it), the direction of the
    approach there (template frame), the depth (mm) and the length of the template's profile
    facet under the grid point (mm)."""

    at: Located
    cells: Cells
    direction: np.ndarray
    depth: np.ndarray
    facet: np.ndarray

    def take(self, index: np.ndarray) -> Matching:
        """The grid points ``index`` of these."""
        at = Located(self.at.sector[index], self.at.local[index], self.at.turn[index])
        return Matching(at, self.cells.take(index), self.direction[index], self.depth[index],
                        self.facet[index])


@dataclass(eq=False)
class RingContact:
    """The assembled contact at one rolling angle β, gear 1 turned by ``turn`` (rad, its
    kinematic angle included): the grids and their points (gear 1's frame), outward normals,
    arc positions (mm) and hat weights ∫φ ds (mm); each gear's loads per unit hat pressure
    (sector → :class:`LoadBlock`) and matching points; gear 2's points facing the grid and its
    outward normals there (its own frame) and its curve's parameter ξ there, the foot last
    found (the rigid gap's searches at nearby rotations start from it:
    :func:`~.contact.rigid_gap`); A (mm/MPa) between the ``formed`` points (rows and
    columns in the points' order), which only the solve reads (a solved position's record,
    :class:`~.results.RingDetail`, is without it), and what forms A's columns of the points
    given where they are formed as they are read (``former``, :mod:`.lazy`; else None)."""

    beta: float
    turn: float
    grids: tuple[ToothGrid, ...]
    offsets: np.ndarray
    x: np.ndarray
    normal: np.ndarray
    weight: np.ndarray
    loads: tuple[dict[int, LoadBlock], dict[int, LoadBlock]] = field(repr=False)
    matching: tuple[Matching, Matching] = field(repr=False)
    facing: tuple[np.ndarray, np.ndarray] = field(repr=False)
    A: np.ndarray | None = field(repr=False)
    formed: np.ndarray = field(repr=False)   # the points whose rows and columns A holds
    feet: np.ndarray = field(repr=False)     # gear 2's parameter ξ at each point's foot, the
                                             # last found: the next search's start
    placed: Placed | None = field(default=None, repr=False)   # the pair's deviations here
    former: Callable[[np.ndarray], None] | None = field(default=None, repr=False)

    def ready(self, points: np.ndarray) -> None:
        """Have A's columns of ``points`` formed (:attr:`former`) before they are read."""
        if self.former is not None:
            self.former(points)

    @property
    def teeth(self) -> np.ndarray:
        """Each point's gear-1 tooth."""
        return np.repeat([g.tooth for g in self.grids], np.diff(self.offsets))

    @property
    def complete(self) -> bool:
        """Whether A spans every point (its columns formed, or formed where read: :attr:`former`;
        else the probe grids' are left out: zero)."""
        return bool(self.formed.all())

    @property
    def npoints(self) -> int:
        return len(self.x)

    def block(self, k: int) -> slice:
        """The points of grid ``k``."""
        return slice(int(self.offsets[k]), int(self.offsets[k + 1]))

    @property
    def grid_index(self) -> np.ndarray:
        """The grid each point belongs to."""
        return np.repeat(np.arange(len(self.grids)), np.diff(self.offsets))


@dataclass(frozen=True, eq=False)
class ColumnRule:
    """Which of A's columns (and rows: the same points) :func:`assemble_contact` forms. Every
    point's, but: without ``probes`` (and with a fine grid among the grids) not the probe
    grids' (the approach of every point under the fine grids' pressures is all a solve needs
    while no probe point closes: :func:`~.contact.solve_ring_contact`; the probes' columns,
    with the sectors only they load, were a fifth of the influence products); with ``within``
    (mm), only those of the points whose rigid gap at the contact's turn is below it, the hats
    that can carry pressure there (pressure separates the surfaces everywhere, so a loaded
    point overlaps rigidly: on the baseline's cycle, by a fifth of the elastic approach or
    more at the expected turn); with ``mask`` (over the points), only those of these points
    (where the position before carried pressure, say). A rule that would leave no column
    keeps those of the rules before it. Without ``now``, A is left to the caller (None:
    :mod:`.lazy` forms it where it is read)."""

    probes: bool = True
    within: float | None = None
    mask: np.ndarray | None = None
    now: bool = True

    def formed(self, grids, offsets: np.ndarray, gap: np.ndarray) -> np.ndarray:
        """The points whose columns are formed, of the ``grids`` (their points from
        ``offsets``) at the rigid gaps ``gap`` (mm)."""
        every = self.probes or all(g.probe for g in grids)
        formed = np.repeat([every or not g.probe for g in grids], np.diff(offsets))
        if self.within is not None and (formed & (gap < self.within)).any():
            formed &= gap < self.within
        if self.mask is not None and (formed & self.mask).any():
            formed &= self.mask
        return formed


def assemble_contact(model: RingModel, grids: tuple[ToothGrid, ...], beta: float,
                     turn: float, rule: ColumnRule = ColumnRule(),
                     placed: Placed | None = None) -> RingContact:
    """The contact of the ``grids`` with gear 2 turned by β and gear 1 by ``turn`` (rad, its
    kinematic angle included, about its centre), its rigid gaps with the pair's deviations
    ``placed`` at β where there are any, and A on the columns and rows ``rule`` gives (whether
    a point left out closes is told from the solved pressure's fields: :func:`approach_open`).
    The elastic part is the exact pair's: the deviations move the surfaces by µm."""
    p, case = model.case.params, model.case
    g1, g2 = model.gears
    offsets = np.cumsum([0] + [len(g) for g in grids])
    x = np.vstack([g.x for g in grids])
    n1 = np.vstack([g.normal for g in grids])
    weight = np.concatenate([g.weights for g in grids])
    o1 = np.array([0.0, p.e])
    master = Gear2Master(model.curve2, beta)
    feet = np.full(len(x), np.nan)
    cp = master.closest(rotate(x, turn) + o1, feet)
    gap = cp.distance if placed is None else placed.gap(
        x, np.repeat([g.tooth for g in grids], np.diff(offsets)), turn, feet.copy())[0]
    formed = rule.formed(grids, offsets, gap)

    xq, nq, size, col = _hat_loads(model, grids, offsets, case.thickness, formed)
    loads1 = g1.nodal_loads(xq, -nq, col, size)
    cq = master.closest(rotate(xq, turn) + o1)
    loads2 = g2.nodal_loads(rotate(cq.foot, -beta), rotate(rotate(nq, turn), -beta), col, size)

    x2, n2 = rotate(cp.foot, -beta), rotate(cp.normal, -beta)   # n2 out of gear 2's material
    match = (_matching(g1, x, n1, model.level.depth, grids, offsets),
             _matching(g2, x2, n2, model.level.depth, grids, offsets))
    contact = RingContact(beta, turn, tuple(grids), offsets, x, n1, weight, (loads1, loads2),
                          match, (x2, n2), None, formed, feet, placed)
    return replace(contact, A=_influence(model, contact)) if rule.now else contact


def _influence(model: RingModel, contact: RingContact) -> np.ndarray:
    """A between the ``contact``'s formed points (module docstring): each gear's
    finite-element part, then the half-plane's near field on each grid."""
    on = np.flatnonzero(contact.formed)
    place = np.full(contact.npoints, -1)
    place[on] = np.arange(len(on))
    A = np.zeros((len(on), len(on)), order="F")   # read by columns: the loaded points'
    for side, loads, m in zip(model.gears, contact.loads, contact.matching):
        add_fe_part(side, loads, m.take(on), place, A)
    _add_near_field(model, contact, place, A)
    return A


def near_field(model: RingModel, contact: RingContact) -> np.ndarray:
    """A's half-plane part alone between the formed points: each grid's near field, the
    surface's approach relative to the matching depth (zero between grids); A less it is the
    finite-element part, the approach at that depth (the part that spreads along the face:
    :mod:`.face`)."""
    on = np.flatnonzero(contact.formed)
    place = np.full(contact.npoints, -1)
    place[on] = np.arange(len(on))
    out = np.zeros((len(on), len(on)))
    _add_near_field(model, contact, place, out)
    return out


def _add_near_field(model: RingModel, contact: RingContact, place: np.ndarray,
                    A: np.ndarray) -> None:
    """Add the half-plane's near field on each grid to ``A`` (the formed points' rows and
    columns, at ``place``)."""
    case, formed = model.case, contact.formed
    for k, g in enumerate(contact.grids):
        blk = contact.block(k)
        rows = np.flatnonzero(formed[blk])
        if not len(rows):
            continue
        first = place[blk.start + rows[0]]
        for lo, hi in true_runs(formed[blk]):   # the formed hats' columns alone
            c = place[blk.start + lo]
            for m in contact.matching:
                A[first:first + len(rows), c:c + hi - lo] += hat_columns(
                    g.s[rows], m.depth[blk][rows], g.s, lo, hi, case.E, case.nu)


def _hat_loads(model: RingModel, grids, offsets, thickness: float, formed: np.ndarray):
    """Gauss points of every interval of the grids next to a hat whose column is ``formed``
    (per point; gear 1's frame), outward normals there, and per point the two hats it loads
    (the falling one of the interval's start, the rising one of its end) with the force (N)
    per unit pressure of each: (n, 2) columns and sizes (a hat not formed loads nothing: its
    place holds its formed neighbour's column at zero force)."""
    gq, gw = np.polynomial.legendre.leggauss(GAUSS)
    samples = model.samples
    xs, ns, sizes, cols = [], [], [], []
    for k, g in enumerate(grids):
        on = formed[offsets[k]:offsets[k + 1]]
        used = on[:-1] | on[1:]            # intervals next to a formed hat
        if not used.any():
            continue
        a, b = g.s[:-1][used], g.s[1:][used]
        sq = 0.5 * (a + b)[:, None] + 0.5 * (b - a)[:, None] * gq[None, :]
        wq = 0.5 * (b - a)[:, None] * gw[None, :]
        phi = np.interp(sq.ravel(), g.s, g.phi) - g.tooth * samples.shape.pitch
        # load points need no exactness: tooth 0's dense samples (nm off) turned to the tooth
        xq = np.column_stack([np.interp(phi, samples.phi, samples.x[:, d]) for d in (0, 1)])
        nq = np.column_stack([np.interp(phi, samples.phi, samples.normal[:, d]) for d in (0, 1)])
        nq /= np.linalg.norm(nq, axis=1)[:, None]
        turn = g.tooth * samples.shape.pitch
        xs.append(rotate(xq, turn))
        ns.append(rotate(nq, turn))
        start = np.flatnonzero(used)
        fall = ((b[:, None] - sq) / (b - a)[:, None] * wq * on[start][:, None]).ravel()
        rise = ((sq - a[:, None]) / (b - a)[:, None] * wq * on[start + 1][:, None]).ravel()
        j = offsets[k] + np.repeat(start, GAUSS)
        j_fall = np.where(np.repeat(on[start], GAUSS), j, j + 1)
        j_rise = np.where(np.repeat(on[start + 1], GAUSS), j + 1, j)
        sizes.append(np.column_stack([fall, rise]) * thickness)
        cols.append(np.column_stack([j_fall, j_rise]))
    return np.vstack(xs), np.vstack(ns), np.vstack(sizes), np.vstack(cols)


def _matching(side: GearSide, x: np.ndarray, normal: np.ndarray, depth: float,
              grids, offsets) -> Matching:
    """Matching points below the gear's surface points ``x`` (its frame, outward ``normal``),
    and the approach direction (into the material) in the template. The depth is at least
    ``depth`` local facets and changes no faster than the arc along each grid: the smallest
    such function, d(s) = max_j (depth h_j − |s − s_j|). (Taken point by point, it jumped
    where the facets do, at a round's ends, and the peak pressure with it by 0.5 %.)"""
    facet = side.facet_size(side.locate(x).local)
    h = depth * facet
    d = np.empty_like(h)
    for k, g in enumerate(grids):
        blk = slice(int(offsets[k]), int(offsets[k + 1]))
        d[blk] = np.max(h[blk][None, :] - np.abs(g.s[:, None] - g.s[None, :]), axis=1)
    at = side.locate(x - d[:, None] * normal)
    return Matching(at, side.cells(at.local), rotate(-normal, -at.turn), d, facet)


def approach_open(model: RingModel, contact: RingContact, pressure: np.ndarray,
                  rows: np.ndarray) -> tuple[np.ndarray, tuple[dict, dict]]:
    """(A p)[rows] for the points ``rows`` whose rows of A are not formed (``pressure`` p on
    the formed hats, zero elsewhere): each gear's field under p read at their matching points
    (the cut motions of their sectors through Ψ, the clamped field of p's loads where they
    share a loaded sector) and the half-plane's approach on their grids. Also each gear's
    clamped fields of its loaded sectors (sector → template field), which the stresses'
    fields then take (:class:`~.contact.RingContactSolution`)."""
    case = model.case
    out = np.zeros(len(rows))
    clamped = []
    for side, loads, m in zip(model.gears, contact.loads, contact.matching):
        part, fields = _fe_approach(side, loads, m.take(rows), pressure)
        out += part
        clamped.append(fields)
    grid = contact.grid_index[rows]
    for k in np.unique(grid):
        g, blk = contact.grids[k], contact.block(k)
        loaded = np.flatnonzero(pressure[blk])
        if not len(loaded):
            continue
        a, b = loaded_hats(loaded, len(g))
        r = np.flatnonzero(grid == k)
        local = rows[r] - blk.start
        for m in contact.matching:
            out[r] += approach_matrix(g.s[local], m.depth[blk][local], g.s[a:b], case.E,
                                      case.nu) @ pressure[blk][a:b]
    return out, tuple(clamped)


def loaded_hats(loaded: np.ndarray, n: int) -> tuple[int, int]:
    """The hats [a, b) of an ``n``-point grid from the first ``loaded`` point's neighbour to
    the last's (``loaded``: increasing indices of the points with pressure): a half-plane sum
    over them is the sum over the whole grid, where the others carry nothing."""
    return max(int(loaded[0]) - 1, 0), min(int(loaded[-1]) + 2, n)


def _fe_approach(side: GearSide, loads: dict[int, LoadBlock], match: Matching,
                 pressure: np.ndarray) -> tuple[np.ndarray, dict]:
    """n · u_FE at the matching points under the hats' ``pressure`` (one load, not a column
    per hat: :func:`add_fe_part` times p), and the clamped fields of the loaded sectors."""
    at, (N, NQ, _) = match.at, matching_rows(side, match)
    rho = {t: side.cut_loads(blk.dofs) @ (blk.matrix @ pressure[blk.columns])
           for t, blk in loads.items()}
    f = {t: blk.vector(pressure, side.body.ndofs) for t, blk in loads.items()}
    own = [t for t, v in f.items() if v.any()]
    clamped = dict(zip(own, side.body.clamped(np.column_stack([f[t] for t in own])).T)) \
        if own else {}
    out = np.zeros(len(at.sector))
    sectors = np.unique(at.sector)
    cuts = side.body.cut_motions(rho, sectors)
    for j, k in enumerate(sectors):
        r = np.flatnonzero(at.sector == k)
        out[r] = NQ[r] @ cuts[:, j]
        if k in clamped:
            out[r] += (N @ clamped[k])[r]
    return out, clamped


def matching_rows(side: GearSide, match: Matching) -> tuple:
    """The matching points' rows of the template's fields (sparse: the approach per template
    dof) and of the cut motions (dense, points × cut dofs: by Ψ), which :func:`add_fe_part`
    reads, and room for what it forms of them (a sector's rows, their products with a far
    coupling's thin factor) for its later calls on the same points."""
    N = side.rows_at(match.cells, match.direction)
    return N, np.asarray(N @ side.cut_field), {}


def add_fe_part(side: GearSide, loads: dict[int, LoadBlock], match: Matching,
                place: np.ndarray, out: np.ndarray, fields: tuple | None = None) -> None:
    """Add n · u_FE at the matching points per unit pressure of each hat (see module
    docstring) to ``out`` (points × formed hats; ``place``: each hat's column there): for the
    points in sector k and the hats loading sector t, the clamped field if t = k plus
    N Ψ W(t − k) ρ, the product taken through the thin factors of W where the sectors are far
    apart (:meth:`~fegear.fe.cyclic.CyclicBody.coupling_factors`). A sector's points and a
    sector's hats are each one run of rows and of columns but where a grid straddles two
    sectors. ``fields``: :func:`matching_rows` of ``match``, where formed before. The clamped
    fields are read at the points of the loaded sectors alone (zero in every other)."""
    at = match.at
    N, NQ, by_sector = matching_rows(side, match) if fields is None else fields
    dofs = np.unique(np.concatenate([blk.dofs for blk in loads.values()]))
    loaded = np.isin(at.sector, np.fromiter(loads, int))
    own = np.cumsum(loaded) - 1                           # a loaded sector's point's row …
    clamped = side.clamped_rows(N if loaded.all() else N[loaded], dofs)   # … here
    rho = {t: side.cut_loads(blk.dofs) @ blk.matrix for t, blk in loads.items()}
    columns = {t: _run(place[blk.columns]) for t, blk in loads.items()}
    for k in np.unique(at.sector):
        if k not in by_sector:
            by_sector[k] = np.flatnonzero(at.sector == k), {}
        r, far = by_sector[k]
        rows = _run(r)
        Nk = NQ[r]
        for t, blk in loads.items():
            factors = side.body.coupling_factors(t - k)
            if factors is None:   # the cheaper order: a probe's few points by W first
                W = side.body.coupling(t - k)
                block = ((Nk @ W) @ rho[t] if len(r) < rho[t].shape[1]
                         else Nk @ (W @ rho[t]))
            else:
                if t - k not in far:
                    far[t - k] = Nk @ factors[0]
                block = far[t - k] @ (factors[1] @ rho[t])
            if t == k:
                block += clamped[_run(own[r])][:, np.searchsorted(dofs, blk.dofs)] @ blk.matrix
            if isinstance(rows, slice) or isinstance(columns[t], slice):
                out[rows, columns[t]] += block
            else:
                out[np.ix_(r, place[blk.columns])] += block


def _run(index: np.ndarray) -> slice | np.ndarray:
    """``index`` (increasing) as a slice where it is one run of consecutive numbers."""
    if len(index) and index[-1] - index[0] + 1 == len(index):
        return slice(int(index[0]), int(index[-1]) + 1)
    return index

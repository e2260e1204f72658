"""One gear of the ring model: its template sector as a cyclic body, where a point of the gear
lies in which sector, loads on its profile, and what its finite elements say at a point.

Sector k of a gear is its template turned by k pitches about the gear's centre; a point of the
gear (its own frame) is carried into the template by turning it back. The template's unit-load
responses (a clamped field and the loads carried to the cuts) are formed once per template dof
when a load first reaches it, and kept for every later position, torque and tooth: every tooth
loads the same template dofs (the stage "responses" of a solve's times).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp

from ...contact import FacetLocator, p2_edge_shape
from ...fe import Cells, CyclicBody, Probe, facet_nodes, node_dofs
from ...planar import rotate
from ...timing import timed
from .template import Template


@dataclass(frozen=True)
class Located:
    """Points carried into the template: sector index, template-frame positions and the
    rotation (rad) that takes template vectors to the gear's frame."""

    sector: np.ndarray
    local: np.ndarray
    turn: np.ndarray


@dataclass(frozen=True)
class LoadBlock:
    """The loads that a set of unknowns (columns) puts on one sector: template ``dofs``, the
    ``columns`` they come from and the dense (dofs × columns) map, N per unit unknown."""

    dofs: np.ndarray
    columns: np.ndarray
    matrix: np.ndarray

    def vector(self, values: np.ndarray, ndofs: int) -> np.ndarray:
        """The sector's load vector (ndofs,) for the unknowns' ``values`` (all columns)."""
        f = np.zeros(ndofs)
        f[self.dofs] = self.matrix @ values[self.columns]
        return f


@dataclass(frozen=True)
class Responses:
    """A side's unit-load responses formed so far: template dof → response column (-1: not
    formed), the clamped fields' interior rows (interior dofs, columns) and the loads they
    carry to the cuts (2 n_f, columns)."""

    column: np.ndarray
    X: np.ndarray
    rho: np.ndarray


@dataclass(eq=False)
class GearSide:
    """A gear of the ring: ``body`` (the cyclic template) and its ``template``; ``count``
    sectors of ``pitch`` from polar angle ``template.start``."""

    body: CyclicBody
    template: Template
    facets: np.ndarray = field(init=False, repr=False)      # the template's profile facets
    on_facets: FacetLocator = field(init=False, repr=False)  # … and their search tree
    probe: Probe = field(init=False, repr=False)
    _column: np.ndarray = field(init=False, repr=False)     # template dof → response column
    _X: list = field(init=False, repr=False)                # clamped fields (interior rows):
                                                            # column blocks
    _rho: np.ndarray = field(init=False, repr=False)        # cut loads, by column
    _used: int = 0
    _cut_field: np.ndarray | None = field(default=None, repr=False)
    readout: object | None = field(default=None, repr=False)   # :class:`.readout.RootReadout`

    def __post_init__(self) -> None:
        m = self.body.mesh
        self.facets = np.concatenate([m.boundaries[n] for n in self.template.profile])
        self.on_facets = FacetLocator(m, self.facets)
        self.probe = Probe(m)
        self._column = np.full(self.body.ndofs, -1, dtype=np.int64)
        self._X = []
        self._rho = np.zeros((len(self.body.interface), 0))

    @property
    def count(self) -> int:
        return self.body.count

    @property
    def pitch(self) -> float:
        return self.template.pitch

    def locate(self, x: np.ndarray) -> Located:
        """Sector and template-frame position of points ``x`` (n, 2) of the gear."""
        phi = np.arctan2(x[:, 1], x[:, 0])
        k = np.floor((phi - self.template.start) / self.pitch).astype(int)
        turn = k * self.pitch
        return Located(np.mod(k, self.count), rotate(x, -turn), turn)

    def facet_size(self, local: np.ndarray) -> np.ndarray:
        """Length (mm) of the template profile facet under each template-frame point."""
        fac, _ = self.on_facets.locate(local)
        ends = self.body.mesh.p[:, self.body.mesh.facets[:, fac]]
        return np.linalg.norm(ends[:, 1] - ends[:, 0], axis=0)

    def nodal_loads(self, x: np.ndarray, direction: np.ndarray, column: np.ndarray,
                    size: np.ndarray) -> dict[int, LoadBlock]:
        """Consistent nodal loads of point forces at profile points ``x`` (n, 2, gear frame)
        along unit ``direction`` s (n, 2): point i loads unknown ``column[i, j]`` with
        ``size[i, j]`` N per unit value (both (n, c))."""
        where = self.locate(x)
        d_local = rotate(direction, -where.turn)
        fac, s = self.on_facets.locate(where.local)
        shape = p2_edge_shape(np.clip(s, 0.0, 1.0))
        nodes = facet_nodes(self.body.mesh, fac)
        out = {}
        for k in np.unique(where.sector):
            sel = where.sector == k
            m, c = int(sel.sum()), column.shape[1]
            # (point, facet node, direction, unknown): dof, force per unit value, unknown
            rows = np.broadcast_to(node_dofs(nodes[sel])[:, :, :, None], (m, 3, 2, c)).ravel()
            vals = (shape[sel][:, :, None, None] * d_local[sel][:, None, :, None]
                    * size[sel][:, None, None, :]).ravel()
            cols = np.broadcast_to(column[sel][:, None, None, :], (m, 3, 2, c)).ravel()
            dofs, r = np.unique(rows, return_inverse=True)
            columns, c = np.unique(cols, return_inverse=True)
            matrix = np.zeros((len(dofs), len(columns)))
            np.add.at(matrix, (r, c), vals)
            out[int(k)] = LoadBlock(dofs, columns, matrix)
        return out

    def rows(self, local: np.ndarray, direction: np.ndarray,
             strain: bool = False) -> sp.csr_matrix:
        """Rows over template dofs giving, at template-frame points ``local``, the displacement
        along ``direction`` (n, 2), or (``strain``) the strain along it."""
        return self.probe.rows(local, direction, strain=strain)

    def rows_at(self, cells: Cells, direction: np.ndarray,
                strain: bool = False) -> sp.csr_matrix:
        """:meth:`rows` at template-frame points located before (``cells``, from
        :meth:`cells`)."""
        return self.probe.rows_at(cells, direction, strain=strain)

    def cells(self, local: np.ndarray) -> Cells:
        """The template elements holding template-frame points ``local``, and where in them."""
        return self.probe.locate(local)

    # --- responses to unit loads ------------------------------------------------------------
    def _form(self, dofs: np.ndarray) -> np.ndarray:
        """Response columns of template ``dofs``, forming those not formed yet."""
        new = np.unique(dofs[self._column[dofs] < 0])
        if len(new):
            with timed("responses"):
                need = self._used + len(new)
                # the fields are kept as the blocks they were formed in (growing one array
                # copied it whole every time), their interior rows alone (the cut's are
                # zero); the cut loads are small
                self._X.append((self._used, self.body.unit_clamped(new, interior=True)))
                self._rho = np.hstack([self._rho, self.body.unit_cut_loads(new)])
                self._column[new] = np.arange(self._used, need)
                self._used = need
        return self._column[dofs]

    @property
    def formed(self) -> int:
        """How many template dofs have their responses formed."""
        return self._used

    def responses(self) -> Responses:
        """The responses formed so far, for the model cache."""
        X = (np.hstack([block for _, block in self._X]) if len(self._X) > 1
             else self._X[0][1] if self._X else np.zeros((len(self.body.interior), 0)))
        return Responses(self._column, X, self._rho)

    def restore_responses(self, parts: Responses) -> None:
        """Take back the :meth:`responses` of a side of the same template."""
        self._column = np.array(parts.column, dtype=np.int64)
        self._X = [(0, parts.X)] if parts.X.shape[1] else []
        self._rho = parts.rho
        self._used = int(parts.X.shape[1])

    def clamped_rows(self, rows: sp.csr_matrix, dofs: np.ndarray) -> np.ndarray:
        """``rows`` applied to the clamped fields of unit loads at template ``dofs``:
        (rows, dofs)."""
        cols = self._form(dofs)
        rows = sp.csr_matrix(rows)
        used = np.unique(rows.indices)
        place = self.body.interior_place(used)
        used = used[place >= 0]               # a cut dof's clamped field is zero
        place = place[place >= 0]
        return np.asarray(rows[:, used] @ self._clamped(cols, place))

    def clamped_product(self, rows: np.ndarray, dofs: np.ndarray) -> np.ndarray:
        """Dense ``rows`` over the template's interior dofs (r, interior) applied to the
        clamped fields of unit loads at template ``dofs``: (r, dofs)."""
        return rows @ self._clamped(self._form(dofs))

    def _clamped(self, cols: np.ndarray, place: np.ndarray | None = None) -> np.ndarray:
        """The formed clamped fields' response columns ``cols``, their interior rows ``place``
        (default all), gathered from the blocks they were formed in."""
        rows = len(self.body.interior) if place is None else len(place)
        X = np.empty((rows, len(cols)))
        for start, block in self._X:
            sel = np.flatnonzero((cols >= start) & (cols < start + block.shape[1]))
            if len(sel):
                # rows, then columns: a gather each (np.ix_ took up to four times as long)
                rows_of = block if place is None else np.take(block, place, axis=0)
                X[:, sel] = np.take(rows_of, cols[sel] - start, axis=1)
        return X

    def cut_loads(self, dofs: np.ndarray) -> np.ndarray:
        """Cut loads (2 n_f, dofs) of unit loads at template ``dofs``."""
        cols = self._form(dofs)   # before reading _rho: forming may grow it
        return self._rho[:, cols]

    @property
    def cut_field(self) -> np.ndarray:
        """Template field (ndofs, 2 n_f) per unit cut displacement: interior by Ψ."""
        if self._cut_field is None:
            self._cut_field = self.body.from_cuts(np.eye(len(self.body.interface)))
        return self._cut_field

    # --- fields ------------------------------------------------------------------------------
    def fields(self, loads: dict[int, LoadBlock], values: np.ndarray,
               sectors, clamped: dict | None = None) -> dict[int, np.ndarray]:
        """Template-frame displacement (ndofs,) of each of ``sectors`` under the ``loads`` at
        the unknowns' ``values`` (``clamped``: loaded sectors' clamped fields formed before)."""
        f = {t: b.vector(values, self.body.ndofs) for t, b in loads.items()}
        f = {t: v for t, v in f.items() if np.any(v)}
        # the cut loads from the responses formed for the loads' few dofs (a product over the
        # whole template's Ψ a sector, which two processes read at once in a mesh cycle, else)
        rho = {t: self.cut_loads(loads[t].dofs) @ v[loads[t].dofs] for t, v in f.items()}
        return self.body.displacement(f, sectors, rho, clamped)

    def displacement_at(self, x: np.ndarray, fields: dict[int, np.ndarray]) -> np.ndarray:
        """Displacement (n, 2, gear frame) at points ``x`` of the gear from per-sector
        ``fields``; every sector the points fall in must be there."""
        where = self.locate(x)
        out = np.zeros_like(x)
        for k in np.unique(where.sector):
            sel = where.sector == k
            u = self.probe.displacement(where.local[sel], fields[int(k)])
            out[sel] = rotate(u, where.turn[sel])
        return out

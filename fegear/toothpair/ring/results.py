"""What a designer reads off a solved position of the ring model: per tooth its load, share,
peak pressure and half-width beside Hertz, its root stresses and whether its peak sits on the
tip round; and the whole rings' fields for the pictures and VTU files.

A gear-1 tooth's root stress is the largest σ1 in the tooth space after it, whose fillet it
bends in tension under the + torque; gear 2's is that of the space before the gear-2 tooth
nearest to where the gear-1 tooth touches it (its pressure peak, or the predicted contact point
if it carries none), that tooth's tension side (:func:`~..teeth.tension_fillets`). Hertz p0
and b use the curvature radii at the predicted contact point of the sharp profiles, as the
sector model does (docs/model.md, "Hertz").
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from ...contact import gap_contact, surface_matrix
from ...fe import FIELD_DTYPE, contact_modulus, recover_many, vtu_fields
from ...planar import rotate
from ..case import BodyField, ContactZone, FlankPressure, SolveCase, ToothResult
from ..edge import FlankEdge, flank_and_edge, flank_centre
from ..teeth import tension_fillets
from .contact import RingContactSolution, rigid_gap
from .influence import RingContact
from .model import RingModel
from .stresses import RingStresses, local_half_width

#: grid points across a contact's half-width from which its peak is within 0.7 % on a
#: parabolic gap wherever the points fall (2-3: −1.5 … +1 %; 1.5: +3 … +4 %)
RESOLVED_PER_B = 4.0


def from_tip_corner(shape, grid, pressure: np.ndarray) -> np.ndarray:
    """Distance (mm) of each point of ``grid`` along gear 1's rounded profile ``shape`` from
    the tip corner on its loaded side: the tangent point of a tip round nearest to where the
    flank carries its load (the kink itself on sharp tips); > 0 down the flank, < 0 on the
    round. The grid need not reach the round: the arc between them is measured on the
    profile."""
    centre = flank_centre(grid.phi, pressure, grid.on_round)
    turn = round((centre - shape.tooth_center) / shape.pitch) * shape.pitch
    # the rounds' tangent points, or with sharp tips (--tip-round 0) the kinks themselves
    corners = ([a for f in shape.fillets for a in (f.phi_a, f.phi_b)] if shape.fillets
               else [phi for phi, _ in shape.kinks])
    ends = np.array([a + turn + j * shape.pitch for a in corners for j in (-1, 0, 1)])
    if len(ends) == 0:                     # a smooth tip: no corner, the grid's start instead
        return grid.s - grid.s[0]
    corner = float(ends[np.argmin(np.abs(ends - centre))])
    phi = np.linspace(grid.phi[0], corner, 2001)
    x = shape.point(phi)
    arc = float(np.hypot(*np.diff(x, axis=0).T).sum())     # grid start to the corner, ≥ 0
    s_corner = grid.s[0] + math.copysign(arc, corner - grid.phi[0])
    return (grid.s - s_corner) * math.copysign(1.0, centre - corner)


def solved_rigid_gap(detail: RingDetail) -> tuple[np.ndarray, np.ndarray]:
    """The rigid gap (mm) of every point of the solved position ``detail`` at its solved
    rotation, and its rate with the turn (mm/rad) (:func:`~.contact.rigid_gap`)."""
    case, contact = detail.case, detail.contact
    return rigid_gap(detail.model, contact,
                     case.params.ratio * case.beta + detail.solution.rotation, contact.feet)


def tooth_results(detail: RingDetail, state, cands, rigid: tuple[np.ndarray, np.ndarray],
                  references: bool = True) -> tuple[ToothResult, ...]:
    """One :class:`~fegear.toothpair.case.ToothResult` per gridded tooth of the solved position
    ``detail``; ``state``: the position's clearance state (each tooth's clearance), ``cands``:
    the gridded teeth as candidates (:func:`~..teeth.candidate_data`: Hertz at each one's
    predicted contact point), ``rigid``: :func:`solved_rigid_gap`. Without stresses (a
    contact-only solve) the root stresses are NaN and the half-plane reference and the bending
    curvature are left out (None, 0), as they are without ``references``."""
    contact = detail.contact
    clearance = {c.tooth: c.plus_um for c in state.teeth}
    by_tooth = {c.tooth: c for c in cands}
    return tuple(tooth_result(detail, k, rigid, by_tooth.get(g.tooth), clearance.get(g.tooth),
                              references) for k, g in enumerate(contact.grids))


def tooth_result(detail: RingDetail, k: int, rigid: tuple[np.ndarray, np.ndarray], cand,
                  clearance_um: float | None, references: bool = True) -> ToothResult:
    """The result of grid ``k``'s tooth: ``rigid`` the rigid gap (mm) of every point at the
    solved rotation and its rate with the turn (mm/rad), ``cand`` the tooth as a candidate
    (None where it is not one); ``references``: its half-plane reference and bending
    curvature too."""
    model, case, contact, sol = detail.model, detail.case, detail.contact, detail.solution
    stresses = detail.stresses
    pitch1, pitch2 = model.shape.pitch, 2 * math.pi / case.params.z2
    gap, rate = rigid
    grid, blk = contact.grids[k], contact.block(k)
    w = contact.weight[blk] * case.thickness
    pk = sol.pressure[blk]
    load = float(w @ pk)
    i = blk.start + int(np.argmax(pk)) if load > 0 else blk.start
    if load > 0:
        x2 = contact.facing[0][i]
        theta2 = math.atan2(x2[1], x2[0])
    else:
        theta2 = cand.theta2 if cand is not None else math.nan
    hz = (cand.hertz(load, case.thickness, case.E, case.nu)
          if load > 0 and cand is not None else None)
    fillets = tension_fillets(model.shape.tooth_center + grid.tooth * pitch1, pitch1,
                              theta2 if math.isfinite(theta2) else 0.0, pitch2)
    # an unloaded tooth (most of a kept contact's wide grids): nothing on its flank or round
    # and no reference, what splitting and referencing no pressure give, without forming them
    split = (flank_and_edge(grid.s, pk, grid.on_round, case.thickness, model.shape.radius_mm,
                            contact_modulus(case.E, case.E)) if load > 0
             else FlankEdge(0.0, 0.0, 0.0))
    b = local_half_width(contact, sol.pressure, i) if load > 0 else 0.0
    refs = (_referenced(detail, k, gap[blk], load)
            if stresses is not None and references and load > 0
            else {"halfplane_p_MPa": None, "halfplane_flank_MPa": None, "bending_curvature": 0.0})
    j = i - blk.start
    spacing = 0.5 * (grid.s[min(j + 1, len(grid) - 1)] - grid.s[max(j - 1, 0)])
    per_b = b / spacing if load > 0 else 0.0
    return ToothResult(
        tooth=grid.tooth, clearance_um=clearance_um, load_N=load,
        load_share=float(-(w * pk) @ rate[blk] / (case.torque_Nmm)),
        p_max_MPa=float(pk.max()),
        half_width_mm=b,
        hertz_p0_MPa=hz.p0 if hz else None, hertz_b_mm=hz.b if hz else None,
        b_over_R=hz.b_over_R if hz else None,
        root1_MPa=(stresses.roots[0].near(fillets[0], pitch1) if stresses is not None
                   else math.nan),
        root2_MPa=(math.nan if stresses is None else
                   stresses.roots[1].near(fillets[1], pitch2) if math.isfinite(theta2)
                   else 0.0),
        peak_on_round=bool(load > 0 and grid.on_round[i - blk.start]),
        flank_p_MPa=split.flank_MPa, edge_p_MPa=split.edge_MPa,
        edge_load_N=split.edge_load_N,
        per_half_width=float(per_b),
        resolved=bool(load <= 0 or per_b >= RESOLVED_PER_B),
        tooth2=(int(round(theta2 / pitch2)) % case.params.z2 if math.isfinite(theta2)
                else None), **refs)


def with_references(detail: RingDetail, teeth: tuple[ToothResult, ...],
                    rigid: tuple[np.ndarray, np.ndarray]) -> tuple[ToothResult, ...]:
    """``teeth`` (:func:`tooth_results` without ``references``, one a grid of ``detail``)
    with each loaded tooth's half-plane reference and bending curvature, as
    :func:`tooth_results` forms them with ``references``."""
    out = []
    for k, t in enumerate(teeth):
        if t.load_N > 0:
            t = replace(t, **_referenced(detail, k, rigid[0][detail.contact.block(k)], t.load_N))
        out.append(t)
    return tuple(out)


def _referenced(detail: RingDetail, k: int, gap: np.ndarray, load: float) -> dict:
    """Grid ``k``'s tooth's half-plane reference peak and flank pressure and its bending
    curvature (:func:`_references`), as :class:`~..case.ToothResult`'s fields."""
    curvature, ref = _references(detail, k, gap, load)
    return {"halfplane_p_MPa": float(ref[0].max()) if ref else None,
            "halfplane_flank_MPa": ref[1].flank_MPa if ref else None,
            "bending_curvature": curvature}


def _references(detail: RingDetail, k: int, gap: np.ndarray, load: float):
    """The bending curvature of grid ``k``'s tooth (:func:`_bending`) and its half-plane
    reference (:func:`_halfplane`; None where it carries no ``load``, N), from the rigid
    ``gap`` (mm) of its points."""
    case, grid, blk = detail.case, detail.contact.grids[k], detail.contact.block(k)
    pk = detail.solution.pressure[blk]
    E_star = contact_modulus(case.E, case.E)
    surface = surface_matrix(grid.s, E_star) if load > 0 else None
    bend, curvature = _bending(grid.s, pk, detail.solution.gap[blk] - gap, gap, surface)
    ref = (_halfplane(detail, grid, gap + bend, load / case.thickness, surface, pk > 0)
           if load > 0 else None)
    return curvature, ref


def _bending(s: np.ndarray, p: np.ndarray, elastic: np.ndarray, gap: np.ndarray,
             surface: np.ndarray | None) -> tuple[np.ndarray, float]:
    """How the teeth's own deformation under the load changes the gap along a tooth's grid
    ``s`` (mm): the elastic opening ``elastic`` = A p the ring model computes, less the local
    indentation of two half-planes under the same pressure ``p`` (``surface``, their
    :func:`surface_matrix` on ``s``; None where nothing is loaded),
    fitted by a quadratic over the loaded stretch and held at its end values beyond it (the
    approach constant is immaterial; docs/model.md, "Hertz at load"). Also that quadratic's
    curvature over the unloaded ``gap``'s, fitted over the same stretch: −0.07 lowers the
    gap's curvature by 7 %, which lowers a Hertzian peak by about 3.5 %. Zero (and 0.0) where
    fewer than 3 points are loaded."""
    on = p > 0
    if np.count_nonzero(on) < 3:
        return np.zeros(len(s)), 0.0
    rest = elastic - surface @ p
    lo, hi = s[on].min(), s[on].max()
    inside = (s >= lo) & (s <= hi)
    fit = np.polyfit(s[inside], rest[inside], 2)
    g = np.polyfit(s[inside], gap[inside], 2)[0]
    return np.polyval(fit, np.clip(s, lo, hi)), float(fit[0] / g) if g > 0 else 0.0


def _halfplane(detail: RingDetail, grid, gap: np.ndarray, q: float, surface: np.ndarray,
               loaded: np.ndarray):
    """The reference of docs/model.md, "Hertz": two half-planes with the tooth's exact gap
    along its grid, bent as the teeth bend under the load, pressed by its load q (N/mm); its
    pressure and that split into flank and edge; None where its active set does not settle
    (no reference rather than no result). ``surface``: the grid's :func:`surface_matrix`;
    ``loaded``: the points the ring model loads, where its active set starts."""
    case = detail.case
    E_star = contact_modulus(case.E, case.E)
    thickness, radius = case.thickness, detail.model.shape.radius_mm
    try:
        p = gap_contact(grid.s, gap, q, E_star, surface=surface, start=loaded)
    except (ValueError, np.linalg.LinAlgError):
        return None
    return p, flank_and_edge(grid.s, p, grid.on_round, thickness, radius, E_star)


#: how many sectors :meth:`RingDetail.body_fields` forms at once
FIELD_SECTORS = 8


def _cells(mesh, copies: int) -> np.ndarray:
    """The quadratic triangles of ``copies`` copies of the template ``mesh``, one after the
    other, as 32-bit node numbers."""
    shift = mesh.doflocs.shape[1] * np.arange(copies, dtype=np.int32)
    return (mesh.dofs.element_dofs.T.astype(np.int32) + shift[:, None, None]).reshape(-1, 6)


@dataclass(eq=False)
class RingDetail:
    """The ring model's record of a solved position: the model, case, contact, its solution and
    the stresses (None: a contact-only solve)."""

    model: RingModel = field(repr=False)
    case: SolveCase
    contact: RingContact = field(repr=False)
    solution: RingContactSolution = field(repr=False)
    stresses: RingStresses | None = field(repr=False)

    def body_fields(self, around: int | None = None) -> tuple[BodyField, ...]:
        """Both gears in the fixed frame at the solved position: every sector's field and
        nodal stresses, and the contact pressure on the profile nodes, in
        :data:`~fegear.fe.FIELD_DTYPE`. Whole gears, or with ``around`` only the sectors that
        carry pressure and ``around`` sectors either side (a mesh cycle's series: a tenth of
        the size). The sectors are formed :data:`FIELD_SECTORS` at a time, each written into
        the whole arrays at once, so that what a group needs is freed and reused for the next:
        the memory the fields take is about their own size."""
        out = []
        for g, side in enumerate(self.model.gears):
            pressure = self._nodal_pressure(g)
            sectors = range(side.count) if around is None else sorted(
                {(k + d) % side.count for k in pressure for d in range(-around, around + 1)})
            n = side.body.mesh.doflocs.shape[1]
            whole = BodyField(side.body.name, np.empty((len(sectors) * n, 2), FIELD_DTYPE),
                              _cells(side.body.mesh, len(sectors)), {})
            for j in range(0, len(sectors), FIELD_SECTORS):
                self._fill(g, sectors[j:j + FIELD_SECTORS], pressure, whole, j * n)
            out.append(whole)
        return tuple(out)

    def _fill(self, g: int, sectors, pressure: dict, whole: BodyField, start: int) -> None:
        """Gear ``g``'s ``sectors`` formed and written into ``whole`` from row ``start`` on."""
        side = self.model.gears[g]
        turn, offset = self._placement(g)
        m = side.body.mesh
        n = m.doflocs.shape[1]
        fields = side.fields(self.contact.loads[g], self.solution.pressure, sectors)
        recovered = recover_many(side.body, np.column_stack([fields[k] for k in sectors]))
        for j, (k, s) in enumerate(zip(sectors, recovered)):
            part = vtu_fields(fields[k], s, {"contact_pressure": pressure.get(k, np.zeros(n))})
            angle = k * side.pitch + turn
            part["displacement"][:, :2] = rotate(part["displacement"][:, :2], angle)
            part.update(s.turned(angle))
            rows = slice(start + j * n, start + (j + 1) * n)
            for key, v in part.items():
                if key not in whole.data:
                    whole.data[key] = np.empty((len(whole.points), *v.shape[1:]), FIELD_DTYPE)
                whole.data[key][rows] = v
            whole.points[rows] = rotate(m.doflocs.T, angle) + offset

    def _nodal_pressure(self, gear: int) -> dict[int, np.ndarray]:
        """Per sector, the grid pressure at the template's profile nodes (MPa), by polar
        angle along each grid's points on that gear."""
        side = self.model.gears[gear]
        m = side.body.mesh
        nodes = np.unique(m.facets[:, side.facets].ravel())
        nodes = np.unique(np.concatenate([nodes, m.nvertices + side.facets]))
        local = m.doflocs[:, nodes].T
        pts = self.contact.x if gear == 0 else self.contact.facing[0]
        out = {}
        for k in range(len(self.contact.grids)):
            blk = self.contact.block(k)
            pk = self.solution.pressure[blk]
            if pk.max() <= 0:
                continue
            ang = np.arctan2(pts[blk, 1], pts[blk, 0])
            ref = ang[len(ang) // 2]
            ang = ref + (ang - ref + np.pi) % (2 * np.pi) - np.pi
            order = np.argsort(ang)
            centre = int(side.locate(pts[blk][[len(ang) // 2]]).sector[0])
            for sector in ((centre + d) % side.count for d in (-1, 0, 1)):
                a = np.arctan2(local[:, 1], local[:, 0]) + sector * side.pitch
                a = ref + (a - ref + np.pi) % (2 * np.pi) - np.pi
                on = np.interp(a, ang[order], pk[order], left=0.0, right=0.0)
                v = out.setdefault(sector, np.zeros(m.doflocs.shape[1]))
                v[nodes] = np.maximum(v[nodes], on)
        return out

    def peak_fields(self) -> tuple[BodyField, ...]:
        """The contact submodels in the fixed frame: displacement, stresses
        (:data:`~fegear.fe.FIELD_DTYPE`, as :meth:`body_fields`)."""
        out = []
        for gear, turn, sm in self.stresses.submodels:
            angle, offset = self._placement(gear)
            angle += turn
            m = sm.mesh.mesh
            data = vtu_fields(sm.u, sm.stress)
            data["displacement"][:, :2] = rotate(data["displacement"][:, :2], angle)
            data.update(sm.stress.turned(angle))
            data = {key: v.astype(FIELD_DTYPE) for key, v in data.items()}
            name = f"gear{gear + 1}_contact"
            name += "" if name not in {b.name for b in out} else f"_{len(out)}"
            out.append(BodyField(name, (rotate(m.doflocs.T, angle) + offset).astype(FIELD_DTYPE),
                                 m.dofs.element_dofs.T.astype(np.int32), data))
        return tuple(out)

    def flank_pressures(self) -> tuple[FlankPressure, ...]:
        """The contact pressure along each loaded tooth's grid, fixed frame."""
        angle, offset = self._placement(0)
        out = []
        for k, g in enumerate(self.contact.grids):
            p = self.solution.pressure[self.contact.block(k)]
            if p.max() > 0:
                out.append(FlankPressure(g.tooth, g.s.copy(), p.copy(), g.on_round.copy(),
                                         rotate(g.x, angle) + offset,
                                         from_tip_corner(self.model.shape, g, p)))
        return tuple(out)

    def _placement(self, gear: int) -> tuple[float, np.ndarray]:
        """The turn (rad) and offset (mm) that place ``gear``'s frame in the fixed one."""
        p = self.case.params
        if gear == 0:
            return p.ratio * self.case.beta + self.solution.rotation, np.array([0.0, p.e])
        return self.case.beta, np.zeros(2)

    def contact_zone(self) -> ContactZone:
        """The highest grid pressure, fixed frame."""
        pressure = self.solution.pressure
        i = int(np.argmax(pressure))
        k = int(self.contact.grid_index[i])
        angle, offset = self._placement(0)
        x = rotate(self.contact.x[i:i + 1], angle)[0] + offset
        return ContactZone((float(x[0]), float(x[1])), local_half_width(self.contact, pressure, i),
                           f"tooth {self.contact.grids[k].tooth}")


def equilibrium_residuals(model: RingModel, contact: RingContact, sol, stresses
                          ) -> list[float]:
    """Each gear's equilibrium residual on its computed sectors (relative to its loads)."""
    out = []
    for side, loads, fields in zip(model.gears, contact.loads, stresses.fields):
        f = {t: b.vector(sol.pressure, side.body.ndofs) for t, b in loads.items()}
        out.append(side.body.residual(f, fields))
    return out

"""The Hertz validation case: two disks pressed together, or a disk inside a bore.

Body 1 is the lower half of a disk of radius r1 about (0, r1); its flat cut is tied to a rigid
translation δ that carries the load P downwards. Body 2 is, for r2 > 0, the upper half of a disk
of radius r2 about (0, −r2) with its flat cut fixed; for r2 < 0, a ring whose bore of radius |r2|
about (0, |r2|) holds disk 1, with the outer rim (radius 2|r2|) fixed. First touch is at the
origin. Contact windows of a few Hertz half-widths are refined to b / ``elements_per_b``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..fe import (
    Body,
    BodyGeometry,
    HertzLine,
    Refinement,
    RigidLink,
    Segment,
    StressField,
    assemble_body,
    facet_nodes,
    mesh_bodies,
    recover,
    vtu_fields,
    write_vtu,
)
from ..files import write_json
from ..timing import clocked, timed
from .disk_case import DiskCase
from .penalty import (
    Circle,
    ContactError,
    ContactModel,
    ContactPair,
    ContactSettings,
    ContactSolution,
    build_contact,
    nodal_pressure,
    solve_contact,
)

SLAVE_WINDOW = 3.0   # slave contact window half-length, in Hertz half-widths
MASTER_WINDOW = 4.0  # master window: wider, so that every slave point has a facet under it


@dataclass(frozen=True)
class DiskResult:
    """FE against Hertz. ``p_max`` (MPa) and ``half_width`` (mm) from the FE traction;
    ``*_error_pct`` relative to Hertz; ``timings_s`` per stage; ``dofs`` of both bodies."""

    case: DiskCase
    hertz: HertzLine
    p_max: float
    half_width: float
    load_fe: float
    dofs: int
    contact_points: int
    iterations: int
    max_penetration: float
    surface_stress: float
    timings_s: dict[str, float]
    bodies: tuple[Body, ...] = field(repr=False)
    model: ContactModel = field(repr=False)
    solution: ContactSolution = field(repr=False)
    stresses: tuple[StressField, ...] = field(repr=False)

    @property
    def p_error_pct(self) -> float:
        return 100.0 * (self.p_max / self.hertz.p0 - 1.0)

    @property
    def b_error_pct(self) -> float:
        return 100.0 * (self.half_width / self.hertz.b - 1.0)

    def summary(self) -> dict:
        """JSON-ready summary: inputs, FE and Hertz values, errors, sizes, timings."""
        c, h = self.case, self.hertz
        return {
            "inputs": {"r1_mm": c.r1, "r2_mm": c.r2, "load_N": c.load,
                       "thickness_mm": c.thickness, "E_MPa": c.E, "nu": c.nu, "plane": c.plane,
                       "quality": c.quality, "elements_per_b": c.elements_per_b,
                       "penalty_factor": c.penalty_factor},
            "fe": {"p_max_MPa": self.p_max, "half_width_mm": self.half_width,
                   "surface_normal_stress_MPa": self.surface_stress,
                   "normal_load_N": self.load_fe},
            "hertz": {"p0_MPa": h.p0, "b_mm": h.b, "R_star_mm": h.R_star, "E_star_MPa": h.E_star,
                      "b_over_R": h.b_over_R,
                      "half_angle_deg": math.degrees(self.half_width / c.r1)},
            "error_pct": {"p_max": self.p_error_pct, "half_width": self.b_error_pct},
            "dofs": self.dofs, "contact_points": self.contact_points,
            "contact_iterations": self.iterations,
            "max_penetration_mm": self.max_penetration,
            "timings_s": self.timings_s,
        }


def _arc(center, radius, a0, a1, chord=None) -> np.ndarray:
    n = max(8, int(abs(a1 - a0) * radius / (chord or radius / 40)) + 2)
    a = np.linspace(a0, a1, n)
    return np.asarray(center) + radius * np.column_stack([np.cos(a), np.sin(a)])


def disk_geometries(case: DiskCase) -> tuple[BodyGeometry, BodyGeometry, Circle, Circle]:
    """Both bodies' boundaries (with named windows) and their exact curves."""
    h = case.hertz
    size_c = h.b / case.elements_per_b
    r1 = case.r1
    c1 = (0.0, r1)
    circle1 = Circle(c1, r1, "inside")
    w1 = min(SLAVE_WINDOW * h.b / r1, 0.45 * math.pi)
    down = 1.5 * math.pi
    body1 = BodyGeometry("disk1", (
        Segment("rim_left", _arc(c1, r1, math.pi, down - w1), circle1.project),
        Segment("contact", _arc(c1, r1, down - w1, down + w1, size_c), circle1.project),
        Segment("rim_right", _arc(c1, r1, down + w1, 2 * math.pi), circle1.project),
        Segment("cut", np.array([[r1, r1], [-r1, r1]])),
    ), size=r1 / 5, refinements=(Refinement(("contact",), size_c),))

    if case.r2 > 0:
        r2 = case.r2
        c2 = (0.0, -r2)
        circle2 = Circle(c2, r2, "inside")
        w2 = min(MASTER_WINDOW * h.b / r2, 0.45 * math.pi)
        up = 0.5 * math.pi
        body2 = BodyGeometry("disk2", (
            Segment("rim_right", _arc(c2, r2, 0.0, up - w2), circle2.project),
            Segment("contact", _arc(c2, r2, up - w2, up + w2, size_c), circle2.project),
            Segment("rim_left", _arc(c2, r2, up + w2, math.pi), circle2.project),
            Segment("cut", np.array([[-r2, -r2], [r2, -r2]])),
        ), size=r2 / 5, refinements=(Refinement(("contact",), size_c),))
    else:
        R = -case.r2
        c2 = (0.0, R)
        circle2 = Circle(c2, R, "outside")
        rim = Circle(c2, 2 * R, "inside")
        w2 = min(MASTER_WINDOW * h.b / R, 0.45 * math.pi)
        down = 1.5 * math.pi
        body2 = BodyGeometry("bore", (
            Segment("rim", _arc(c2, 2 * R, 0.0, math.pi), rim.project),
            Segment("rim", _arc(c2, 2 * R, math.pi, 2 * math.pi), rim.project),
        ), size=R / 5, holes=((
            Segment("bore_right", _arc(c2, R, down + w2, 2 * math.pi + down - w2),
                    circle2.project),
            Segment("contact", _arc(c2, R, down - w2, down + w2, size_c), circle2.project),
        ),), refinements=(Refinement(("contact",), size_c),))
    return body1, body2, circle1, circle2


def solve_disks(case: DiskCase) -> DiskResult:
    """Mesh, assemble, condense and solve the disk case; compare with Hertz."""
    with clocked() as clock:
        with timed("mesh"):
            g1, g2, _, circle2 = disk_geometries(case)
            m1, m2 = mesh_bodies([g1, g2])
        with timed("assemble_factor"):
            mat = case.material
            link = RigidLink("cut", "translation", direction=(0.0, -1.0))
            b1 = assemble_body(m1, mat, link=link)
            fixed = ("cut",) if case.r2 > 0 else ("rim",)
            b2 = assemble_body(m2, mat, fixed=fixed)
        with timed("condense"):
            settings = ContactSettings(penalty_factor=case.penalty_factor)
            pair = ContactPair("disk1/disk2", 0, "contact", 1, "contact", circle2)
            model = build_contact([b1, b2], [pair], settings)
        with timed("contact"):   # the flexibility columns it forms meanwhile: "condense"
            sol = solve_contact(model, load=case.load)
        if len(sol.zones) != 1:
            raise ContactError(f"expected one contact zone, found {len(sol.zones)}")
        zone = sol.zones[0]
        with timed("recovery"):
            stresses = tuple(recover(b, u) for b, u in zip((b1, b2), sol.displacements))
    times = dict(clock.stages)
    surface = _surface_peak(b1, stresses[0], case.r1)
    return DiskResult(case=case, hertz=case.hertz, p_max=zone.p_max,
                      half_width=zone.half_width, load_fe=sol.total_load,
                      dofs=b1.ndofs + b2.ndofs, contact_points=model.npoints,
                      iterations=sol.iterations, max_penetration=sol.max_penetration,
                      surface_stress=surface, timings_s=times, bodies=(b1, b2), model=model,
                      solution=sol, stresses=stresses)


def write_disk_outputs(result: DiskResult, out: Path) -> dict[str, Path]:
    """VTU per body (displacement, stresses, von Mises, σ1, contact pressure) and summary.json."""
    files = {}
    for i, (body, u, stress) in enumerate(zip(result.bodies, result.solution.displacements,
                                               result.stresses)):
        pressure = nodal_pressure(result.model, result.solution, i)
        data = vtu_fields(u, stress, {"contact_pressure": pressure})
        files[body.name] = write_vtu(out / f"{body.name}.vtu", body.mesh.doflocs.T,
                                     body.mesh.dofs.element_dofs.T, data)
    files["summary"] = write_json(out / "summary.json", result.summary())
    return files


def _surface_peak(body: Body, stress: StressField, r1: float) -> float:
    """Largest compressive recovered normal stress −n·σ·n on disk 1's contact window (MPa)."""
    nodes = np.unique(facet_nodes(body.mesh, body.mesh.boundaries["contact"]))
    r = body.mesh.doflocs.T[nodes] - np.array([0.0, r1])
    n = r / np.linalg.norm(r, axis=1)[:, None]
    return float(-stress.normal_stress(nodes, n).min())

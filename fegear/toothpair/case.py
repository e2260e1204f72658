"""A tooth-pair case and its results: :class:`SolveCase` (the inputs, checked),
:class:`ToothResult` per paired tooth and :class:`PairSolution` per rolling position.

Units: torque N·m, lengths mm, angles rad, stresses MPa.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Protocol

import numpy as np

from ..checks import require_range
from ..fe import ElasticMaterial
from ..geometry import NO_DEVIATIONS, Deviations, PairParameters, check_teeth, gear1_profile
from ..planar import wrap
from ..quantities import HEADLINES
from .inputs import (
    SOLVE_INPUTS,
    TIP_ROUND,
    Quality,
    check_tip_round,
    check_torque,
    torque_limit,
)

#: headline stresses: JSON key (MPa) → label (:data:`fegear.quantities.HEADLINES`)
HEADLINE = {q.key: q.label for q in HEADLINES}
#: gear 1's rim reaches at most this share of its root radius: the bore keeps the rest (a gear
#: of few teeth and deep teeth has a root radius below the default 3 m; the rim stops short)
RIM1_SHARE = 0.6


@dataclass(frozen=True)
class SolveCase:
    """Inputs: the pair, torque (N·m) on gear 1, rolling angle β (rad), face width (mm), one
    material (E MPa, ν), quality, rim thicknesses below the roots (mm; default 3 m), extra
    teeth paired on each side of the chosen ones (beyond what the closure needs: the safety
    check), gear 1's tip-edge round (mm) and the pair's manufacturing and assembly
    deviations (:class:`~fegear.geometry.Deviations`; none: the exact pair)."""

    params: PairParameters
    torque: float = SOLVE_INPUTS["torque"].default
    beta: float = 0.0
    thickness: float = SOLVE_INPUTS["face-width"].default
    E: float = SOLVE_INPUTS["E"].default
    nu: float = SOLVE_INPUTS["nu"].default
    quality: Quality = SOLVE_INPUTS["quality"].default
    rim1: float | None = None
    rim2: float | None = None
    extra_pairs: int = SOLVE_INPUTS["extra-pairs"].default
    tip_round: float | None = None
    deviations: Deviations = NO_DEVIATIONS

    def __post_init__(self) -> None:
        # a position's own input is ±π; a revolution runs on up to one turn of gear 1 beyond
        require_range("position", self.beta, -math.pi, 3 * math.pi, unit="rad")
        ElasticMaterial(self.E, self.nu, self.thickness)  # validates E, nu, thickness
        check_torque(self.torque, self.E, self.params.m, self.thickness, self.params.r1)
        SOLVE_INPUTS["quality"].check(self.quality)
        m = self.params.m
        if self.rim1 is not None:
            deepest = min(20 * m, RIM1_SHARE * self.root_radius1)
            require_range("rim1", self.rim1, min(0.5 * m, deepest), deepest,
                          unit=f"mm (m/2 ... 20 m, at most {RIM1_SHARE:g} of gear 1's root "
                               f"radius {self.root_radius1:.4g} mm)")
        if self.rim2 is not None:
            require_range("rim2", self.rim2, 0.5 * m, 20 * m, unit="mm")
        SOLVE_INPUTS["extra-pairs"].check(self.extra_pairs)
        if self.tip_round is not None:
            check_tip_round(self.tip_round, m)
        check_teeth(self.deviations, self.params.z1, self.params.z2)

    @property
    def torque_limit(self) -> float:
        """The largest torque the solve takes (N·m): :data:`~.inputs.LOAD_LIMIT` E m b r1."""
        return torque_limit(self.E, self.params.m, self.thickness, self.params.r1)

    @property
    def torque_Nmm(self) -> float:
        """The torque in N·mm: the contact's units are mm, N and MPa."""
        return self.torque * 1e3

    @property
    def material(self) -> ElasticMaterial:
        return ElasticMaterial(self.E, self.nu, self.thickness, "stress")

    @property
    def edge_radius(self) -> float:
        """Gear 1's tip-edge round (mm); default TIP_ROUND · m."""
        return self.tip_round if self.tip_round is not None else TIP_ROUND * self.params.m

    @property
    def root_radius1(self) -> float:
        """Gear 1's root radius (mm), from its exact profile."""
        g1 = gear1_profile(self.params)
        return float(g1.radius(np.array([g1.phi_space]))[0])

    @property
    def rims(self) -> tuple[float, float]:
        """Gear 1's rim below its roots and gear 2's beyond its roots (mm): those given, else
        3 m each, gear 1's at most :data:`RIM1_SHARE` of its root radius."""
        d = 3.0 * self.params.m
        return (self.rim1 if self.rim1 is not None else min(d, RIM1_SHARE * self.root_radius1),
                self.rim2 if self.rim2 is not None else d)


@dataclass(frozen=True)
class ToothResult:
    """One paired gear-1 tooth: normal load (N), torque share, FE contact pressure peak (MPa)
    and half-width (mm), Hertz p0 and b from the FE load and the analytic curvature radii
    (None where the curvatures are not a Hertz pair), b/R*, unloaded clearance (µm); whether
    the peak sits on gear 1's tip round; the flank and edge pressures apart and the round's
    load (edge contact); the pressure of two half-planes with the profiles' exact gap under
    the same load (Hertz without the constant curvature; ring model); and how finely the
    contact is resolved."""

    tooth: int
    clearance_um: float | None    # None: no + contact point on this tooth at this β
    load_N: float
    load_share: float
    p_max_MPa: float
    half_width_mm: float
    hertz_p0_MPa: float | None
    hertz_b_mm: float | None
    b_over_R: float | None
    root1_MPa: float          # max σ1 in the fillets of the space after this tooth (its
                              # tension side under the + torque) …
    root2_MPa: float          # … and of gear 2's space before the tooth it presses on
    peak_on_round: bool       # the largest traction sits on gear 1's tip-edge round
    flank_p_MPa: float = 0.0  # pressure on the flank and its relief, away from the round …
    edge_p_MPa: float = 0.0   # … and on the round (:mod:`~fegear.toothpair.edge`)
    edge_load_N: float = 0.0  # the load the round carries
    halfplane_p_MPa: float | None = None      # the exact-gap half-plane reference, the teeth's
                                              # bending included: its peak …
    halfplane_flank_MPa: float | None = None  # … and its flank pressure (docs/model.md, "Hertz")
    bending_curvature: float = 0.0  # the bending's change of the gap's curvature (relative)
    per_half_width: float = 0.0  # grid points (or elements) across the half-width (0: no load) …
    resolved: bool = True        # … and whether that is enough for a converged pressure
    tooth2: int | None = None    # the gear-2 tooth it presses on (None: not known)

    @property
    def edge_contact(self) -> bool:
        """Whether this tooth's tip round carries load."""
        return self.edge_load_N > 0


@dataclass(frozen=True)
class ContactChecks:
    """How a position's contact solve converged: torque-balance error (relative), the largest
    overlap left where pressure acts (mm), iterations, each body's equilibrium residual
    (relative) and the number of contact unknowns."""

    balance_error: float
    max_penetration: float
    iterations: int
    residuals: tuple[float, ...]
    points: int


@dataclass(frozen=True)
class BodyField:
    """What the output stage draws of one body: its name, node coordinates in the fixed frame
    (n, 2, mm), quadratic triangles (m, 6: corners, then the midside nodes of edges 01, 12,
    20) and point data by name (fixed-frame components)."""

    name: str
    points: np.ndarray
    cells: np.ndarray
    data: dict


@dataclass(frozen=True)
class FlankPressure:
    """The contact pressure along one loaded gear-1 tooth: arc length along its profile ``s``
    (mm, increasing with the polar angle), pressure (MPa), whether each point lies on the tip
    round, the points (n, 2, fixed frame, mm) and each point's distance along the profile from
    the tooth's tip corner on the loaded side (mm: > 0 down the flank, < 0 on the round; the
    corner is where the round meets the flank)."""

    tooth: int
    s: np.ndarray
    pressure: np.ndarray
    on_round: np.ndarray
    points: np.ndarray
    from_corner: np.ndarray


@dataclass(frozen=True)
class ContactZone:
    """Where the highest contact stress sits (fixed frame, mm), the contact's half-width there
    (mm) and a label."""

    centre: tuple[float, float]
    half_width: float
    label: str


class SolutionDetail(Protocol):
    """A model's own record of a solved position (its meshes, fields, contact state), which
    the output stage turns into pictures and VTU files."""

    def body_fields(self, around: int | None = None) -> tuple[BodyField, ...]: ...

    def peak_fields(self) -> tuple[BodyField, ...]: ...

    def flank_pressures(self) -> tuple[FlankPressure, ...]: ...

    def contact_zone(self) -> ContactZone: ...


@dataclass(frozen=True)
class PairSolution:
    """One solved position of a tooth pair, by the ring model or by the sector model (its
    peer). Stresses in MPa, rotations in rad: θ of gear 1 from its kinematic position under
    the load, and at the first touch."""

    case: SolveCase
    teeth: tuple[ToothResult, ...]
    root_stress: tuple[float, float]          # max σ1 on the root zones of gear 1, gear 2
    von_mises_max: float
    rotation: float
    first_touch: float
    dofs: int
    checks: ContactChecks
    timings_s: dict
    detail: SolutionDetail = field(repr=False)
    von_mises_estimated: bool = False   # the von Mises stress at the contacts is the ring
                                        # model's surface estimate: no submodel solved there
    tangent_stiffness: float = math.nan  # dT/dθ at the load, the contact set kept (N·m/rad;
                                         # the ring model's; NaN where not computed)

    @property
    def contact_pressure(self) -> float:
        return max(t.p_max_MPa for t in self.teeth if t.load_N > 0)

    @property
    def flank_contact_pressure(self) -> float:
        """The largest flank pressure, away from the tip rounds."""
        return max(t.flank_p_MPa for t in self.teeth if t.load_N > 0)

    @property
    def mesh_stiffness(self) -> float:
        """Secant mesh stiffness T / (θ − θ_touch), N·m/rad: the static one (a linearised
        dynamic model's spring is :attr:`tangent_stiffness`)."""
        return self.case.torque / (self.rotation - self.first_touch)

    @property
    def teeth_in_contact(self) -> int:
        return sum(1 for t in self.teeth if t.load_N > 0)

    def headline(self) -> dict[str, float]:
        return {"root_stress_gear1_MPa": self.root_stress[0],
                "root_stress_gear2_MPa": self.root_stress[1],
                "contact_pressure_MPa": self.contact_pressure,
                "flank_contact_pressure_MPa": self.flank_contact_pressure,
                "von_mises_max_MPa": self.von_mises_max}


def cycle_positions(beta0: float, n: int, z2: int) -> tuple[float, ...]:
    """``n`` rolling angles evenly across one tooth pitch 2π/z2 of gear 2, from β0."""
    return tuple(float(wrap(beta0 + k * 2 * math.pi / z2 / n)) for k in range(n))


def revolution_positions(beta0: float, per_pitch: int, z1: int, z2: int) -> tuple[float, ...]:
    """Rolling angles β (rad) from ``beta0`` over z1 pitches of gear 2 (one turn of gear 1),
    ``per_pitch`` evenly in each."""
    step = 2 * math.pi / z2 / per_pitch
    return tuple(beta0 + k * step for k in range(z1 * per_pitch))


def phase_major(count: int, z1: int) -> list[int]:
    """The ``count`` positions of a revolution over ``z1`` pitches (:func:`revolution_positions`)
    in the order a solve takes them: each place within a pitch over every pitch, then the
    next. A solve kept for the first pitch of a place serves the others (the ring model's
    :mod:`~.ring.phases`), and a mesh cycle's two chains, its halves, then carry alike
    whichever teeth the deviations are on."""
    per_pitch = count // z1
    return sorted(range(count), key=lambda k: (k % per_pitch, k // per_pitch))


def in_given_order(order, solved) -> tuple:
    """``solved``, one result a position taken in ``order`` (:func:`phase_major`), back in
    the positions' own order."""
    back = [None] * len(order)
    for k, got in zip(order, solved):
        back[k] = got
    return tuple(back)

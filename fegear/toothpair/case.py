"""A tooth-pair case and its results: :class:`SolveCase` (the inputs, checked),
:class:`ToothResult` per paired tooth and :class:`PairSolution` per rolling position.

Units: torque N·m, lengths mm, angles rad, stresses MPa.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from ..checks import require_range
from ..fe import Material
from ..geometry import PairParameters
from ..planar import wrap
from .inputs import SOLVE_INPUTS, TIP_ROUND

if TYPE_CHECKING:  # the FE stack is imported where it runs, not by the input checks
    from ..contact import ContactModel, ContactSolution
    from ..fe import Body, StressField
    from .scene import Scene

#: headline stresses: JSON key (MPa) → label in the table and the cycle plot
HEADLINE = {"root_stress_gear1_MPa": "root σ1, gear 1", "root_stress_gear2_MPa": "root σ1, gear 2",
            "contact_pressure_MPa": "contact pressure", "von_mises_max_MPa": "von Mises max"}


@dataclass(frozen=True)
class SolveCase:
    """Inputs: the pair, torque (N·m) on gear 1, rolling angle β (rad), face width (mm), one
    material (E MPa, ν), quality, rim thicknesses below the roots (mm; default 3 m), unloaded
    extra teeth meshed on each side, extra teeth paired on each side of the chosen ones
    (beyond what the closure needs: the safety check), penalty factor, gear 1's tip-edge
    round (mm)."""

    params: PairParameters
    torque: float = 200.0
    beta: float = 0.0
    thickness: float = 5.0
    E: float = 206000.0
    nu: float = 0.29
    quality: str = "standard"
    rim1: float | None = None
    rim2: float | None = None
    extra_teeth: int = 2
    extra_pairs: int = 0
    penalty_factor: float = 1000.0
    tip_round: float | None = None

    def __post_init__(self) -> None:
        SOLVE_INPUTS["torque"].check(self.torque)
        require_range("position", self.beta, -math.pi, math.pi, unit="rad")
        Material(self.E, self.nu, self.thickness)  # validates E, nu, thickness
        SOLVE_INPUTS["quality"].check(self.quality)
        for name in ("rim1", "rim2"):
            v = getattr(self, name)
            if v is not None:
                require_range(name, v, 0.5 * self.params.m, 20 * self.params.m, unit="mm")
        for name in ("extra-teeth", "extra-pairs", "penalty-factor"):
            SOLVE_INPUTS[name].check(getattr(self, SOLVE_INPUTS[name].dest))
        if self.tip_round is not None:
            require_range("tip_round", self.tip_round, 0.0, 0.5 * self.params.m, unit="mm")

    @property
    def material(self) -> Material:
        return Material(self.E, self.nu, self.thickness, "stress")

    @property
    def edge_radius(self) -> float:
        """Gear 1's tip-edge round (mm); default TIP_ROUND · m."""
        return self.tip_round if self.tip_round is not None else TIP_ROUND * self.params.m

    @property
    def rims(self) -> tuple[float, float]:
        d = 3.0 * self.params.m
        return (self.rim1 if self.rim1 is not None else d,
                self.rim2 if self.rim2 is not None else d)


@dataclass(frozen=True)
class ToothResult:
    """One paired gear-1 tooth: normal load (N), torque share, FE contact pressure peak (MPa)
    and half-width (mm), Hertz p0 and b from the FE load and the analytic curvature radii
    (None where the curvatures are not a Hertz pair), b/R*, unloaded clearance (µm); whether
    the peak sits on gear 1's tip round (edge contact)."""

    tooth: int
    clearance_um: float | None    # None: no + contact point on this tooth at this β
    load_N: float
    load_share: float
    p_max_MPa: float
    half_width_mm: float
    hertz_p0_MPa: float | None
    hertz_b_mm: float | None
    b_over_R: float | None
    root1_MPa: float          # max σ1 in the root zone within ± half a pitch of this tooth
    root2_MPa: float          # … and of the gear-2 tooth it meshes with
    peak_on_round: bool       # the largest traction sits on gear 1's tip-edge round


@dataclass(frozen=True)
class PairSolution:
    """One position of the tooth-pair solve (see module docstring). Stresses in MPa."""

    case: SolveCase
    scene: Scene = field(repr=False)
    bodies: tuple[Body, ...] = field(repr=False)
    model: ContactModel = field(repr=False)
    contact: ContactSolution = field(repr=False)
    stresses: tuple[StressField, ...] = field(repr=False)
    root_zones: tuple[np.ndarray, np.ndarray] = field(repr=False)  # nodes per gear
    teeth: tuple[ToothResult, ...]
    root_stress: tuple[float, float]          # max σ1 on the root zones of gear 1, gear 2
    von_mises_max: float
    rotation: float                           # θ of gear 1 (rad), from its kinematic position
    first_touch: float                        # θ at which the first tooth touches (rad)
    dofs: int
    timings_s: dict

    @property
    def contact_pressure(self) -> float:
        return max(t.p_max_MPa for t in self.teeth if t.load_N > 0)

    @property
    def mesh_stiffness(self) -> float:
        """Secant mesh stiffness T / (θ − θ_touch), N·m/rad."""
        return self.case.torque / (self.rotation - self.first_touch)

    @property
    def teeth_in_contact(self) -> int:
        return sum(1 for t in self.teeth if t.load_N > 0)

    def headline(self) -> dict[str, float]:
        return {"root_stress_gear1_MPa": self.root_stress[0],
                "root_stress_gear2_MPa": self.root_stress[1],
                "contact_pressure_MPa": self.contact_pressure,
                "von_mises_max_MPa": self.von_mises_max}


def cycle_positions(beta0: float, n: int, z2: int) -> tuple[float, ...]:
    """``n`` rolling angles evenly across one tooth pitch 2π/z2 of gear 2, from β0."""
    return tuple(float(wrap(beta0 + k * 2 * math.pi / z2 / n)) for k in range(n))

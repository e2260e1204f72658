"""The inputs of seed 003's reducer model (:mod:`.reducer`): Table 1's values as defaults and
the choices for what it leaves unsaid (docs/drive.md). No numpy here: ``fegear drive reducer
--help`` reads the defaults."""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..checks import require_range
from ..errors import ParameterError

#: the builds: plate thickness fractions and eccentric phases (rad)
BUILDS = {1: ((1.0, 0.0),),
          2: ((0.5, 0.0), (0.5, math.pi)),
          3: ((0.25, 0.0), (0.5, math.pi), (0.25, 0.0))}


@dataclass(frozen=True)
class ReducerInputs:
    """Seed 003's Table 1 (defaults) and what it leaves unsaid (docs/drive.md says how each
    unsaid value was chosen). Stiffnesses in N/m; masses kg; the plate's polar inertia
    kg·m²; lengths mm. ``mesh_stiffness``, ``plate_mass``, ``plate_inertia`` and
    ``eccentric_mass`` are a single plate's of the whole thickness."""

    power_kW: float = 4.0
    speed_rpm: float = 1500.0
    module_mm: float = 2.0
    z_plate: int = 122
    z_gear: int = 120
    eccentricity_mm: float = 2.34
    mesh_angle_deg: float = 36.75
    bearing_stiffness: float = 1e8
    mesh_stiffness: float = 4.97e8
    mesh_damping: float = 0.05
    plate_mass: float = 39.54
    plate_inertia: float = 2.102
    eccentric_mass: float = 0.29
    motor_inertia: float = 0.0
    input_diameter_mm: float = 38.75
    input_length_mm: float = 465.0
    output_diameter_mm: float = 68.0
    output_length_mm: float = 585.0
    plate_thickness_mm: float = 25.0
    plate_gap_mm: float = 5.0
    crank_radius_mm: float = 190.0
    crank_angle_deg: float = 0.0
    elements: int = 24

    def __post_init__(self) -> None:
        positive = ("power_kW", "speed_rpm", "module_mm", "eccentricity_mm",
                    "bearing_stiffness", "mesh_stiffness", "plate_mass", "plate_inertia",
                    "input_diameter_mm", "input_length_mm", "output_diameter_mm",
                    "output_length_mm", "plate_thickness_mm")
        for name in positive:
            require_range(name, getattr(self, name), 0.0, None, lo_open=True)
        require_range("z_gear", self.z_gear, 3, 1000)
        require_range("z_plate", self.z_plate, self.z_gear + 1, 1001)
        require_range("mesh_angle_deg", self.mesh_angle_deg, 0.0, 60.0, lo_open=True,
                      hi_open=True)
        require_range("mesh_damping", self.mesh_damping, 0.0, 1.0, hi_open=True)
        require_range("eccentric_mass", self.eccentric_mass, 0.0, None)
        require_range("motor_inertia", self.motor_inertia, 0.0, 1e3)
        require_range("plate_gap_mm", self.plate_gap_mm, 0.0, None)
        require_range("elements", self.elements, 4, 400)
        if self.output_length_mm < self.input_length_mm:
            raise ParameterError("output_length_mm", self.output_length_mm,
                                 f">= the crank shafts' span {self.input_length_mm:g} mm "
                                 "(the output shaft has their span and an overhang)")
        stack = 3 * self.plate_gap_mm + self.plate_thickness_mm
        if stack >= self.input_length_mm:
            raise ParameterError("plate_thickness_mm", self.plate_thickness_mm,
                                 f"< {self.input_length_mm - 3 * self.plate_gap_mm:g} mm "
                                 "(the plates fit between the support bearings)")
        if self.module_mm * self.z_gear <= self.output_diameter_mm:
            raise ParameterError("z_gear", self.z_gear,
                                 f"> {self.output_diameter_mm / self.module_mm:g} (the gear's "
                                 f"reference diameter beyond the {self.output_diameter_mm:g} mm "
                                 "output shaft)")
        gear_radius = 0.5 * self.module_mm * self.z_gear
        require_range("crank_radius_mm", self.crank_radius_mm,
                      gear_radius + 0.5 * self.input_diameter_mm, 1e4, lo_open=True,
                      unit="mm (the crank shafts stand outside the gear)")
        require_range("crank_angle_deg", self.crank_angle_deg, -360.0, 360.0, unit="deg")

    @property
    def ratio(self) -> float:
        """Input (crank) to output speed: z_gear / (z_plate − z_gear)."""
        return self.z_gear / (self.z_plate - self.z_gear)

    @property
    def omega(self) -> float:
        """Working crank speed (rad/s)."""
        return self.speed_rpm * math.pi / 30.0

    @property
    def output_torque(self) -> float:
        """Output torque at the power and speed, losses aside (N·m)."""
        return 1e3 * self.power_kW * self.ratio / self.omega

    @property
    def mesh_frequency(self) -> float:
        """Mesh frequency at the working speed (rad/s): the contact runs once round the
        non-turning plate a crank turn, z_plate teeth."""
        return self.z_plate * self.omega

    @property
    def working_pitch_radii(self) -> tuple[float, float]:
        """Working pitch radii (m) of the gear and the plate: centre distance e, ratio
        z_plate / z_gear."""
        e = 1e-3 * self.eccentricity_mm
        d = self.z_plate - self.z_gear
        return e * self.z_gear / d, e * self.z_plate / d

    @property
    def base_radius(self) -> float:
        """The gear's lever arm of the line of action (m)."""
        return self.working_pitch_radii[0] * math.cos(math.radians(self.mesh_angle_deg))

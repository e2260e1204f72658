"""The inputs of seed 003's reducer model (:mod:`.reducer`): Table 1's values as defaults and
the choices for what it leaves unsaid (docs/drive.md). No numpy here: ``fegear drive reducer
--help`` reads the defaults."""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..checks import Input, require_int, require_range
from ..errors import ParameterError

#: the builds: plate thickness fractions and eccentric phases (rad)
BUILDS = {1: ((1.0, 0.0),),
          2: ((0.5, 0.0), (0.5, math.pi)),
          3: ((0.25, 0.0), (0.5, math.pi), (0.25, 0.0))}


#: the model's inputs (``fegear drive reducer``'s options): Table 1's values as defaults and
#: the choices for what it leaves unsaid (docs/drive.md says how each was chosen). The ranges
#: of those with ``limits`` depend on the others and are stated at their values.
REDUCER_INPUTS = (
    Input("power-kW", float, 4.0, "power", "kW", low=0.0, low_open=True),
    Input("speed-rpm", float, 1500.0, "working crank (input) speed", "r/min", low=0.0,
          low_open=True),
    Input("module-mm", float, 2.0, "module", "mm", low=0.0, low_open=True),
    Input("z-plate", int, 122, "internal-gear plate teeth", low=4, high=1001,
          limits="an integer z-gear < z-plate <= 1001"),
    Input("z-gear", int, 120, "external (output) gear teeth", low=3, high=1000,
          limits="an integer 3 <= z-gear <= 1000 with the gear's reference diameter beyond "
                 "the output shaft"),
    Input("eccentricity-mm", float, 2.34, "eccentricity", "mm", low=0.0, low_open=True),
    Input("mesh-angle-deg", float, 36.75, "working pressure angle", "deg", low=0.0,
          high=60.0, low_open=True, high_open=True),
    Input("bearing-stiffness", float, 1e8, "support and planet bearing stiffness", "N/m",
          low=0.0, low_open=True),
    Input("mesh-damping", float, 0.05, "mesh damping ratio ζ", low=0.0, high=1.0,
          high_open=True),
    Input("plate-mass", float, 39.54, "plate mass, a single plate of the whole thickness",
          "kg", low=0.0, low_open=True),
    Input("plate-inertia", float, 2.102, "plate polar moment of inertia (Table 1: 21.02, "
          "unit lost; docs/drive.md)", "kg·m²", low=0.0, low_open=True),
    Input("eccentric-mass", float, 0.29, "mass of each crank's eccentric (Table 1's 0.29 kg, "
          "label lost)", "kg", low=0.0),
    Input("motor-inertia", float, 0.0, "the motor rotor's inertia at the input's drive end "
          "(not in Table 1)", "kg·m²", low=0.0, high=1e3),
    Input("input-diameter-mm", float, 38.75, "crank shafts' mean diameter", "mm", low=0.0,
          low_open=True),
    Input("input-length-mm", float, 465.0, "crank shafts' length = support span", "mm",
          low=0.0, low_open=True),
    Input("output-diameter-mm", float, 68.0, "output shaft's mean diameter", "mm", low=0.0,
          low_open=True),
    Input("output-length-mm", float, 585.0, "output shaft's length (the span and an "
          "overhang)", "mm", low=0.0, low_open=True,
          limits="input-length-mm <= output-length-mm"),
    Input("plate-thickness-mm", float, 25.0, "total plate thickness (not in Table 1)", "mm",
          low=0.0, low_open=True,
          limits="0 < plate-thickness-mm < input-length-mm - 3 plate-gap-mm"),
    Input("plate-gap-mm", float, 5.0, "axial gap between plates (not in Table 1)", "mm",
          low=0.0),
    Input("crank-radius-mm", float, 190.0, "distance of the crank shafts from the output "
          "axis (not in Table 1)", "mm", low=0.0, high=1e4, low_open=True,
          limits="the gear's pitch radius + input-diameter-mm/2 < crank-radius-mm <= 10000 "
                 "mm"),
    Input("crank-angle-deg", float, 0.0, "crank angle the model's geometry is frozen at",
          "deg", low=-360.0, high=360.0),
    Input("elements", int, 24, "beam elements over the crank shafts' span", low=4, high=400),
)
_ROW = {row.dest: row for row in REDUCER_INPUTS}


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
        for row in REDUCER_INPUTS:          # the static ranges; those with limits below
            if not row.limits:
                row.check(getattr(self, row.dest))
        require_range("mesh_stiffness", self.mesh_stiffness, 0.0, None, lo_open=True)
        shaft = self.output_diameter_mm / self.module_mm   # the gear's teeth beyond it
        _require_teeth("z_gear", self.z_gear, max(3, math.floor(shaft) + 1), 1000,
                       f"the gear's reference diameter beyond the {self.output_diameter_mm:g} "
                       "mm output shaft")
        _require_teeth("z_plate", self.z_plate, self.z_gear + 1, 1001,
                       f"z-plate > z-gear = {self.z_gear}")
        require_range("output_length_mm", self.output_length_mm, self.input_length_mm, None,
                      reason="the output shaft has the crank shafts' span and an overhang")
        require_range("plate_thickness_mm", self.plate_thickness_mm, 0.0,
                      self.input_length_mm - 3 * self.plate_gap_mm, lo_open=True, hi_open=True,
                      unit="mm (the plates fit between the support bearings)")
        gear_radius = 0.5 * self.module_mm * self.z_gear
        require_range("crank_radius_mm", self.crank_radius_mm,
                      gear_radius + 0.5 * self.input_diameter_mm, 1e4, lo_open=True,
                      unit="mm (the crank shafts stand outside the gear)")

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


def _require_teeth(name: str, value: object, low: int, high: int, why: str) -> None:
    """A number of teeth from ``low`` to ``high``; a refusal states the range and ``why``."""
    try:
        require_int(name, value, low, high)
    except ParameterError as exc:
        raise ParameterError(name, value, f"{exc.admissible} ({why})") from None

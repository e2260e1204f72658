"""Drive-level bearing forces of the internal-teeth planetary (three-ring) reducer.

Source: Liang Zhaolan, Wang Naixin, Wang Jing, "Theoretical analysis for the epicyclic gear drive
with internal teeth" (seed 000). Each planet ring 2 (internal teeth) translates on a circle of
radius a', drives the centre gear 1 (output) and rides on eccentric bearings A and B, 2l apart,
of two parallel crank shafts D and C.

* eq. (1): i_H1 = -z1 / (z2 - z1).
* eqs. (2)/(3): inertia force P = m a' ω_H² = π² m (z2 - z1) mass cos α / (1800 cos α') n_H².
* eqs. (4)/(5): F_A(φ), F_B(φ) on the eccentric bearings, used literally as printed. They equal
  ``|R(φ) + w e_z|``: ``R = (P_i2/2) u(φ) + (F_n/2) v(φ)`` turns rigidly with the crank, and ``v``
  lags ``u`` by 90° + α'. The vertical part is ``w_A = -(G_2/2 + F_n r_b/(2l))`` and
  ``w_B = -(G_2/2 - F_n r_b/(2l))``. The extremes are therefore ``|R| ± |w|``.
* eqs. (6)-(15): crank-shaft support reactions. They hold for three rings whose eccentrics are
  120° apart and B apart axially; the paper derives them for no other ring count.

Reproduction: the table of extremes, R_G, 3F_n r_b/(4l), R_Dmax and R_Cmax match to the printed
precision. R_MFi = 1464.1 N does not (1465.06 N with P_H = P_i2 G_H/G_2; P_H is not printed).
The printed P_i2 = 8050.2 N is not eq. (2) with m_2 = G_2/g (8220.4 N, +2.1 %); the table needs
the printed value, so it is the default.

Units: lengths in mm, forces in N, torques and couples in N·m, angles in degrees.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType

import numpy as np

from ..checks import number, require_finite, require_int, require_range
from ..errors import ParameterError
from .inputs import BEARING_INPUTS

_ROW = {row.dest: row for row in BEARING_INPUTS}

#: Load cases of the paper's table, ``case -> (gravity, inertia)``: 1 neglects gravity and
#: inertia, 2 neglects gravity, 3 includes both.
LOAD_CASES: Mapping[int, tuple[bool, bool]] = MappingProxyType(
    {1: (False, False), 2: (False, True), 3: (True, True)})


def _require_angle(name: str, value: float) -> float:
    return require_range(name, value, 0.0, 90.0, lo_open=True, hi_open=True, unit="deg")


def inertia_force(m_mm: float, z1: int, z2: int, mass_kg: float, pressure_angle_deg: float,
                  working_angle_deg: float, speed_rpm: float) -> float:
    """Centrifugal force [N] of a member on the crank circle, eq. (2)/(3): m_mass a' ω_H².

    ``m_mm`` module [mm], ``mass_kg`` mass [kg], angles [deg], ``speed_rpm`` crank speed [r/min].
    The module is converted to metres here.
    """
    m = require_range("m_mm", m_mm, 0.0, None, lo_open=True, unit="mm") * 1e-3
    mass = require_range("mass_kg", mass_kg, 0.0, None, unit="kg")
    cos_a = math.cos(math.radians(_require_angle("pressure_angle_deg", pressure_angle_deg)))
    cos_aw = math.cos(math.radians(_require_angle("working_angle_deg", working_angle_deg)))
    n_h = require_finite("speed_rpm", speed_rpm)
    dz = require_finite("z2 - z1", z2 - z1)
    return math.pi**2 * m * dz * mass * cos_a / (1800.0 * cos_aw) * n_h**2


@dataclass(frozen=True)
class RingDrive:
    """Inputs of the three-ring reducer; the defaults are the paper's worked example.

    Attributes:
        z1: teeth of the external centre gear 1 (output), >= 1.
        z2: teeth of the internal planet ring 2, > z1.
        m: module [mm].
        torque: output (load) torque T [N·m], > 0.
        rings: number of planet rings n (eccentrics per crank shaft), >= 1. It enters F_n;
            :func:`support_reactions` needs 3.
        speed: crank (input) speed n_H [r/min], >= 0.
        pressure_angle: standard pressure angle α [deg] (not printed; 20° is implied by r_b).
        working_angle: working pressure angle α' [deg] of the 1-2 mesh.
        base_radius: base radius r_b of ring 2 [mm].
        ring_weight: weight G_2 of one planet ring [N].
        inertia_force: P_i2 [N] as printed; ``None`` computes it from eq. (2) with m_2 = G_2/g.
        load_factor: F_n = load_factor T / (rings r_b); 1.2 gives the paper's 0.4 T / r_b.
        half_span: l, half the distance between the eccentric bearings A and B [mm].
        eccentric_spacing: B, axial distance between adjacent eccentrics on a shaft [mm].
        support_span: L', span of the two supports of a crank shaft [mm].
        bearing_weight: weight G_H of one eccentric bearing [N].
        bearing_inertia: P_H [N]; ``None`` uses P_i2 G_H / G_2 (the reading that reproduces
            R_MFi best; m_H is not printed).
        g: gravitational acceleration [m/s²].
    """

    z1: int = 78
    z2: int = 81
    m: float = 4.5
    torque: float = 1117.0
    rings: int = 3
    speed: float = 1500.0
    pressure_angle: float = 20.0
    working_angle: float = 35.286
    base_radius: float = 171.26
    ring_weight: float = 420.6
    inertia_force: float | None = 8050.2
    load_factor: float = 1.2
    half_span: float = 338.0
    eccentric_spacing: float = 40.0
    support_span: float = 180.0
    bearing_weight: float = 20.0
    bearing_inertia: float | None = None
    g: float = 9.81

    def __post_init__(self) -> None:
        set_ = object.__setattr__
        z1, z2 = _ROW["z1"], _ROW["z2"]
        two = number(self.z2)      # z1 below a sound z2, else below the largest z2
        sound = two is not None and z2.low <= two <= z2.high and two == int(two)
        one = require_int("z1", self.z1, int(z1.low), int(z1.high))
        if sound and two <= one:
            raise ParameterError("z2", self.z2, f"an integer {one + 1} <= z2 <= "
                                 f"{z2.high:g} (z2 > z1 = {one})",
                                 "the internal ring needs more teeth than the centre gear")
        set_(self, "z1", one)
        set_(self, "z2", require_int("z2", self.z2, one + 1, int(z2.high)))
        for row in BEARING_INPUTS[2:]:
            value = getattr(self, row.dest)
            if value is not None or row.dest != "inertia_force":   # None: from eq. (2)
                set_(self, row.dest, row.check(value))
        for name in ("bearing_inertia", "g"):
            if getattr(self, name) is not None:
                set_(self, name, require_range(name, getattr(self, name), 0.0, None,
                                               lo_open=name == "g"))

    @property
    def eccentricity(self) -> float:
        """a' = m (z2 - z1) cos α / (2 cos α') [mm], the radius of the ring centre's circle."""
        return (self.m * (self.z2 - self.z1) * math.cos(math.radians(self.pressure_angle))
                / (2.0 * math.cos(math.radians(self.working_angle))))

    @property
    def omega_H(self) -> float:
        """Crank angular speed ω_H = π n_H / 30 [rad/s]."""
        return math.pi * self.speed / 30.0

    @property
    def normal_force(self) -> float:
        """Tooth normal force on one ring F_n = load_factor T / (rings r_b) [N]."""
        return self.load_factor * self.torque * 1e3 / (self.rings * self.base_radius)

    @property
    def ratio(self) -> float:
        """Transmission ratio i_H1 = ω_H / ω_1 = -z1 / (z2 - z1), eq. (1)."""
        return -self.z1 / (self.z2 - self.z1)

    @property
    def P_i2(self) -> float:
        """Inertia force of one ring [N]: ``inertia_force``, or eq. (2) with m_2 = G_2/g."""
        if self.inertia_force is not None:
            return self.inertia_force
        return inertia_force(self.m, self.z1, self.z2, self.ring_weight / self.g,  # eq. (2)
                             self.pressure_angle, self.working_angle, self.speed)

    @property
    def P_H(self) -> float:
        """Inertia force of one eccentric bearing [N]: ``bearing_inertia`` or P_i2 G_H / G_2."""
        if self.bearing_inertia is not None:
            return self.bearing_inertia
        return self.P_i2 * self.bearing_weight / self.ring_weight


@dataclass(frozen=True)
class BearingForces:
    """Eccentric-bearing forces of one ring: ``F_A``, ``F_B`` [N] at crank angles ``phi_deg``
    [deg] (read-only 1-D arrays of equal length)."""

    phi_deg: np.ndarray
    F_A: np.ndarray
    F_B: np.ndarray


@dataclass(frozen=True)
class Extreme:
    """Minimum and maximum [N] of one bearing force and the crank angles [deg] where they occur
    (angles are NaN when the force does not depend on the crank angle)."""

    name: str
    min_N: float
    min_at_deg: float
    max_N: float
    max_at_deg: float


def _case(case: int) -> tuple[bool, bool]:
    if case not in LOAD_CASES:
        raise ParameterError("case", case, "one of 1, 2, 3 (see LOAD_CASES)")
    return LOAD_CASES[case]


def _loads(drive: RingDrive, gravity: bool, inertia: bool) -> tuple[float, float, float, float]:
    """(P_i2, G_2, F_n, F_n r_b / (2l)) in N, with the neglected loads set to zero."""
    fn = drive.normal_force
    return (drive.P_i2 if inertia else 0.0, drive.ring_weight if gravity else 0.0, fn,
            fn * drive.base_radius / (2.0 * drive.half_span))


def bearing_forces(drive: RingDrive, phi_deg, gravity: bool, inertia: bool) -> BearingForces:
    """F_A, F_B [N] of eqs. (4)/(5) at the crank angles ``phi_deg`` [deg].

    ``gravity`` includes the ring weight G_2, ``inertia`` the inertia force P_i2.
    """
    try:
        phi_deg = np.array(phi_deg, dtype=float, ndmin=1).ravel()  # a copy: frozen below
    except (TypeError, ValueError):
        raise ParameterError("phi_deg", phi_deg, "crank angles in degrees") from None
    bad = phi_deg[~np.isfinite(phi_deg)]
    if bad.size:
        raise ParameterError("phi_deg", float(bad[0]), "finite crank angles in degrees")
    p, g2, fn, t = _loads(drive, gravity, inertia)  # t = F_n r_b / (2l)
    k = drive.base_radius / drive.half_span  # r_b / l
    aw = math.radians(drive.working_angle)
    s, c = np.sin(np.radians(phi_deg)), np.cos(np.radians(phi_deg) - aw)
    common = p**2 / 4 + g2**2 / 4 - p * fn / 2 * math.sin(aw) - p * g2 / 2 * s + fn * g2 / 2 * c
    sq_a = common + g2 * t - p * t * s + fn**2 / 4 * (1 + k**2 + 2 * k * c)  # eq. (4)
    sq_b = common - g2 * t + p * t * s + fn**2 / 4 * (1 + k**2 - 2 * k * c)  # eq. (5)
    arrays = [phi_deg, np.sqrt(np.maximum(sq_a, 0.0)), np.sqrt(np.maximum(sq_b, 0.0))]
    for a in arrays:
        a.flags.writeable = False
    return BearingForces(*arrays)


def extremes(drive: RingDrive, case: int, step_deg: float = 1.0) -> tuple[Extreme, ...]:
    """Grid extremes (``F_A<case>``, ``F_B<case>``) on 0 <= φ < 360° every ``step_deg`` [deg].

    The paper's table uses a 1° grid. Ties go to the smallest angle.
    """
    step = require_range("step_deg", step_deg, 0.0, 360.0, lo_open=True, unit="deg")
    phi = step * np.arange(math.ceil(360.0 / step - 1e-9))
    forces = bearing_forces(drive, phi, *_case(case))
    out = []
    for side, f in (("A", forces.F_A), ("B", forces.F_B)):
        i, j = int(np.argmin(f)), int(np.argmax(f))
        out.append(Extreme(f"F_{side}{case}", float(f[i]), float(phi[i]),
                           float(f[j]), float(phi[j])))
    return tuple(out)


def exact_extremes(drive: RingDrive, case: int) -> tuple[Extreme, ...]:
    """Continuous extremes (``F_A<case>``, ``F_B<case>``): ``|R| ± |w|`` (module docstring).

    The maximum occurs where R points along ``w e_z``, the minimum half a turn later. The
    angles do not depend on G_2 as long as G_2/2 < F_n r_b/(2l) (true in the paper); beyond
    that, ``w_B`` changes sign and B's minimum and maximum swap places.
    """
    p, g2, fn, torque = _loads(drive, *_case(case))
    aw = math.radians(drive.working_angle)
    rx, rz = p / 2 - fn / 2 * math.sin(aw), -fn / 2 * math.cos(aw)  # R at φ = 0
    r = math.hypot(rx, rz)
    theta0 = math.degrees(math.atan2(rz, rx))
    out = []
    for side, w in (("A", -(g2 / 2 + torque)), ("B", -(g2 / 2 - torque))):
        if w == 0.0:
            at_max = at_min = math.nan
        else:
            at_max = (math.copysign(90.0, w) - theta0) % 360.0
            at_min = (at_max + 180.0) % 360.0
        out.append(Extreme(f"F_{side}{case}", abs(r - abs(w)), at_min, r + abs(w), at_max))
    return tuple(out)


@dataclass(frozen=True)
class SupportReactions:
    """Crank-shaft support reactions, eqs. (6)-(15), at each support I, I' of one shaft.

    Attributes: ``R_G`` weights; ``M_i`` [N·m] and ``R_Mi`` inertia couple; ``M_Fn`` [N·m] and
    ``R_MFn`` couple of the F_n'/2 forces; ``R_MFi`` their law-of-cosines resultant (angle
    90° + α'); ``torque_term`` = 3 F_n r_b / (4l); ``R_D_max``, ``R_C_max`` maxima at shafts D
    and C. All in N unless noted.
    """

    R_G: float
    M_i: float
    R_Mi: float
    M_Fn: float
    R_MFn: float
    R_MFi: float
    torque_term: float
    R_D_max: float
    R_C_max: float


def support_reactions(drive: RingDrive) -> SupportReactions:
    """Support reactions of eqs. (6)-(15) with ``drive.P_i2`` and ``drive.P_H``.

    Only for ``rings == 3``: the factors √3, 3/2 and 3/4 come from three eccentrics 120° apart
    at axial positions -B, 0, +B; the paper gives no other ring count.
    """
    if drive.rings != 3:
        raise ParameterError("rings", drive.rings, "rings = 3",
                             "eqs. (6)-(15) are derived for three eccentrics 120° apart")
    fn, b, span = drive.normal_force, drive.eccentric_spacing, drive.support_span
    r_g = 1.5 * (drive.ring_weight / 2 + drive.bearing_weight)
    m_i = math.sqrt(3.0) * (drive.P_i2 / 2 + drive.P_H) * b  # eqs. (6)-(8), N·mm
    m_fn = math.sqrt(3.0) / 2 * fn * b  # eq. (11), N·mm
    r_mi, r_mfn = m_i / span, m_fn / span  # eqs. (10), (13)
    gamma = math.radians(90.0 + drive.working_angle)
    r_mfi = math.sqrt(r_mi**2 + r_mfn**2 + 2 * r_mi * r_mfn * math.cos(gamma))
    torque_term = 3 * fn * drive.base_radius / (4 * drive.half_span)
    return SupportReactions(R_G=r_g, M_i=m_i * 1e-3, R_Mi=r_mi, M_Fn=m_fn * 1e-3, R_MFn=r_mfn,
                            R_MFi=r_mfi, torque_term=torque_term,
                            R_D_max=r_g + r_mfi + torque_term,  # eq. (14)
                            R_C_max=-r_g + r_mfi + torque_term)  # eq. (15)


@dataclass(frozen=True)
class PaperValues:
    """Values printed in the paper, for "paper vs ours" comparisons (N, degrees)."""

    extremes: tuple[Extreme, ...]
    P_i2: float = 8050.2
    F_n: float = 2608.9
    R_G: float = 345.0
    R_MFi: float = 1464.1
    torque_term: float = 991.42
    R_D_max: float = 2800.0
    R_C_max: float = 2110.0

#: Printed table of extremes (the first "F_max" column of the paper is really the minimum).
PAPER = PaperValues(extremes=(
    Extreme("F_A1", 643.52, 215.0, 1965.39, 35.0),
    Extreme("F_A2", 2779.55, 108.0, 4101.44, 288.0),
    Extreme("F_A3", 2569.25, 108.0, 4311.74, 288.0),
    Extreme("F_B1", 643.52, 35.0, 1965.39, 215.0),
    Extreme("F_B2", 2779.55, 288.0, 4101.44, 108.0),
    Extreme("F_B3", 2989.85, 288.0, 3891.14, 108.0),
))

"""Seed 003's three-axis internal-gear reducer: a lumped bending–torsional model of the input
shaft, the two support shafts and the output shaft, coupled by the internal-gear plates.

The mechanism (Zhang, Zhang and Li, 2007): three parallel crank shafts, 120° apart on a circle
about the output axis, each with an eccentric of eccentricity e for every plate; the plates,
rigid, ride on the eccentrics on planet bearings and so translate on a circle of radius e
without turning; each plate's internal gear meshes with the output shaft's external gear. The
input shaft drives; the two support shafts carry the plate and close the mechanism.

The model, as the seed describes it:

* each shaft is beam elements (:mod:`.beams`), 5 dofs a node (x, y, the section's rotations,
  torsion; no axial motion), on two support bearings (radial springs k_b at z = 0 and z = L
  of the crank shafts' span; the output shaft has the same span and an overhang to its output
  end, where the load holds its torsion; the input's drive end carries the motor's inertia,
  none by default: the seed gives none);
* a plate is rigid and plane: x, y and its rotation Θ;
* the vector closure at each eccentric (the seed's eqs. 1–3): the planet bearing's deflection
  is the plate's bore centre's displacement minus the eccentric centre's, which is the shaft
  node's displacement plus e θz along the crank's tangent (the eccentric turning with the
  shaft's torsion);
* the mesh (eq. 4): a spring k_m and damper c_m along the line of action, at the working
  pressure angle, through the pitch point on the side away from the plate's offset; the
  relative displacement of the gear's and the plate's points there;
* constant stiffness, the geometry frozen at one crank angle (the seed's assumption; the
  natural frequencies' spread over the crank angle is reported), no bearing damping, mesh
  damping ratio ζ.

Builds of the same total plate thickness: one plate; two of half thickness at 180°; three,
the outer quarter, the middle half at 180°. A plate of fraction f has f of the mass, inertia,
mesh stiffness and planet-bearing stiffness of the single plate (the seed keeps the total
constant). The excitation is the plates' unbalance: each plate's centre circles at radius e,
an inertia force f m_p e ω² turning with the crank (with each eccentric's own mass).

SI units inside (m, kg, N, rad, s); the inputs in the seed's units (mm, kW, r/min).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from functools import cached_property

import numpy as np

from ..errors import ParameterError
from .beams import DOF, SX, SY, TZ, Section, ShaftMaterial, X, Y, shaft_matrices
from .reducer_inputs import BUILDS, ReducerInputs

SHAFTS = ("input", "support 1", "support 2", "output")
CRANK_ANGLES = (90.0, 210.0, 330.0)  # where the crank shafts stand about the output axis (deg)
TURN_ANGLES = 6    # crank angles a turn at which the geometry's turning is looked at


@dataclass(frozen=True)
class Station:
    """Where a plate sits: thickness fraction, eccentric phase (rad), axial centre (m)."""

    fraction: float
    phase: float
    z: float


@dataclass(eq=False)
class ReducerModel:
    """The assembled model of one build at one crank angle: mass and stiffness over all dofs,
    the mesh dampers and springs, the dofs kept (the output's end torsion is held; a caller
    that holds more sets ``free`` before the first solve: the reduced matrices are kept), the
    shafts' node positions (m), the plates' stations, and the dof numbers by name."""

    inputs: ReducerInputs
    plates: int
    stations: tuple[Station, ...]
    z: tuple[np.ndarray, ...]
    M: np.ndarray
    K: np.ndarray
    free: np.ndarray
    dampers: list = field(default_factory=list)   # the mesh dampers: (g over all dofs, c),
                                                  # each the term c g gᵀ of the damping
    meshes: list = field(default_factory=list)    # the mesh springs, a plate each: (g, k),
                                                  # δ = g · x along the line of action

    def dof(self, shaft: int, node: int, comp: int) -> int:
        """Global dof of ``comp`` (:data:`~.beams.X` …) at ``node`` of shaft ``shaft``."""
        return int(self._offsets[shaft] + node * DOF + comp)

    def plate_dof(self, plate: int, comp: int) -> int:
        """Global dof of plate ``plate``: 0 x, 1 y, 2 Θ."""
        return int(self._offsets[-1] + 3 * plate + comp)

    @property
    def C(self) -> np.ndarray:
        """The damping matrix over all dofs: the mesh dampers' Σ c g gᵀ."""
        C = np.zeros_like(self.K)
        for g, c in self.dampers:
            C += c * np.outer(g, g)
        return C

    @cached_property
    def reduced(self) -> tuple[np.ndarray, np.ndarray]:
        """K and M on the kept dofs."""
        ix = np.ix_(self.free, self.free)
        return self.K[ix], self.M[ix]

    @cached_property
    def damper_basis(self) -> tuple[np.ndarray, np.ndarray]:
        """The dampers with c > 0 on the kept dofs: directions (kept dofs, dampers) and c."""
        live = [(g, c) for g, c in self.dampers if c > 0]
        return (np.column_stack([g[self.free] for g, _ in live]) if live
                else np.zeros((len(self.free), 0)), np.array([c for _, c in live]))

    @cached_property
    def modal(self) -> tuple[np.ndarray, np.ndarray]:
        """All undamped eigenpairs (ω², mass-normalised shapes on the kept dofs)."""
        from scipy.linalg import eigh

        K, M = self.reduced
        return eigh(K, M)

    @cached_property
    def whirl_modes(self) -> tuple[np.ndarray, ...]:
        """For :func:`whirl`: the kept lateral dofs (positions in ``free``), the rest, the
        eigenpairs (λ, Φ) of the stiffness with the rest condensed out against the lateral
        mass, and the rest's static answer to the lateral dofs."""
        from scipy.linalg import eigh

        K, M = self.reduced
        lat = np.isin(self.free, lateral(self))
        a, b = np.flatnonzero(lat), np.flatnonzero(~lat)
        back = -np.linalg.solve(K[np.ix_(b, b)], K[np.ix_(b, a)])
        lam, phi = eigh(K[np.ix_(a, a)] + K[np.ix_(a, b)] @ back, M[np.ix_(a, a)])
        return a, b, lam, phi, back

    def node(self, shaft: int, z: float) -> int:
        return int(np.argmin(np.abs(self.z[shaft] - z)))

    @cached_property
    def _offsets(self) -> np.ndarray:
        return np.cumsum([0] + [len(z) * DOF for z in self.z])

    @property
    def ndofs(self) -> int:
        return len(self.M)


def stations(inputs: ReducerInputs, plates: int) -> tuple[Station, ...]:
    """The build's plates centred on the crank shafts' span, ``plate_gap_mm`` apart."""
    build = BUILDS[plates]
    t, gap = 1e-3 * inputs.plate_thickness_mm, 1e-3 * inputs.plate_gap_mm
    widths = [f * t for f, _ in build]
    stack = sum(widths) + gap * (len(build) - 1)
    z0 = 0.5e-3 * inputs.input_length_mm - 0.5 * stack
    out = []
    for (f, phase), w in zip(build, widths):
        out.append(Station(f, phase, z0 + 0.5 * w))
        z0 += w + gap
    return tuple(out)


def _nodes(length: float, span: float, elements: int, marks) -> np.ndarray:
    """Nodes every span/elements or closer, through ``marks``."""
    step = span / elements
    base = np.linspace(0.0, length, max(2, round(length / step)) + 1)
    z = np.unique(np.concatenate([base, marks]))
    keep = np.concatenate([[True], np.diff(z) > 1e-3 * step])
    z = z[keep]
    for m in marks:   # a mark merged with a grid point: the grid point moves onto it
        z[np.argmin(np.abs(z - m))] = m
    return z


def build_reducer(inputs: ReducerInputs, plates: int,
                  mesh_stiffness: float | None = None) -> ReducerModel:
    """Assemble the build with ``plates`` (1, 2 or 3) at ``inputs.crank_angle_deg``;
    ``mesh_stiffness`` (N/m, a single plate's) replaces the input's."""
    if plates not in BUILDS:
        raise ParameterError("plates", plates, "1, 2 or 3")
    ip = inputs
    km = ip.mesh_stiffness if mesh_stiffness is None else mesh_stiffness
    steel = ShaftMaterial()
    span, length_out = 1e-3 * ip.input_length_mm, 1e-3 * ip.output_length_mm
    st = stations(ip, plates)
    marks = [s.z for s in st]
    crank_z = _nodes(span, span, ip.elements, [0.0, span, *marks])
    out_z = _nodes(length_out, span, ip.elements, [0.0, span, length_out, *marks])
    zs = (crank_z, crank_z, crank_z, out_z)
    sections = (Section(1e-3 * ip.input_diameter_mm, steel),) * 3 + (
        Section(1e-3 * ip.output_diameter_mm, steel),)
    n = sum(len(z) for z in zs) * DOF + 3 * plates
    M, K = np.zeros((n, n)), np.zeros((n, n))
    model = ReducerModel(ip, plates, st, zs, M, K, np.arange(n))
    for j, (sec, z) in enumerate(zip(sections, zs)):
        k, m = shaft_matrices(sec, z)
        sl = slice(model.dof(j, 0, 0), model.dof(j, 0, 0) + len(z) * DOF)
        K[sl, sl] += k
        M[sl, sl] += m
    kb, e = ip.bearing_stiffness, 1e-3 * ip.eccentricity_mm
    for j in range(4):   # support bearings at both ends of the span
        for zb in (0.0, span):
            node = model.node(j, zb)
            for c in (X, Y):
                _spring(K, {model.dof(j, node, c): 1.0}, kb)
    rw1, rw2 = ip.working_pitch_radii
    alpha = math.radians(ip.mesh_angle_deg)
    gear = _gear_disk(ip, sections[3])
    m_eq = 1.0 / (1.0 / ip.plate_mass + ip.base_radius ** 2 / (
        gear[1] + steel.rho * sections[3].J * length_out))
    cm = 2.0 * ip.mesh_damping * math.sqrt(km * m_eq)
    cranks = [1e-3 * ip.crank_radius_mm * np.array([math.cos(math.radians(a)),
                                                      math.sin(math.radians(a))])
              for a in CRANK_ANGLES]
    phi0 = math.radians(ip.crank_angle_deg)
    for i, s in enumerate(st):
        u, t = _directions(phi0 + s.phase)
        px, py, pr = (model.plate_dof(i, c) for c in range(3))
        M[px, px] += s.fraction * ip.plate_mass
        M[py, py] += s.fraction * ip.plate_mass
        M[pr, pr] += s.fraction * ip.plate_inertia
        for j, c in enumerate(cranks):   # planet bearings: the vector closure at each eccentric
            node = model.node(j, s.z)
            ux, uy, tz = (model.dof(j, node, q) for q in (X, Y, TZ))
            M[ux, ux] += s.fraction * ip.eccentric_mass
            M[uy, uy] += s.fraction * ip.eccentric_mass
            M[tz, tz] += s.fraction * ip.eccentric_mass * e ** 2
            _spring(K, {px: 1.0, pr: -c[1], ux: -1.0, tz: -e * t[0]}, s.fraction * kb)
            _spring(K, {py: 1.0, pr: c[0], uy: -1.0, tz: -e * t[1]}, s.fraction * kb)
        node = model.node(3, s.z)   # the output gear's share of the disk
        ux, uy, sx, sy, tz = (model.dof(3, node, q) for q in (X, Y, SX, SY, TZ))
        mass, polar, diametral = (s.fraction * v for v in gear)
        for d, v in ((ux, mass), (uy, mass), (sx, diametral), (sy, diametral), (tz, polar)):
            M[d, d] += v
        # the mesh: pitch point P away from the plate's offset, line of action n
        p = -rw1 * u
        q = -rw2 * u       # P from the plate's centre
        nrm = math.cos(alpha) * t + math.sin(alpha) * u
        g = {ux: nrm[0], uy: nrm[1], tz: -nrm[0] * p[1] + nrm[1] * p[0],
             px: -nrm[0], py: -nrm[1], pr: nrm[0] * q[1] - nrm[1] * q[0]}
        _spring(K, g, s.fraction * km)
        direction = np.zeros(n)
        direction[list(g)] = list(g.values())
        model.dampers.append((direction, s.fraction * cm))
        model.meshes.append((direction, s.fraction * km))
    M[model.dof(0, 0, TZ), model.dof(0, 0, TZ)] += ip.motor_inertia   # at the drive end
    held = model.dof(3, len(out_z) - 1, TZ)   # the load holds the output end's torsion
    model.free = np.setdiff1d(np.arange(n), [held])
    return model


def _directions(phi: float) -> tuple[np.ndarray, np.ndarray]:
    """The crank's direction u and its tangent t at crank angle φ."""
    return (np.array([math.cos(phi), math.sin(phi)]),
            np.array([-math.sin(phi), math.cos(phi)]))


def _gear_disk(ip: ReducerInputs, shaft: Section) -> tuple[float, float, float]:
    """The output gear, a steel disk from the shaft to the reference radius, the plates'
    thickness wide: mass (kg), polar and diametral inertia (kg·m²)."""
    r1, r0 = 0.5e-3 * ip.module_mm * ip.z_gear, 0.5 * shaft.d
    b = 1e-3 * ip.plate_thickness_mm
    mass = shaft.material.rho * math.pi * (r1 ** 2 - r0 ** 2) * b
    polar = 0.5 * mass * (r1 ** 2 + r0 ** 2)
    return mass, polar, 0.5 * polar + mass * b ** 2 / 12.0


def _spring(K: np.ndarray, g: dict[int, float], k: float) -> None:
    """K += k g gᵀ for the scalar deflection δ = Σ g_d u_d."""
    idx = np.fromiter(g, int)
    v = np.fromiter(g.values(), float)
    K[np.ix_(idx, idx)] += k * np.outer(v, v)


# --- natural frequencies and modes -----------------------------------------------------------

@dataclass(frozen=True)
class Mode:
    """A natural frequency (rad/s), its shape over all dofs (mass-normalised; the held dof
    0) and its kind: the kinetic-energy shares of each part ("input bending", "plate 2
    translation", …), largest first."""

    omega: float
    shape: np.ndarray
    shares: tuple[tuple[str, float], ...]

    @property
    def hz(self) -> float:
        return self.omega / (2.0 * math.pi)

    @property
    def kind(self) -> str:
        """The parts holding 20 % of the kinetic energy or more, with their shares."""
        big = [(name, s) for name, s in self.shares if s >= 0.2] or [self.shares[0]]
        return ", ".join(f"{name} {100 * s:.0f} %" for name, s in big)


def modes(model: ReducerModel, count: int = 10) -> tuple[Mode, ...]:
    """The first ``count`` undamped natural frequencies and modes."""
    f = model.free
    count = min(count, len(f))
    w2, v = model.modal
    out = []
    parts = _parts(model)
    for k in range(count):
        shape = np.zeros(model.ndofs)
        shape[f] = v[:, k]
        energy = shape * (model.M @ shape)
        total = energy.sum()
        shares = sorted(((name, float(energy[idx].sum() / total)) for name, idx in parts),
                        key=lambda x: -x[1])
        out.append(Mode(math.sqrt(max(w2[k], 0.0)), shape, tuple(shares)))
    return tuple(out)


def _parts(model: ReducerModel) -> list[tuple[str, np.ndarray]]:
    """Dof groups a mode's kinetic energy is split over."""
    parts = []
    for j, name in enumerate(SHAFTS):
        base = model.dof(j, 0, 0)
        nodes = base + DOF * np.arange(len(model.z[j]))
        bend = np.concatenate([nodes + c for c in (X, Y, SX, SY)])
        parts += [(f"{name} bending", bend), (f"{name} torsion", nodes + TZ)]
    for i in range(model.plates):
        label = "plate" if model.plates == 1 else f"plate {i + 1}"
        parts += [(f"{label} translation", np.array([model.plate_dof(i, 0),
                                                     model.plate_dof(i, 1)])),
                  (f"{label} rotation", np.array([model.plate_dof(i, 2)]))]
    return parts


def over_turn(inputs: ReducerInputs, plates: int, angles: int = TURN_ANGLES,
              mesh_stiffness: float | None = None) -> tuple[ReducerModel, ...]:
    """The build at ``angles`` crank angles evenly over one turn: the model freezes the
    geometry at one, and these say how much that matters."""
    return tuple(build_reducer(replace(inputs, crank_angle_deg=float(a)), plates,
                               mesh_stiffness)
                 for a in np.arange(angles) * 360.0 / angles)


def frequency_spread(models, count: int = 10) -> np.ndarray:
    """Natural frequencies (rad/s) of each of ``models`` (:func:`over_turn`): (models,
    count)."""
    return np.array([[m.omega for m in modes(model, count)] for model in models])


# --- unbalance response ----------------------------------------------------------------------

#: what the seed's Figs. 2–6 plot: x amplitude of the input and output shafts' support
#: journals and of the input's planet-bearing journal (the middle plate of three), and the
#: twist of the input and output shafts
RESPONSES = {"input_support_um": "input shaft, support bearing journal, x (Fig. 2)",
             "output_support_um": "output shaft, support bearing journal, x (Fig. 3)",
             "input_planet_um": "input shaft, planet bearing journal, x (Fig. 4)",
             "input_twist_urad": "input shaft torsion (Fig. 5)",
             "output_twist_urad": "output shaft torsion (Fig. 6)"}


def unbalance_forces(model: ReducerModel, omega: float) -> np.ndarray:
    """Complex amplitudes of the plates' and eccentrics' inertia forces at crank speed ω
    (rad/s): f m e ω² turning with each plate's crank, x = F cos(ωt + φ), y = F sin(ωt + φ)."""
    ip = model.inputs
    e = 1e-3 * ip.eccentricity_mm
    F = np.zeros(model.ndofs, complex)
    phi0 = math.radians(ip.crank_angle_deg)
    for i, s in enumerate(model.stations):
        turn = np.exp(1j * (phi0 + s.phase)) * e * omega ** 2 * s.fraction
        F[model.plate_dof(i, 0)] += ip.plate_mass * turn
        F[model.plate_dof(i, 1)] += -1j * ip.plate_mass * turn
        for j in range(3):
            node = model.node(j, s.z)
            F[model.dof(j, node, X)] += ip.eccentric_mass * turn
            F[model.dof(j, node, Y)] += -1j * ip.eccentric_mass * turn
    return F


def response(model: ReducerModel, omega: float) -> np.ndarray:
    """Complex displacement amplitudes under the unbalance at crank speed ω (rad/s)."""
    w2, phi = model.modal
    force = unbalance_forces(model, omega)[model.free]

    def undamped(v: np.ndarray) -> np.ndarray:   # (K − ω² M)⁻¹ v, modally
        gain = 1.0 / (w2 - omega ** 2)
        return phi @ ((phi.T @ v) * (gain if v.ndim == 1 else gain[:, None]))

    xf = undamped(force)
    G, c = model.damper_basis
    if len(c):   # the mesh dampers are a few rank-one terms: Sherman–Morrison–Woodbury
        Y = undamped(G)
        S = np.diag(1.0 / (1j * omega * c)) + G.T @ Y
        xf = xf - Y @ np.linalg.solve(S, G.T @ xf)
    x = np.zeros(model.ndofs, complex)
    x[model.free] = xf
    return x


def measures(model: ReducerModel, x: np.ndarray) -> dict[str, float]:
    """The seed's five amplitudes (:data:`RESPONSES`) of a response ``x``: µm and µrad. A
    support journal's is the larger of its two bearings'; the twist is between the plate
    stations and the shaft's drive end (input) or held end (output), the largest."""
    span = 1e-3 * model.inputs.input_length_mm
    ends = [model.node(0, 0.0), model.node(0, span)]
    out_ends = [model.node(3, 0.0), model.node(3, span)]
    middle = model.stations[len(model.stations) // 2]
    return {
        "input_support_um": 1e6 * max(abs(x[model.dof(0, k, X)]) for k in ends),
        "output_support_um": 1e6 * max(abs(x[model.dof(3, k, X)]) for k in out_ends),
        "input_planet_um": 1e6 * abs(x[model.dof(0, model.node(0, middle.z), X)]),
        "input_twist_urad": 1e6 * np.abs(_twists(model, x, 0)).max(),
        "output_twist_urad": 1e6 * np.abs(_twists(model, x, 3)).max(),
    }


def _twists(model: ReducerModel, x: np.ndarray, shaft: int) -> np.ndarray:
    """Shaft 0's (input) or 3's (output) twist at each plate station (rad) in ``x``: from its
    drive end, or from its held output end."""
    end = model.dof(shaft, 0 if shaft == 0 else len(model.z[shaft]) - 1, TZ)
    return np.array([x[model.dof(shaft, model.node(shaft, s.z), TZ)] - x[end]
                     for s in model.stations])


def sweep(model: ReducerModel, speeds_rpm) -> dict[str, np.ndarray]:
    """The seed's five amplitudes of its frozen model (:func:`response`) at each crank speed
    (r/min)."""
    rows = [measures(model, response(model, n * math.pi / 30.0)) for n in speeds_rpm]
    return {k: np.array([r[k] for r in rows]) for k in RESPONSES}


def turning_sweep(models, speeds_rpm) -> dict[str, np.ndarray]:
    """The turning mechanism's amplitudes (:func:`whirl`) at each crank speed (r/min), the
    largest over ``models`` (:func:`over_turn`: the whirl is not quite the same at each
    crank angle, since the three cranks stand still while the mesh turns)."""
    best = {k: np.zeros(len(speeds_rpm)) for k in RESPONSES}
    for model in models:
        for i, n in enumerate(speeds_rpm):
            for k, v in whirl_measures(model, whirl(model, n * math.pi / 30.0)).items():
                best[k][i] = max(best[k][i], v)
    return best


def lateral(model: ReducerModel) -> np.ndarray:
    """The lateral dofs: the shafts' x, y and slopes, the plates' x and y."""
    out = []
    for j in range(4):
        nodes = model.dof(j, 0, 0) + DOF * np.arange(len(model.z[j]))
        out += [nodes + c for c in (X, Y, SX, SY)]
    out += [np.array([model.plate_dof(i, 0), model.plate_dof(i, 1)])
            for i in range(model.plates)]
    return np.sort(np.concatenate(out))


def whirl(model: ReducerModel, omega: float) -> np.ndarray:
    """The turning mechanism's steady response to its unbalance at crank speed ω (rad/s),
    in the frame turning with the cranks, where the plates' inertia force, the eccentrics and
    the mesh stand still: every lateral dof whirls forward at ω on a circle (its inertia
    −ω² M), every torsion and the plates' rotation stay constant (no inertia, no damping:
    nothing across the mesh moves). Exact where the model is the same at every crank angle
    (three identical cranks 120° apart, isotropic bearings: its natural frequencies do not
    move with the crank angle); the shafts' gyroscopic terms are left out as everywhere.
    Returns the positions at the model's crank angle, real."""
    a, b, lam, phi, back = model.whirl_modes
    force = unbalance_forces(model, omega).real[model.free]   # on lateral dofs only
    xa = phi @ ((phi.T @ force[a]) / (lam - omega ** 2))
    xf = np.zeros(len(model.free))
    xf[a] = xa
    xf[b] = back @ xa
    x = np.zeros(model.ndofs)
    x[model.free] = xf
    return x


def whirl_measures(model: ReducerModel, x: np.ndarray) -> dict[str, float]:
    """:func:`measures` of a whirl: a journal's x amplitude is its circle's radius; the
    twists do not vibrate (0)."""
    span = 1e-3 * model.inputs.input_length_mm
    middle = model.stations[len(model.stations) // 2]

    def radius(j: int, z: float) -> float:
        k = model.node(j, z)
        return float(np.hypot(x[model.dof(j, k, X)], x[model.dof(j, k, Y)]))

    return {"input_support_um": 1e6 * max(radius(0, 0.0), radius(0, span)),
            "output_support_um": 1e6 * max(radius(3, 0.0), radius(3, span)),
            "input_planet_um": 1e6 * radius(0, middle.z),
            "input_twist_urad": 0.0, "output_twist_urad": 0.0}


# --- the unbalance's balance, by hand --------------------------------------------------------

def unbalance_resultants(inputs: ReducerInputs, plates: int) -> tuple[float, float]:
    """The resultant inertia force (N) and couple about the span's middle (N·m) of the
    build's plates and eccentrics at the working speed: what the support bearings must
    carry if the shafts were rigid (by hand: the fractions, phases and stations)."""
    e, w = 1e-3 * inputs.eccentricity_mm, inputs.omega
    mass = inputs.plate_mass + 3 * inputs.eccentric_mass
    mid = 0.5e-3 * inputs.input_length_mm
    force = sum(s.fraction * mass * e * w ** 2 * np.exp(1j * s.phase)
                for s in stations(inputs, plates))
    couple = sum(s.fraction * mass * e * w ** 2 * np.exp(1j * s.phase) * (s.z - mid)
                 for s in stations(inputs, plates))
    return float(abs(force)), float(abs(couple))


def support_reactions(model: ReducerModel, force: np.ndarray) -> tuple[complex, complex,
                                                                     complex, complex]:
    """The support bearings' total force on the shafts in x and y (N) and its couple about
    the span's middle (N·m, of the x and the y forces) under the static load ``force``
    (complex amplitudes allowed): equilibrium says they are minus the load's resultant and
    couple, the held output end carrying torque only."""
    x = _static(model, force)
    span = 1e-3 * model.inputs.input_length_mm
    out = [0.0, 0.0, 0.0, 0.0]
    for j in range(4):
        for zb in (0.0, span):
            node = model.node(j, zb)
            for c, (f_at, m_at) in ((X, (0, 2)), (Y, (1, 3))):
                f = -model.inputs.bearing_stiffness * x[model.dof(j, node, c)]
                out[f_at] += f
                out[m_at] += f * (zb - 0.5 * span)
    return tuple(out)


def turning_geometry(models, omega: float) -> dict[str, np.ndarray]:
    """What the frozen geometry leaves out, quasi-statically: over one crank turn, each of
    ``models`` (:func:`over_turn`) under the inertia forces of crank speed ω (rad/s) at its
    crank angle, without dynamic amplification, real: how far the input's support journal
    is pushed (µm; the push turns with the crank) and the output's twist (µrad, signed).
    The twist's part that varies over the turn is what the turning mechanism excites at 1×
    (and its harmonics); :func:`frozen_quasi_static` is what the frozen model says it is."""
    out: dict[str, list[float]] = {"crank_angle_deg": [], "input_support_um": [],
                                   "output_twist_urad": []}
    for model in models:
        x = _static(model, unbalance_forces(model, omega).real)
        twists = _twists(model, x, 3)
        out["crank_angle_deg"].append(model.inputs.crank_angle_deg)
        out["input_support_um"].append(1e6 * math.hypot(x[model.dof(0, 0, X)],
                                                        x[model.dof(0, 0, Y)]))
        out["output_twist_urad"].append(1e6 * twists[np.argmax(np.abs(twists))])
    return {k: np.array(v) for k, v in out.items()}


def frozen_quasi_static(model: ReducerModel) -> dict[str, float]:
    """The frozen ``model``'s 1× amplitudes of the same two quantities, quasi-statically (the
    working speed's forces on the stiffness alone)."""
    x = _static(model, unbalance_forces(model, model.inputs.omega))
    return {"input_support_um": 1e6 * abs(x[model.dof(0, 0, X)]),
            "output_twist_urad": 1e6 * np.abs(_twists(model, x, 3)).max()}


def _static(model: ReducerModel, force: np.ndarray) -> np.ndarray:
    x = np.zeros(model.ndofs, force.dtype)
    x[model.free] = np.linalg.solve(model.reduced[0], force[model.free])
    return x

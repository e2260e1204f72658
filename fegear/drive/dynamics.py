"""A torsional lumped-parameter model of the tooth pair, driven by the FE mesh stiffness.

The FE mesh cycle (``fegear solve --positions N``, :class:`~fegear.toothpair.MeshStiffness`)
gives, at each mesh phase, gear 1's static rotation under the torque T with gear 2 held: the
unloaded part e (rotation to first touch: the kinematic transmission error) and the elastic part
T/k_s. ``k_s`` is the secant mesh stiffness in N·m/rad of gear-1 rotation: with it the model
reproduces the FE rotation exactly when static. The spring of the vibration about that static
state is the tangent stiffness k_t = dT/dθ (the contact set kept), larger than the secant where
the contact grows with the load; ``spring="secant"`` uses k_s for both (the model before the
tangent was known). The teeth are not involutes, so no base-circle line of action exists: the
model works in gear-1 rotation, which needs none.

Model (two inertias on fixed axes, the spirit of seed 003; both gears of an internal pair turn
the same way): with ``q = θ1 − i θ2``, ``i = z2/z1``, the mesh torque on gear 1 is
``F = T1 + k_t(φ)(q − q_s(φ)) + c q'`` about the static state ``q_s = e(φ) + T1/k_s(φ)`` (φ the
mesh phase, advancing z1 per gear-1 turn; with k_t = k_s, ``F = k_s(q − e) + c q'``), so

    J1 θ1'' + F = T1,    J2 θ2'' − i F = −T_L,    T_L = i T1 (steady load),

and q obeys ``J_e q'' + c q' + k_t(φ)(q − q_s(φ)) = 0`` with ``1/J_e = 1/J1 + i²/J2``. Natural
frequency ``ω_n = sqrt(k̄/J_e)``, k̄ the spring's mean (the other mode is the rigid rotation),
damping ``c = 2 ζ sqrt(k̄ J_e)``. The steady response to the stiffness and error variation at
constant speed is the periodic solution over one mesh period, found by shooting (Floquet): the
monodromy matrix also says whether the response is stable (parametric resonance).

Units: kg·m², N·m, rad, s.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..checks import require_range
from ..errors import ParameterError
from ..toothpair import MeshStiffness
from .inputs import DYNAMICS_INPUTS

_ROW = {row.dest: row for row in DYNAMICS_INPUTS}

STEEL_DENSITY = 7850.0  # kg/m³, for the default inertias


def default_inertias(mesh: MeshStiffness) -> tuple[float, float]:
    """J1, J2 (kg·m²) if nothing better is known: gear 1 a steel disk of its pitch radius,
    gear 2 a steel ring from its pitch radius out by 3 m (the FE model's rim), both of the
    face width."""
    r1 = 0.5e-3 * mesh.module * mesh.z1
    r2 = 0.5e-3 * mesh.module * mesh.z2
    r3 = r2 + 3e-3 * mesh.module
    b = 1e-3 * mesh.thickness
    return (0.5 * math.pi * STEEL_DENSITY * b * r1 ** 4,
            0.5 * math.pi * STEEL_DENSITY * b * (r3 ** 4 - r2 ** 4))


@dataclass(frozen=True)
class TorsionalPair:
    """Two inertias J1, J2 (kg·m²) coupled by the mesh: ratio i = z2/z1 (q = θ1 − i θ2),
    mean mesh stiffness k (N·m/rad of gear-1 rotation) and mesh damping ratio ζ."""

    J1: float
    J2: float
    ratio: float
    stiffness: float
    zeta: float = 0.05

    def __post_init__(self) -> None:
        for name in ("J1", "J2", "zeta"):   # each given: their defaults are the command's
            row = _ROW[name]
            if getattr(self, name) is None:
                raise ParameterError(name, None, row.range_text)
            row.check(getattr(self, name))
        for name in ("ratio", "stiffness"):
            require_range(name, getattr(self, name), 0.0, None, lo_open=True)

    @property
    def equivalent_inertia(self) -> float:
        """J_e = 1/(1/J1 + i²/J2) (kg·m²)."""
        return 1.0 / (1.0 / self.J1 + self.ratio ** 2 / self.J2)

    @property
    def natural_frequency(self) -> float:
        """Closed form ω_n = sqrt(k (1/J1 + i²/J2)) (rad/s)."""
        return math.sqrt(self.stiffness / self.equivalent_inertia)

    @property
    def damping(self) -> float:
        """c = 2 ζ sqrt(k J_e) (N·m·s/rad)."""
        return 2.0 * self.zeta * math.sqrt(self.stiffness * self.equivalent_inertia)

    def matrices(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """M, C, K of (θ1, θ2) at the mean stiffness."""
        g = np.array([1.0, -self.ratio])  # q = g·θ
        return (np.diag([self.J1, self.J2]), self.damping * np.outer(g, g),
                self.stiffness * np.outer(g, g))

    def modes(self) -> tuple[np.ndarray, np.ndarray]:
        """Undamped natural frequencies (rad/s, ascending; the first is the rigid rotation, 0)
        and mode shapes (columns) from the 2×2 eigenproblem K φ = ω² M φ."""
        from scipy.linalg import eigh

        m, _, k = self.matrices()
        w2, v = eigh(k, m)
        return np.sqrt(np.clip(w2, 0.0, None)), v


@dataclass(frozen=True)
class Response:
    """Steady periodic response at one speed: gear-1 speed (rad/s), mesh frequency (rad/s),
    time over one mesh period (s), q (rad), mesh torque F (N·m), the dynamic factor
    max F / T1 and min F / T1 (below 0 the teeth would separate: the linear model no longer
    holds), the dynamic part of q peak to peak (rad) and the Floquet multipliers' largest
    modulus (< 1: stable)."""

    speed: float
    mesh_frequency: float
    t: np.ndarray
    q: np.ndarray
    force: np.ndarray
    dynamic_factor: float
    min_factor: float
    q_peak_to_peak: float
    multiplier: float


def steady_response(pair: TorsionalPair, mesh: MeshStiffness, torque: float, speed_rpm: float,
                    steps: int = 4096, spring: str = "secant") -> Response:
    """The periodic solution of ``J_e q'' + c q' + k_t(φ)(q − q_s(φ)) = 0`` at gear-1 speed
    ``speed_rpm``, ``spring`` "tangent" (k_t the mesh's tangent stiffness) or "secant" (k_t =
    k_s). ``pair.stiffness`` sets the spring's mean; the secant is scaled alike. One mesh
    period is cut into ``steps`` intervals with k and e frozen at the interval's midpoint; on
    each the state x = (q, q') relaxes exactly towards that interval's static state
    x* = (e + T1/k_s, 0): ``x ← E x + (I − E) x*``, ``E = exp(A h)``. The product of
    the E is the monodromy matrix Φ (its eigenvalues: the Floquet multipliers), and the
    periodic start solves ``(I − Φ) x0 = p``. No time-step limit: the natural period may be
    any fraction of the mesh period."""
    from scipy.linalg import expm

    torque = require_range("torque", torque, 0.0, None, lo_open=True, unit="N·m")
    speed_rpm = require_range("speed", speed_rpm, 0.0, None, lo_open=True, unit="r/min")
    steps = int(require_range("steps", steps, 8, 1e7))
    omega1 = speed_rpm * math.pi / 30.0
    wm = mesh.z1 * omega1  # the mesh phase advances z1 per gear-1 turn
    period = 2.0 * math.pi / wm
    h = period / steps
    je, c = pair.equivalent_inertia, pair.damping
    dyn = mesh.kind(spring)
    level = pair.stiffness / dyn.mean  # the pair's stiffness level, the mesh's shape
    mid = (np.arange(steps) + 0.5) / steps
    ks, e = mesh.at(mid)
    k = dyn.at(mid)[0] * level
    ks = ks * level
    a = np.zeros((steps, 2, 2))
    a[:, 0, 1] = 1.0
    a[:, 1, 0] = -k / je
    a[:, 1, 1] = -c / je
    big = expm(a * h)
    star = np.zeros((steps, 2))
    star[:, 0] = e + torque / ks  # static state (q, 0) of each interval
    phi, p = np.eye(2), np.zeros(2)
    for j in range(steps):  # x_{j+1} = E_j (x_j − x*_j) + x*_j
        phi = big[j] @ phi
        p = big[j] @ (p - star[j]) + star[j]
    x = np.linalg.solve(np.eye(2) - phi, p)
    q, v = np.empty(steps + 1), np.empty(steps + 1)
    q[0], v[0] = x
    for j in range(steps):
        x = big[j] @ (x - star[j]) + star[j]
        q[j + 1], v[j + 1] = x
    t = np.linspace(0.0, period, steps + 1)
    kks, ee = mesh.at(t / period)
    kk = dyn.at(t / period)[0] * level
    static = ee + torque / (kks * level)
    force = torque + kk * (q - static) + c * v
    return Response(omega1, wm, t, q, force, float(force.max() / torque),
                    float(force.min() / torque), float(np.ptp(q - static)),
                    float(np.abs(np.linalg.eigvals(phi)).max()))

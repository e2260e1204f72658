"""Shaft elements of the reducer model (:mod:`.reducer`), checked against closed forms in the
tests (tests/drive/test_reducer.py).

A shaft node has 5 degrees of freedom, seed 003's (no axial motion): the lateral displacements
x, y, the section's rotations in the xz and yz planes (the slopes dx/dz, dy/dz where shear is
left out), and the torsion angle θz. The bending element is Timoshenko's (shear flexibility
through Φ = 12 EI / (κ G A L²); translational and rotary inertia, consistent with it), the
same in both planes; the torsion element is linear. No gyroscopic
terms: the shafts turn at 1500 r/min and carry no large disk (docs/drive.md says what that
leaves out). SI units: m, kg, N, rad, s.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

DOF = 5                      # x, y, the two section rotations, θz per node
X, Y, SX, SY, TZ = range(DOF)


@dataclass(frozen=True)
class ShaftMaterial:
    """A shaft's material: Young's modulus E (Pa), Poisson ratio ν, density ρ (kg/m³)."""

    E: float = 2.06e11
    nu: float = 0.3
    rho: float = 7850.0

    @property
    def G(self) -> float:
        return self.E / (2.0 * (1.0 + self.nu))


STEEL = ShaftMaterial()


@dataclass(frozen=True)
class Section:
    """A solid round shaft of diameter d (m): area, second moment, polar moment and the shear
    factor κ of a solid circle (6(1 + ν)/(7 + 6ν), Cowper's)."""

    d: float
    material: ShaftMaterial = STEEL

    @property
    def A(self) -> float:
        return math.pi * self.d ** 2 / 4.0

    @property
    def I(self) -> float:  # noqa: E743 (the second moment's name)
        return math.pi * self.d ** 4 / 64.0

    @property
    def J(self) -> float:
        return 2.0 * self.I

    @property
    def kappa(self) -> float:
        nu = self.material.nu
        return 6.0 * (1.0 + nu) / (7.0 + 6.0 * nu)


def bending_element(s: Section, L: float, shear: bool = True,
                    rotary: bool = True) -> tuple[np.ndarray, np.ndarray]:
    """Stiffness and mass of one plane's bending element of length ``L``, dofs (w1, θ1, w2,
    θ2), θ the section's rotation (the slope where shear is left out): Timoshenko's stiffness
    with Φ = 12 EI/(κ G A L²) (Φ = 0 without ``shear``: Euler–Bernoulli), the consistent
    translational mass and, with ``rotary``, the rotary inertia ρ I, both of the
    interdependent interpolation that goes with that stiffness."""
    m = s.material
    EI = m.E * s.I
    phi = 12.0 * EI / (s.kappa * m.G * s.A * L ** 2) if shear else 0.0
    k = EI / ((1.0 + phi) * L ** 3) * np.array([
        [12.0, 6 * L, -12.0, 6 * L],
        [6 * L, (4 + phi) * L ** 2, -6 * L, (2 - phi) * L ** 2],
        [-12.0, -6 * L, 12.0, -6 * L],
        [6 * L, (2 - phi) * L ** 2, -6 * L, (4 + phi) * L ** 2]])
    # the interdependent interpolation's consistent mass (Friedman and Kosmatka, 1993):
    # Euler–Bernoulli's at Φ = 0
    a, b, c = 1.0 + phi, phi, phi * phi
    t = m.rho * s.A * L / a ** 2 * np.array([
        [13 / 35 + 7 * b / 10 + c / 3, (11 / 210 + 11 * b / 120 + c / 24) * L,
         9 / 70 + 3 * b / 10 + c / 6, -(13 / 420 + 3 * b / 40 + c / 24) * L],
        [0.0, (1 / 105 + b / 60 + c / 120) * L ** 2, (13 / 420 + 3 * b / 40 + c / 24) * L,
         -(1 / 140 + b / 60 + c / 120) * L ** 2],
        [0.0, 0.0, 13 / 35 + 7 * b / 10 + c / 3, -(11 / 210 + 11 * b / 120 + c / 24) * L],
        [0.0, 0.0, 0.0, (1 / 105 + b / 60 + c / 120) * L ** 2]])
    mass = t + np.triu(t, 1).T
    if rotary:
        r = m.rho * s.I / (a ** 2 * L) * np.array([
            [6 / 5, (1 / 10 - b / 2) * L, -6 / 5, (1 / 10 - b / 2) * L],
            [0.0, (2 / 15 + b / 6 + c / 3) * L ** 2, -(1 / 10 - b / 2) * L,
             -(1 / 30 + b / 6 - c / 6) * L ** 2],
            [0.0, 0.0, 6 / 5, -(1 / 10 - b / 2) * L],
            [0.0, 0.0, 0.0, (2 / 15 + b / 6 + c / 3) * L ** 2]])
        mass = mass + r + np.triu(r, 1).T
    return k, mass


def torsion_element(s: Section, L: float) -> tuple[np.ndarray, np.ndarray]:
    """Stiffness G J / L and consistent mass ρ J L / 6 of a linear torsion element."""
    m = s.material
    one = np.array([[1.0, -1.0], [-1.0, 1.0]])
    return m.G * s.J / L * one, m.rho * s.J * L / 6.0 * np.array([[2.0, 1.0], [1.0, 2.0]])


def shaft_matrices(s: Section, z: np.ndarray, shear: bool = True,
                   rotary: bool = True) -> tuple[np.ndarray, np.ndarray]:
    """Stiffness and mass of a uniform shaft with nodes at ``z`` (m, increasing), 5 dofs a
    node in the order of :data:`X` … :data:`TZ`."""
    n = len(z) * DOF
    K, M = np.zeros((n, n)), np.zeros((n, n))
    for e, L in enumerate(np.diff(z)):
        kb, mb = bending_element(s, float(L), shear, rotary)
        for w, slope in ((X, SX), (Y, SY)):
            idx = [e * DOF + w, e * DOF + slope, (e + 1) * DOF + w, (e + 1) * DOF + slope]
            K[np.ix_(idx, idx)] += kb
            M[np.ix_(idx, idx)] += mb
        kt, mt = torsion_element(s, float(L))
        idx = [e * DOF + TZ, (e + 1) * DOF + TZ]
        K[np.ix_(idx, idx)] += kt
        M[np.ix_(idx, idx)] += mt
    return K, M

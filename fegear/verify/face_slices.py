"""The slice model of the face width against the 3D tooth (:mod:`.tooth3d`; docs/model.md,
"Across the face: the tooth in 3D"): the influence matrix the sections' model gives on the
3D tooth's patches, from the ring model's own parts and the coupling
(:mod:`fegear.toothpair.ring.face`), and the measured kernel's table fitted to the 3D tooth.

The 2D parts: gear 1's ring model under a unit line load on the 3D tooth's load band,
read as tooth3d reads its patches (:func:`~fegear.toothpair.ring.face.flank_compliance`):
c_hp, the half-plane's near field, and c_fe, the finite-element part. Across the face a
point's approach is A_hp p(z) + A_fe (S p)(z): under a unit force on patch j (a line load 1/w
over its width w), patch i reads

    G_ij = δ_ij c_hp / w + c_fe (1/w²) ∫_i ∫_j S(z, z') dz' dz,

S the coupling on sections fine enough that the patches' edges are sections (the continuum
the product's nine sections sample), a patch's load its sections' consistent share.
"""

from __future__ import annotations

import sys
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from scipy.optimize import nnls

from ..geometry import PairParameters
from ..toothpair import (
    KERNEL_STEP,
    FaceCoupling,
    SolveCase,
    correction_factors,
    exponential_kernel,
    face_coupling,
    flank_compliance,
    kernel_weights,
    measured_kernel,
    ring_model,
    tooth_coupling,
    twist_of,
)
from .tooth3d import FaceInfluence, face_influence, load_band

#: sections a patch's width when the slice model's S is formed on the patches (its limit:
#: 9 patches on 9 × 12 + 1 sections read within 0.1 % of 9 × 24 + 1's)
PER_PATCH = 12
#: the fit's kernel reaches this many tooth heights (the 10 mm face's patches 4.7 h apart)
REACH = 5.0
#: the fit: its linearisations (the rows' scales held at the last one's), and the weight of
#: ∫ τ = 1 among its equations (G / uniform, order one each)
FIT_ROUNDS = 6
MASS_WEIGHT = 100.0


@dataclass(frozen=True)
class BandCompliance:
    """Gear 1's ring model under a unit line load (N/mm) spread evenly over the load band:
    the band's mean approach, µm per N/mm, split as the sections take it: ``near`` the
    half-plane's near field (stays in its section), ``fe`` the finite-element part (spreads
    along the face); and the tooth height (mm)."""

    near: float
    fe: float
    tooth_height: float

    @property
    def total(self) -> float:
        return self.near + self.fe

    @property
    def near_share(self) -> float:
        return self.near / self.total


def band_compliance(params: PairParameters, height: float = 0.5,
                    quality: str = "coarse") -> BandCompliance:
    """Gear 1's 2D compliance at the 3D tooth's load band at ``height`` of its working flank,
    from the ring model at ``quality`` (module docstring)."""
    case, _, band = load_band(params, height)
    model = ring_model(SolveCase(params=params, quality=quality, tip_round=case.tip_round))
    return BandCompliance(*flank_compliance(model, band), band.tooth_height)


def table_kernel(table, band: BandCompliance) -> Callable[[np.ndarray], np.ndarray]:
    """:func:`~fegear.toothpair.ring.face.measured_kernel` for a ``table`` of values (τ h at
    |x| = KERNEL_STEP k h) without clipping: the fit reads its hats one by one."""
    h = band.tooth_height
    values = np.array(table, dtype=float) / h
    values[0] -= band.near_share / (KERNEL_STEP * h)
    values /= 1.0 - band.near_share
    nodes = KERNEL_STEP * h * np.arange(len(values))
    return lambda x: np.interp(np.abs(x), nodes, values, right=0.0)


def _patches(width: float, patches: int) -> tuple[np.ndarray, float]:
    """∫ over patch j of section i's hat (mm; sections × patches) on PER_PATCH sections a
    patch, and the patch width (mm)."""
    w = width / patches
    h = w / PER_PATCH
    within = np.zeros((patches * PER_PATCH + 1, patches))
    for j in range(patches):
        within[j * PER_PATCH:(j + 1) * PER_PATCH + 1, j] = h
        within[[j * PER_PATCH, (j + 1) * PER_PATCH], j] = 0.5 * h
    return within, w


def slice_influence(band: BandCompliance, width: float, patches: int,
                    kernel: Callable[[np.ndarray], np.ndarray], mirror: bool = True,
                    correction: str = "slope", twist: float = 0.0) -> np.ndarray:
    """The slice model's G (µm per N; patches × patches) on ``patches`` equal patches tiling
    a face ``width`` (mm) wide, its coupling from ``kernel`` (and ``twist``) as
    :func:`~fegear.toothpair.ring.face.face_coupling` forms it (module docstring)."""
    return _influence(band, width, patches, face_coupling(
        patches * PER_PATCH + 1, width, kernel, mirror, correction, twist))


def _influence(band: BandCompliance, width: float, patches: int,
               coupling: FaceCoupling) -> np.ndarray:
    """The slice model's G on ``patches`` patches under ``coupling`` (PER_PATCH sections a
    patch)."""
    within, w = _patches(width, patches)
    load = within / w / (coupling.share * width)[:, None]   # line load per N on patch j
    return band.fe * (within.T / w) @ coupling.spread @ load + np.eye(patches) * band.near / w


@dataclass(frozen=True)
class Comparison:
    """A column of the slice model's G against the 3D tooth's, each row divided by its
    uniform load's response (the 3D's ends are softer under it: the slice model's rows sum
    to the 2D pair's), ``slice`` and ``solid`` (patches); the largest difference against the
    column's largest entry (``peak``) and, beyond the loaded patch and its neighbours, against
    the largest entry there (``far``), as fractions."""

    column: int
    slice: np.ndarray
    solid: np.ndarray

    @property
    def peak(self) -> float:
        return float(np.abs(self.slice - self.solid).max() / self.solid.max())

    @property
    def far(self) -> float:
        away = np.abs(np.arange(len(self.solid)) - self.column) > 1
        return float(np.abs(self.slice - self.solid)[away].max() / self.solid[away].max())


def compare(solid: FaceInfluence, G: np.ndarray, column: int) -> Comparison:
    """``G`` (the slice model's) against ``solid``'s at patch ``column``, row by row divided
    by the uniform load's response (:class:`Comparison`)."""
    return Comparison(column, (G / G.mean(axis=1)[:, None])[:, column],
                      (solid.G / solid.uniform[:, None])[:, column])


def mismatch_loads(G: np.ndarray, ratio: float) -> np.ndarray:
    """The patches' loads (per their mean) that close a rigid gap tilted across the face by
    ``ratio`` times the mean approach (a misalignment in full contact: the approach G F
    plus the tilt is the same at every patch), from the influence ``G``."""
    n = len(G)
    zeta = (np.arange(n) + 0.5) / n - 0.5
    system = np.block([[G, -np.ones((n, 1))], [np.ones((1, n)), np.zeros((1, 1))]])
    mean = G.mean()                                   # the approach per N spread evenly
    loads = np.linalg.solve(system, np.append(ratio * zeta, 1.0 / mean))[:n]
    return loads / loads.mean()


def fit_table(solid: FaceInfluence, band: BandCompliance,
              correction: str = "slope") -> np.ndarray:
    """The kernel's table (τ h at |x| = KERNEL_STEP k h up to REACH h) with which the slice
    model (mirrored, ``correction``'s rows) reads ``solid``'s G, row by row divided by the
    uniform load's response, closest in the least squares: τ never rises with the distance
    (non-negative steps, :func:`scipy.optimize.nnls`), ∫ τ = 1 (the even load's answer). The
    kernel is affine in the table; the rows' corrections are held at the last round's."""
    width, patches = solid.z[0] + solid.z[-1], len(solid.z)
    nodes = int(round(REACH / KERNEL_STEP)) + 1
    within, w = _patches(width, patches)
    n = len(within)
    z, share, fixed = kernel_weights(n, width, table_kernel(np.zeros(nodes), band), True)
    basis = [kernel_weights(n, width, table_kernel(np.eye(nodes)[k], band), True)[2] - fixed
             for k in range(nodes)]
    load = within / w / (share * width)[:, None]
    target = (solid.G / solid.uniform[:, None]).ravel()
    near = (np.eye(patches) * band.near / w).ravel()
    mean = band.total / width                  # the slice model's rows' mean
    steps = np.tril(np.ones((nodes, nodes)))   # τ_k = Σ_{j ≥ k} step_j
    mass = 2 * KERNEL_STEP * np.ones(nodes)     # ∫ τ dx / h, the trapezoid rule on the nodes
    mass[0] = KERNEL_STEP
    table = np.exp(-KERNEL_STEP * np.arange(nodes))
    for _ in range(FIT_ROUNDS):
        raw = fixed + sum(t * b for t, b in zip(table, basis))
        scale = correction_factors(z, share, raw, correction)
        A = np.column_stack([_response(b * scale, band, within, load) for b in basis]) / mean
        rhs = target - (_response(fixed * scale, band, within, load) + near) / mean
        A = np.vstack([A, MASS_WEIGHT * mass])       # ∫ τ = 1: the even load's own answer
        rhs = np.append(rhs, MASS_WEIGHT)
        table = steps.T @ nnls(A @ steps.T, rhs)[0]
    return table


def _response(weights: np.ndarray, band: BandCompliance, within: np.ndarray,
              load: np.ndarray) -> np.ndarray:
    """The finite-element part's G (raveled) under the sections' spread ``weights``."""
    w = within.sum(axis=0)[0]
    return (band.fe * (within.T / w) @ weights @ load).ravel()


def table_text(table: np.ndarray) -> str:
    """``table`` as the source's KERNEL_TABLE."""
    rows = [", ".join(f"{v:.4f}" for v in table[k:k + 8]) for k in range(0, len(table), 8)]
    return "KERNEL_TABLE = (" + ",\n                ".join(rows) + ")"


def product_influence(band: BandCompliance, width: float, patches: int,
                      twist: float | None = None) -> np.ndarray:
    """The slice model's G as the product couples a tooth's face (the measured kernel
    mirrored, the rows' slope corrected, the tooth's twist:
    :func:`~fegear.toothpair.ring.face.tooth_coupling`); ``twist`` in place of the
    product's (:func:`~fegear.toothpair.ring.face.twist_of`), 0 for none."""
    if twist is None:
        twist = twist_of(width, band.tooth_height)
    return _influence(band, width, patches, tooth_coupling(
        patches * PER_PATCH + 1, width, band.tooth_height, band.near_share, twist))


def check_text(solid: FaceInfluence, band: BandCompliance, kernels: dict) -> str:
    """The mid-face and end columns of each of ``kernels`` (name → (kernel, mirror,
    correction, twist)) against ``solid``'s, row by row per the uniform load's response, with
    the differences."""
    width, patches = solid.z[0] + solid.z[-1], len(solid.z)
    lines = [f"{solid.size} 3D, face {width:g} mm, {patches} patches, tooth height "
             f"{band.tooth_height:.3f} mm; 2D near field {band.near:.5f}, finite-element "
             f"part {band.fe:.5f} µm per N/mm (near share {band.near_share:.3f})"]
    for column in (patches // 2, 0):
        lines.append(f"load on patch {column} (z {solid.z[column]:.3f} mm): G_i,j / uniform_i")
        lines.append("  3D            " + " ".join(
            f"{v:6.3f}" for v in (solid.G / solid.uniform[:, None])[:, column]))
        for name, (kernel, mirror, correction, twist) in kernels.items():
            c = compare(solid, slice_influence(band, width, patches, kernel, mirror,
                                               correction, twist), column)
            lines.append(f"  {name:<13} " + " ".join(f"{v:6.3f}" for v in c.slice)
                         + f"   peak {100 * c.peak:5.2f} %, far {100 * c.far:5.1f} %")
    return "\n".join(lines)


def main(argv: list[str]) -> str:
    """``python -m fegear.verify.face_slices fit|check [size] [quality=…] [name=value …]``:
    ``fit`` solves the 3D tooth on a face 5 tooth heights wide (18 patches) and prints the
    kernel's table; ``check`` solves it on the pair's 5 mm face (9 patches) and prints the
    slice model's columns against it: the product's (with the tooth's twist), the same without
    the twist and the exponential kernel's."""
    command, rest = argv[0], argv[1:]
    given = dict(a.split("=", 1) for a in rest if "=" in a)
    quality = given.pop("quality", "coarse")
    size = next((a for a in rest if "=" not in a), "standard")
    params = PairParameters(**{k: int(v) if k in ("z1", "z2") else float(v)
                               for k, v in given.items()})
    band = band_compliance(params, quality=quality)
    if command == "fit":
        solid = face_influence(params, thickness=5 * band.tooth_height, patches=18, size=size)
        return table_text(fit_table(solid, band))
    solid = face_influence(params, size=size)
    kernel = measured_kernel(band.tooth_height, band.near_share)
    kernels = {"product": (kernel, True, "slope", twist_of(5.0, band.tooth_height)),
               "no twist": (kernel, True, "slope", 0.0),
               "exponential": (exponential_kernel(4 * params.e1), False, "linear", 0.0)}
    return check_text(solid, band, kernels)


if __name__ == "__main__":
    sys.stdout.write(main(sys.argv[1:]) + "\n")

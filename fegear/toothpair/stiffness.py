"""Mesh stiffness over a mesh cycle: what ``fegear solve --positions N`` hands the drive level.

At each mesh phase the cycle gives gear 1's static rotation under the torque T with gear 2
held: the unloaded part e (rotation to first touch, the kinematic transmission error) and the
elastic part T/k, k the secant mesh stiffness in N·m/rad of gear-1 rotation; and the tangent
stiffness dT/dθ at T with the contact set kept, the spring of a dynamic model linearised about
the loaded state (larger than the secant where the contact grows with the load). They are
written to ``mesh_stiffness.json`` (and ``.csv``), which ``fegear drive dynamics`` and
``fegear drive reducer`` read.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import FegearError, ParameterError


@dataclass(frozen=True)
class MeshStiffness:
    """Mesh stiffness and transmission error over one mesh period at one torque: phase in
    [0, 1) (one gear-1 tooth pitch), stiffness k (N·m/rad of gear-1 rotation, gear 2 held,
    secant: T/elastic rotation), unloaded error e (rad of gear-1 rotation to first touch),
    torque (N·m), teeth z1, z2, module (mm) and face width (mm); ``tangent`` dT/dθ at each
    phase (N·m/rad), None in a file written before fegear computed it."""

    phase: np.ndarray
    stiffness: np.ndarray
    error: np.ndarray
    torque: float
    z1: int
    z2: int
    module: float
    thickness: float
    tangent: np.ndarray | None = None

    def __post_init__(self) -> None:
        n = len(self.phase)
        if n < 2 or len(self.stiffness) != n or len(self.error) != n:
            raise ParameterError("mesh stiffness", n, "two or more phases, one k and e each")
        if np.any(np.diff(self.phase) <= 0) or self.phase[0] < 0 or self.phase[-1] >= 1:
            raise ParameterError("phase", list(self.phase), "increasing, within [0, 1)")
        if not np.all(np.isfinite(self.stiffness)) or np.any(self.stiffness <= 0):
            raise ParameterError("stiffness", list(self.stiffness), "finite and > 0")
        t = self.tangent
        if t is not None and (len(t) != n or not np.all(np.isfinite(t)) or np.any(t <= 0)):
            raise ParameterError("tangent stiffness", list(t), "one per phase, finite and > 0")

    @property
    def mean(self) -> float:
        """Mean stiffness over the period (N·m/rad), trapezoidal on the periodic samples."""
        return float(_periodic_mean(self.phase, self.stiffness))

    @property
    def mean_tangent(self) -> float | None:
        """Mean tangent stiffness over the period (N·m/rad), None if not known."""
        return None if self.tangent is None else _periodic_mean(self.phase, self.tangent)

    def kind(self, name: str) -> MeshStiffness:
        """This mesh with the ``name`` ("secant" or "tangent") stiffness as its ``stiffness``
        (the error is the same): what a model that reads ``stiffness`` should use."""
        if name == "secant":
            return self
        if name != "tangent":
            raise ParameterError("stiffness kind", name, "secant or tangent")
        if self.tangent is None:
            raise FegearError("this mesh_stiffness.json has no tangent stiffness (written "
                              "before fegear computed it): solve the cycle again, or use "
                              "the secant spring (fegear drive: --spring secant)")
        return MeshStiffness(self.phase, self.tangent, self.error, self.torque, self.z1,
                             self.z2, self.module, self.thickness, self.tangent)

    def at(self, phase) -> tuple[np.ndarray, np.ndarray]:
        """k and e at ``phase`` (any real; periodic), linear between the samples."""
        x = np.mod(phase, 1.0)
        xp = np.concatenate([self.phase, [self.phase[0] + 1.0]])
        k = np.interp(x, xp, np.concatenate([self.stiffness, self.stiffness[:1]]),
                      period=1.0)
        e = np.interp(x, xp, np.concatenate([self.error, self.error[:1]]), period=1.0)
        return k, e

    def harmonics(self, n: int = 5) -> dict[str, list[float]]:
        """Amplitudes of the first ``n`` harmonics of k and e (mesh orders 1..n), from the
        samples taken as evenly spaced."""
        out = {}
        for name, v in (("stiffness", self.stiffness), ("error", self.error)):
            c = np.fft.rfft(v) / len(v)
            out[name] = [float(2 * abs(c[j])) for j in range(1, min(n, len(c) - 1) + 1)]
        return out

    def to_json(self) -> dict:
        return {"z1": self.z1, "z2": self.z2, "module_mm": self.module,
                "thickness_mm": self.thickness, "torque_Nm": self.torque,
                "mean_stiffness_Nm_per_rad": self.mean,
                "mean_tangent_Nm_per_rad": self.mean_tangent, "harmonics": self.harmonics(),
                "phase": self.phase.tolist(), "stiffness_Nm_per_rad": self.stiffness.tolist(),
                "tangent_stiffness_Nm_per_rad": (None if self.tangent is None
                                                 else self.tangent.tolist()),
                "error_rad": self.error.tolist()}


def _periodic_mean(x: np.ndarray, v: np.ndarray) -> float:
    xp = np.concatenate([x, [x[0] + 1.0]])
    vp = np.concatenate([v, v[:1]])
    return float(np.sum(0.5 * (vp[1:] + vp[:-1]) * np.diff(xp)) / (xp[-1] - xp[0]))


def mesh_stiffness_of_cycle(rows: list[dict], z1: int, z2: int, module: float, thickness: float,
               torque: float) -> MeshStiffness:
    """The mesh stiffness of a ``fegear solve --positions`` cycle (rows of
    :func:`fegear.toothpair.summary.cycle_rows`): phase = (β − β0)·z2/360°. A revolution's
    rows (``--revolution``: the same phases on every pitch) give their first pitch's."""
    beta = np.degrees(np.unwrap(np.radians([r["position_deg"] for r in rows])))  # past ±180°
    pitches = (beta - beta[0]) * z2 / 360.0
    first = np.flatnonzero(pitches < 1.0 - 1e-9)
    rows = [rows[i] for i in first]
    phase = pitches[first]
    order = np.argsort(phase)
    k = np.array([r["mesh_stiffness_Nm_per_rad"] for r in rows])
    e = 1e-6 * np.array([r["first_touch_urad"] for r in rows])
    tangent = [r.get("tangent_stiffness_Nm_per_rad") for r in rows]
    tangent = None if None in tangent else np.array(tangent)[order]
    return MeshStiffness(phase[order], k[order], e[order], torque, z1, z2, module, thickness,
                         tangent)


def read_mesh_stiffness(path: str | Path) -> MeshStiffness:
    """A ``mesh_stiffness.json`` written by ``fegear solve --positions N``."""
    try:
        d = json.loads(Path(path).read_text())
        return MeshStiffness(np.array(d["phase"], float),
                             np.array(d["stiffness_Nm_per_rad"], float),
                             np.array(d["error_rad"], float), float(d["torque_Nm"]),
                             int(d["z1"]), int(d["z2"]), float(d["module_mm"]),
                             float(d["thickness_mm"]),
                             None if d.get("tangent_stiffness_Nm_per_rad") is None
                             else np.array(d["tangent_stiffness_Nm_per_rad"], float))
    except OSError as exc:
        raise FegearError(f"--stiffness {str(path)!r}: cannot be read: {exc.strerror}") from None
    except (ValueError, KeyError, TypeError) as exc:
        raise FegearError(f"--stiffness {str(path)!r}: not a mesh_stiffness.json "
                          f"({type(exc).__name__}: {exc})") from None

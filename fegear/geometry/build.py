"""The geometry stage as one call: both profiles, the clearance table and the backlash."""

from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np

from ..timing import clocked, timed
from .clearance import Backlash, ContactState, ToothContact
from .gear1 import gear1_profile
from .gear2 import gear2_curve
from .parameters import PairParameters


@dataclass(frozen=True)
class PairGeometry:
    """Profiles and unloaded contact of a pair.

    Attributes:
        params: the inputs.
        gear1, gear2: closed polylines (n, 2) [mm], each in its own frame at β = 0.
        chord_error: bound on the polylines' chord error [mm].
        contact: clearance table at β = 0.
        backlash: smallest clearance per direction over a mesh cycle (or ``None``).
        timings: seconds per step.
    """

    params: PairParameters
    gear1: np.ndarray
    gear2: np.ndarray
    chord_error: float
    tip_radius: float
    root_radius: float
    contact: ContactState
    backlash: Backlash | None
    timings: dict
    relief_depth: np.ndarray | None = None   # tip relief depth (mm) at each gear-1 point
    relief_chart: tuple = ()                 # :meth:`Gear1Profile.relief_chart`

    def summary(self) -> dict:
        """JSON-ready summary (units in the key names)."""
        p = self.params
        teeth = [
            {"tooth": t.tooth, "position_deg": round(t.position_deg, 6),
             "plus_um": t.plus_um, "minus_um": t.minus_um}
            for t in sorted(self.contact.teeth, key=lambda t: t.position_deg)
        ]
        out = {
            "inputs": {"m": p.m, "z2": p.z2, "z1": p.z1, "h1": p.h1, "f1": p.f1,
                       "shift_mm": p.shift, "rotation_mm": p.rotation,
                       "tip_clearance_mm": p.radial_tip_clearance, "relief_um": p.relief,
                       "relief_extent_mm": p.relief_extent, "relief_start_mm": p.relief_start,
                       "relief_shape": p.relief_shape},
            "derived": {"r0_mm": p.r0, "e1_mm": p.e1, "e2_mm": p.e2, "e_mm": p.e,
                        "gear2_tip_radius_mm": p.r0 - 2 * p.e1,
                        "gear2_root_radius_mm": p.r0 + 2 * p.e1,
                        "gear1_tip_radius_mm": self.tip_radius,
                        "gear1_root_radius_mm": self.root_radius},
            "chord_error_um": self.chord_error * 1e3,
            "clearance_um": teeth,
            "interference": [asdict(i) for i in self.contact.interference],
            "timings_s": {k: round(v, 4) for k, v in self.timings.items()},
        }
        if self.relief_chart:
            out["relief"] = [{k: v for k, v in c.items() if not isinstance(v, np.ndarray)}
                             for c in self.relief_chart]
        if self.backlash is not None:
            b = self.backlash
            out["backlash_um"] = {"plus": b.plus_um, "minus": b.minus_um,
                                  "beta_plus_deg": float(np.degrees(b.beta_plus)),
                                  "beta_minus_deg": float(np.degrees(b.beta_minus))}
        return out


def build_geometry(params: PairParameters, chord_error: float = 1e-4,
               backlash_positions: int | None = 16) -> PairGeometry:
    """Generate both profiles, the β = 0 clearance table and (optionally) the backlash."""
    backlash = None
    with clocked() as clock:
        with timed("gear1_envelope"):
            g1 = gear1_profile(params)
        with timed("polylines"):
            poly1, depth = g1.polyline(chord_error, relief=True)
            poly2 = gear2_curve(params).polyline(chord_error, -np.pi / params.z2,
                                                 2 * np.pi - np.pi / params.z2)[:-1]
        with timed("clearance_table"):
            tca = ToothContact(params, g1)
            contact = tca.state(0.0)
        if backlash_positions:
            with timed("backlash"):
                backlash = tca.backlash(backlash_positions)
    tip = float(g1.radius(np.array([g1.tooth_center]))[0])
    root = float(g1.radius(np.array([g1.phi_space]))[0])
    return PairGeometry(params=params, gear1=poly1, gear2=poly2, chord_error=chord_error,
                        tip_radius=tip, root_radius=root, contact=contact, backlash=backlash,
                        timings=dict(clock.stages),
                        relief_depth=depth if params.relief > 0 else None,
                        relief_chart=tuple(g1.relief_chart()))

"""What varies across the face width of a pair (``fegear solve --misalignment`` and the
options beside it; docs/model.md, "Across the face"): the inputs of a solve across the face,
and what each adds to a contact point's rigid gap at a section of the face. The coupling of
the sections and the solve are the ring model's (:mod:`.ring.face`, :mod:`.ring.face_contact`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ..geometry import gear2_tooth, helix_trace
from ..planar import rotate

if TYPE_CHECKING:   # a contact's points, normals and feet: read, never built here
    from .ring.influence import RingContact

#: sections across the face where none are given: K_Hβ and the worst root stress move by less
#: than 1 % from 9 to 17 on the baseline (docs/model.md)
SECTIONS = 9
#: the deepest lead modification (crowning and end relief at an end together) per mm of module
#: (µm): the bound the profile's tip relief takes (``--relief``), a grinding depth that leaves
#: the tooth its flank
LEAD_DEPTH_PER_MODULE = 50.0


def deepest_lead_um(m: float) -> float:
    """The deepest lead modification a tooth of module ``m`` (mm) takes (µm):
    :data:`LEAD_DEPTH_PER_MODULE` m."""
    return LEAD_DEPTH_PER_MODULE * m


@dataclass(frozen=True)
class Face:
    """What varies across the face, in µm over the face width unless named otherwise.
    ``sections``: how many sections the line load is linear between (both ends among them).
    ``misalignment``: gear 1's axis displaced against gear 2's across the line of centres,
    from the face's first end (ζ = −½) to its second, + in the direction gear 1's loaded
    flanks push gear 2's at the pitch point (−x under a positive torque), so that the second
    end closes first; ``tilt``: the same along the line of centres (+: the centre distance
    grows towards the second end). ``crowning`` C_β: gear 1's teeth thinned by a parabola
    across the face, zero at mid-face and C_β at each end; ``end_relief`` C_I over
    ``end_length`` (mm) from each end, linear. ``helix1``/``helix2``: a tooth's helix slope
    f_Hβ (+: its loaded flank towards its mate at the second end, as much away at the first)
    and helix form f_fβ (+: towards its mate at mid-face, a parabola zero at the ends), as
    (gear-1 or gear-2 tooth, f_Hβ, f_fβ); ``leads1``/``leads2``: a tooth's measured lead as
    (tooth, places from the face's first end (mm), the flank's deviations there (µm, +: towards
    its mate))."""

    sections: int = SECTIONS
    misalignment: float = 0.0
    tilt: float = 0.0
    crowning: float = 0.0
    end_relief: float = 0.0
    end_length: float = 0.0
    helix1: tuple[tuple[int, float, float], ...] = ()
    helix2: tuple[tuple[int, float, float], ...] = ()
    leads1: tuple = ()
    leads2: tuple = ()

    @property
    def uneven_teeth(self) -> bool:
        """Whether a tooth has deviations across the face of its own (a helix deviation or a
        measured lead): the teeth of a gear then differ across the face."""
        return bool(self.helix1 or self.helix2 or self.leads1 or self.leads2)

    def per_tooth(self, zeta: np.ndarray, width: float) -> tuple[dict, dict]:
        """What each tooth's own deviations across the face add to its loaded flank's gap
        (µm, + opens) at the sections ``zeta`` of a face ``width`` mm wide, per gear: tooth →
        values. A helix slope f_Hβ subtracts f_Hβ ζ, a helix form f_fβ subtracts
        f_fβ (1 − 4ζ²), a measured lead its trace (linear between its points, its end
        values beyond them)."""
        out = []
        for helix, leads in ((self.helix1, self.leads1), (self.helix2, self.leads2)):
            teeth: dict[int, np.ndarray] = {}
            for tooth, slope, form in helix:
                teeth[tooth] = teeth.get(tooth, 0.0) - helix_trace(slope, form, zeta)
            for tooth, places, um in leads:
                teeth[tooth] = teeth.get(tooth, 0.0) - np.interp((zeta + 0.5) * width,
                                                                 places, um)
            out.append(teeth)
        return out[0], out[1]

    def offsets(self, contact: RingContact, turn: float, zeta: np.ndarray, width: float,
                z2: int) -> np.ndarray:
        """What the face's inputs add to the rigid gap (mm) of each of ``contact``'s points
        (gear 1 turned by ``turn``, rad) at sections ``zeta`` (fractions of the face
        ``width``, mm, from its middle): points × sections. A displacement d of gear 1 moves
        a point's gap by −n · d (n its outward normal in the fixed frame)."""
        n = rotate(contact.normal, turn)
        closing = n[:, 0] * self.misalignment - n[:, 1] * self.tilt   # −n · d per unit ζ
        out = np.outer(closing, zeta)
        out += self.crowning * (2.0 * zeta) ** 2
        if self.end_relief:
            beyond = np.abs(zeta) * width - (0.5 * width - self.end_length)
            out += self.end_relief * np.clip(beyond / self.end_length, 0.0, None)
        for teeth, own in zip((contact.teeth, gear2_tooth(contact.feet, z2)),
                              self.per_tooth(zeta, width)):
            for tooth, um in own.items():
                out[teeth == tooth] += um
        return 1e-3 * out

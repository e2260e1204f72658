"""Geometry stage: the exact tooth profiles of a compound-cycloid internal pair, and their
unloaded contact.

Gear 2, the internal gear, is the 4th-order compound cycloid of the seed paper's eq. (11)
(:mod:`.gear2`); gear 1 is its exact envelope in relative rolling, the lower envelope of the
solution branches of the meshing equation (:mod:`.envelope`, :mod:`.runs`, :mod:`.gear1`).
Designs gear 1 cannot be built for, or that are not clear before any load, are refused by
:mod:`.admissible` and :mod:`.refusal` with the admissible range of the input to change
(:mod:`.space` maps them). :mod:`.clearance` turns gear 1 until each tooth touches (the
clearance table, backlash, interference); :mod:`.tip_edge` rounds gear 1's tip edges for the
stress model; :func:`build_geometry` runs the stage in one call (``fegear profile``), and
:mod:`.drawing` draws each gear's whole outline to manufacture from (DXF).
Conventions and the seed paper's corrected parameters: docs/model.md.

>>> import math
>>> from fegear.geometry import Gear1Profile, PairParameters, RoundedProfile, ToothContact
>>> p = PairParameters(m=2, h1=0.3, f1=0.15, shift=0.016, rotation=0.002)
>>> p.r0, p.e1, p.e2, p.e                    # pitch radius, cranks, centre distance (mm)
(45.0, 0.6, 0.09, 1.0)
>>> g1 = Gear1Profile(p)                     # exact at any polar angle: point, normal, curvature
>>> round(float(g1.radius(g1.tooth_center)[0]), 4), round(float(g1.radius(g1.phi_space)[0]), 4)
(44.784, 42.784)
>>> first = ToothContact(p, g1).state(0.0).closest(+1)  # the tooth that touches first at β = 0
>>> first.tooth, round(first.plus_um, 3)     # and its clearance, µm of arc at r0
(11, 6.082)
>>> edges = RoundedProfile(g1, 0.25)         # the tip edges rounded for the stress model
>>> [round(math.degrees(kink), 1) for _, kink in edges.kinks]
[20.8, 20.8]
"""

from ..exports import lazy

__getattr__, __dir__, __all__ = lazy(__name__, {
    "parameters": ("PairParameters", "PAIR_INPUTS", "RENAMED"),
    "gear2": ("Cycloid", "gear2_curve", "gear2_tooth"),
    "envelope": ("Branch", "BranchPoints", "NEAR", "FAR"),
    "gear1": ("Gear1Profile", "gear1_profile"),
    "admissible": ("Defect", "defect", "design_defect", "resolve"),
    "refusal": ("admissible_pair", "check_design", "interval"),
    "clearance": ("ToothContact", "ContactState", "ToothClearance", "Backlash", "Interference",
                  "pitch_phase"),
    "tip_edge": ("RoundedProfile", "default_round", "largest_round"),
    "build": ("PairGeometry", "build_geometry"),
    "space": ("DesignMap", "design_map", "map_row", "map_span", "map_tables"),
    "deviations": ("Deviations", "ToothDeviation", "Runout", "Placed", "NO_DEVIATIONS",
                   "moved_clearances", "least_clearances", "least_of_states",
                   "point_clearances", "Closing", "closing_points"),
    "deviation_inputs": ("deviations_of", "read_deviations", "ToothEntry", "runout_text",
                         "check_teeth", "PER_TOOTH", "HELIX", "Helix", "helix_trace",
                         "tooth_deviations",
                         "read_leads"),
    "plot": ("pair_png", "map_png"),
    "drawing": ("Outline", "gear1_outline", "gear2_outline", "write_dxf", "pitch_turns"),
})

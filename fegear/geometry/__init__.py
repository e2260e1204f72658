"""Geometry stage: the exact tooth profiles of a compound-cycloid internal pair, and their
unloaded contact.

TODO walkthrough
"""

from ..exports import lazy

__getattr__, __dir__, __all__ = lazy(__name__, {
    "parameters": ("PairParameters",),
    "gear2": ("Cycloid", "gear2_curve"),
    "envelope": ("Branch", "BranchPoints", "NEAR", "FAR"),
    "gear1": ("Gear1Profile",),
    "admissible": ("check_admissible", "admissible_pair"),
    "clearance": ("ToothContact", "ContactState", "ToothClearance", "Backlash", "Interference"),
    "tip_edge": ("RoundedProfile",),
    "build": ("PairGeometry", "build_geometry"),
    "plot": ("pair_png",),
})

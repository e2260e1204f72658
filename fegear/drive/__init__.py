"""Drive level: ratios and mesh efficiencies of planetary trains, the bearing forces of the
three-ring reducer (seed 000), and a torsional lumped model driven by the FE mesh stiffness.

TODO walkthrough
"""

from ..exports import lazy

__getattr__, __dir__, __all__ = lazy(__name__, {
    "ratios": ("Ratio", "ngw", "nn", "khv", "two_kh", "internal_teeth", "carrier_ratio",
               "differential_speed", "meshing_efficiency", "meshing_phase"),
    "bearings": ("RingDrive", "LOAD_CASES", "PAPER", "bearing_forces", "extremes",
                 "exact_extremes", "support_reactions", "inertia_force"),
    "dynamics": ("TorsionalPair", "Response", "steady_response", "default_inertias",
                 "STEEL_DENSITY"),
    "report": ("bearings_summary", "bearings_table", "write_bearings", "ratio_table",
               "dynamics_summary", "dynamics_table", "write_dynamics"),
    "plot": ("bearings_png", "dynamics_png"),
})

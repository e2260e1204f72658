"""Drive level: ratios and mesh efficiencies of planetary trains, the bearing forces of the
three-ring reducer (seed 000), and a torsional lumped model driven by the FE mesh stiffness.

It stands beside the FE pipeline and uses only its output, the mesh stiffness of a solve cycle
(:class:`~fegear.toothpair.MeshStiffness`). :mod:`.ratios`: the carrier-fixed method and the
meshing-power efficiencies (seed 002); :mod:`.bearings`: seed 000's eccentric-bearing forces and
support reactions; :mod:`.dynamics`: a two-inertia torsional model over speed;
:mod:`.reducer`: seed 003's three-axis reducer, a bending–torsional model of its shafts and
plates (:mod:`.beams` its shaft elements, :mod:`.reducer_inputs` Table 1,
:mod:`.reducer_report` its results and the seed's findings checked, :mod:`.reducer_tilt` the
misalignment at each of its meshes under the rated torque as ``fegear solve`` takes it).

>>> from fegear.drive import internal_teeth, ngw
>>> drive = internal_teeth(44, 45)          # crank H in, gear 1 out, ring 2 translating
>>> round(drive.value, 6), drive.input, drive.output
(-44.0, 'H', '1')
>>> round(drive.efficiency(0.99), 4)        # mesh efficiency at η^H = 0.99
0.6875
>>> ngw(20, 70).value
4.5
"""

from ..exports import lazy

__getattr__, __dir__, __all__ = lazy(__name__, {
    "ratios": ("Ratio", "ngw", "nn", "khv", "two_kh", "internal_teeth", "carrier_ratio",
               "meshing_efficiency", "meshing_phase"),
    "bearings": ("RingDrive", "LOAD_CASES", "PAPER", "bearing_forces", "extremes",
                 "exact_extremes", "support_reactions", "inertia_force"),
    "dynamics": ("TorsionalPair", "Response", "steady_response", "default_inertias",
                 "STEEL_DENSITY"),
    "report": ("bearings_summary", "bearings_table", "write_bearings", "ratio_table",
               "dynamics_summary", "dynamics_table", "write_dynamics"),
    "plot": ("bearings_png", "dynamics_png", "reducer_campbell_png", "reducer_modes_png",
             "reducer_response_png"),
    "beams": ("Section", "ShaftMaterial", "shaft_matrices"),
    "reducer_inputs": ("ReducerInputs", "BUILDS"),
    "reducer": ("ReducerModel", "Mode", "build_reducer", "modes", "response", "whirl",
                "sweep", "turning_sweep", "over_turn", "frequency_spread", "turning_geometry",
                "frozen_quasi_static", "unbalance_forces", "unbalance_resultants",
                "support_reactions", "RESPONSES"),
    "reducer_report": ("MeshSource", "mesh_source", "reducer_summary", "reducer_table",
                       "write_reducer", "findings"),
    "reducer_tilt": ("MeshTilt", "mesh_tilts", "over_the_turn", "rated_misalignment",
                     "rated_torque_load", "face_components", "solve_values",
                     "misalignment_table"),
})

"""Tooth-pair stage: the stress solve of an assembled pair under torque, at one rolling
position or over a mesh cycle.

TODO walkthrough
"""

from ..exports import lazy

__getattr__, __dir__, __all__ = lazy(__name__, {
    "inputs": ("SOLVE_INPUTS", "QUALITY", "TIP_ROUND"),
    "case": ("SolveCase", "PairSolution", "ToothResult", "HEADLINE"),
    "scene": ("Scene", "build_scene"),
    "solve": ("solve_pair", "solve_positions", "cycle_positions", "choose_teeth"),
    "estimate": ("error_estimate", "second_level_estimate"),
    "report": ("pair_summary", "pair_table", "cycle_rows", "cycle_summary", "cycle_table"),
    "output": ("write_pair_outputs", "write_cycle_outputs", "write_mesh_stiffness"),
    "stiffness": ("MeshStiffness", "read_mesh_stiffness", "mesh_stiffness_of_cycle"),
    "job": ("Job", "JobResult", "prepare_job", "run_job"),
})

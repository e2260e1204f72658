"""Verification stage, beside the pipeline: the Hertz disk case, the benchmark (run time
against error), and CalculiX solving the same meshes.

TODO walkthrough
"""

from ..exports import lazy

__getattr__, __dir__, __all__ = lazy(__name__, {
    "disks": ("DiskCase", "DiskResult", "QUALITY", "solve_disks", "disk_geometries",
              "write_disk_outputs"),
    "bench": ("Ladder", "Rung", "Target", "richardson", "geometry_bench", "pair_bench",
              "disk_ladder", "pair_ladder", "ladder_targets", "ladder_table", "ladder_json",
              "peer_speedups", "PEER_TARGET", "machine"),
    "study_overhead": ("study_overhead", "overhead_table"),
    "calculix": ("PeerError", "PeerConvergenceError", "CcxDeck", "CcxResult", "ccx_available",
                 "write_deck", "run_ccx", "ccx_disks"),
    "calculix_pair": ("CcxPairResult", "ccx_pair"),
    "plot": ("ladder_png",),
})

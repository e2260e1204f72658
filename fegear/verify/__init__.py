"""Verification stage, beside the pipeline: the Hertz disk case, the benchmark (run time
against error), and CalculiX solving the same meshes.

:mod:`.disks` is the FE core's analytic reference (``fegear hertz``), solved with the peers'
penalty contact (:mod:`.penalty`, which the sector model, :mod:`.sector`, uses too);
:mod:`.bench` times every stage on meshes each twice as fine as the last and measures each
level's error against the Richardson extrapolation of the finest, and :mod:`.bench_run` runs
one ``fegear bench`` (what runs, its report, its files; the pair's targets in
:mod:`.pair_targets`); :mod:`.calculix` and :mod:`.calculix_pair` write the very same bodies,
supports, penalty and load as CalculiX decks and read its answers back; :mod:`.runner_bench`
times the study runner.

>>> from fegear.verify import DiskCase, richardson, solve_disks
>>> result = solve_disks(DiskCase(quality=4))   # 4 elements across the Hertz half-width
>>> round(result.p_error_pct, 2), round(result.b_error_pct, 2)  # % against Hertz
(0.18, -1.56)
>>> limit, order = richardson([1.04, 1.01, 1.0025])  # values on meshes each twice as fine
>>> round(limit, 6), round(order, 3)
(1.0, 2.0)
"""

from ..exports import lazy

__getattr__, __dir__, __all__ = lazy(__name__, {
    "disk_case": ("DiskCase", "DISK_QUALITY"),
    "disks": ("DiskResult", "solve_disks", "disk_geometries", "write_disk_outputs"),
    "bench": ("Ladder", "Rung", "Target", "richardson", "geometry_bench",
              "disk_ladder", "pair_ladder", "ladder_targets", "ladder_table", "ladder_json",
              "PEER_TARGET", "machine"),
    "ring_bench": ("RingRun", "CacheRuns", "cache_runs", "cache_table", "run_fresh", "ring_ladder",
                   "scaling_runs", "ring_table",
                   "scaling_table", "scaling_png", "paper_study_s", "SECTOR_REFERENCE",
                   "VON_MISES_RESOLVED"),
    "bench_run": ("BenchPlan", "run_bench"),
    "runner_bench": ("study_overhead", "overhead_table"),
    "calculix": ("CcxDeck", "CcxResult", "ccx_available", "write_deck", "run_ccx", "ccx_disks"),
    "ccx_files": ("PeerError", "PeerConvergenceError"),
    "calculix_pair": ("CcxPairResult", "ccx_pair"),
    "plot": ("ladder_png", "Series"),
})

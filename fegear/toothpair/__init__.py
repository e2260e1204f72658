"""Tooth-pair stage: the stress solve of an assembled pair under torque, at one rolling
position or over a mesh cycle.

:data:`SOLVE_INPUTS` is the schema of a solve's inputs (``fegear solve``'s options, a study
file's keys); :func:`prepare_job` checks them into a :class:`SolveCase`. The ring model
(:mod:`.ring`: both gears whole from one condensed tooth sector each, the contact's near field
from the half-plane; seconds a position) solves it; :func:`solve_pair` and
:func:`solve_positions` run it through the one driver over positions (:mod:`.positions`), which
the sector model, the full-FE peer in :mod:`fegear.verify.sector`, shares. :mod:`.teeth`
chooses the teeth that can touch; :mod:`.estimate`
solves a second mesh level for the discretisation error; :mod:`.safety` divides allowable
stresses by the results (safety factors); :mod:`.summary` gathers the numbers. Those are the
solve core; a run's further analyses (a cycle's table, a revolution, a tolerance class, the
sensitivities, a life rating) are one folder each in :mod:`.analyses`, and what a designer
reads (tables, the report page, pictures, files) is :mod:`.present`. :func:`run_job` does all
of it for ``fegear solve`` and a study case.

A light pair (25/24 teeth) at 20 N·m, coarse:

>>> from fegear.geometry import PairParameters
>>> from fegear.toothpair import SolveCase, solve_pair
>>> pair = PairParameters(m=2, z2=25, z1=24, shift=0.016, rotation=0.002)
>>> sol = solve_pair(SolveCase(pair, torque=20.0, quality="coarse"))
>>> {name: round(value) for name, value in sol.headline().items()}  # MPa
... # doctest: +NORMALIZE_WHITESPACE
{'root_stress_gear1_MPa': 75, 'root_stress_gear2_MPa': 55,
 'contact_pressure_MPa': 805, 'flank_contact_pressure_MPa': 310,
 'von_mises_max_MPa': 799}
>>> [(t.tooth, round(t.load_share, 2)) for t in sol.teeth if t.load_N > 0]
[(5, 0.44), (6, 0.56)]
>>> sol.checks.balance_error < 1e-6       # the torque is carried by the contact pressure
True

Safety factors, allowable / stress, at 42CrMo's allowables (558 MPa bending, 745 contact):
S_H divides by the peak pressure, here on tooth 6's tip round (the flank alone gives 2.4):

>>> from fegear.toothpair import pair_summary
>>> s = pair_summary(sol)
>>> [round(s[k], 2) for k in ("safety_bending_gear1", "safety_contact", "safety_contact_flank")]
[7.49, 0.93, 2.4]

The same inputs as ``fegear solve`` takes them, by name (defaults for the rest):

>>> from fegear.toothpair import SOLVE_INPUTS, prepare_job
>>> SOLVE_INPUTS["shift"].default is None  # 0.008 m: the seed paper's built pair
True
>>> job = prepare_job({"z2": 25, "z1": 24, "torque": 20.0, "quality": "coarse",
...                    "positions": 4})
>>> job.case.params.shift, job.case.params.rotation
(0.016, 0.002)
>>> [round(beta, 5) for beta in job.betas]  # rad: one gear-2 pitch in 4 steps
[0.0, 0.06283, 0.12566, 0.1885]
>>> round(job.case.torque_limit)  # N·m: the largest torque, 0.05 E m b r1
2472
"""

from ..exports import lazy

__getattr__, __dir__, __all__ = lazy(__name__, {
    # the solve core: the inputs, the case and its results, the driver, the ring model, the
    # job, the summary and what it is judged by
    "inputs": ("SOLVE_INPUTS", "JOB_INPUTS", "QUALITY", "TIP_ROUND", "RENAMED"),
    "case": ("SolveCase", "PairSolution", "ToothResult", "ContactChecks", "BodyField",
             "ContactZone", "HEADLINE", "cycle_positions"),
    "pair": ("solve_pair", "solve_positions", "solve_job_positions"),
    "teeth": ("choose_teeth", "candidate_data", "refuse_interference", "Candidate",
              "tension_fillets", "TOOTH_STIFFNESS"),
    "face": ("deepest_lead_um",),
    "ring.master": ("Gear2Master",),   # the sector model's master curve too
    "ring.cache": ("model_cache",),
    "ring.model": ("ring_model",),
    # the face's coupling and the 2D parts it reads: what the 3D tooth checks
    "ring.face": ("FlankBand", "FaceCoupling", "flank_band", "flank_compliance", "face_coupling",
                  "exponential_kernel", "measured_kernel", "kernel_weights",
                  "correction_factors", "KERNEL_STEP", "product_coupling",
                  "tooth_coupling", "tilted_across", "twist_of", "neighbour_tilts",
                  "TWIST_TABLE", "NEIGHBOUR_TILTS"),
    "edge": ("flank_and_edge", "FlankEdge", "EDGE_ZONE"),
    "segments": ("ROOT_BAND", "Layout", "PairProfiles", "PolarCurve", "gear2_outline",
                 "gear2_polar", "path_windows", "profile_segments", "root_half_angle",
                 "round_strips", "unwrap_near"),
    "estimate": ("error_estimate", "second_level_estimate"),
    "safety": ("Allowables", "DEFAULT_ALLOWABLES", "SAFETY", "TOOTH_SAFETY", "allowables_of",
               "safety_factor", "safety_factors", "with_safety"),
    "summary": ("pair_summary", "cycle_rows", "cycle_summary"),
    "stiffness": ("MeshStiffness", "read_mesh_stiffness", "mesh_stiffness_of_cycle"),
    "case_file": ("FILE_INPUTS", "CaseFileError", "case_record", "case_toml", "is_file",
                  "read_case", "relative_to"),
    "job": ("Job", "Solved", "prepare_job", "solve_job", "solve_command", "tip_round_of"),
    "positions": ("PositionModel", "Trial", "Attempt", "SHARE_GUESS", "ATTEMPTS", "CHAINED",
                  "drive", "expected_elastic_um", "first_teeth"),
    # the analyses: their registry, and what other stages read of one
    "analyses": ("ANALYSES", "Analysis", "Verdict", "asked", "shown"),
    "analyses.cycle.report": ("cycle_table", "write_cycle_outputs", "write_mesh_stiffness"),
    "analyses.samples.solve": ("class_samples", "Sampled"),
    "analyses.samples.chains": ("Enough",),
    "analyses.samples.report": ("ClassReading", "samples_columns", "samples_summary",
                                "samples_table"),
    "analyses.rating.report": ("damage_text", "life_text", "safety_text"),
    "analyses.sensitivities.report": ("sensitivity_columns", "sensitivity_table"),
    # the presentation: tables, the report page, pictures, files
    "present.tables": ("pair_table", "factor_cell", "stiffness_cell"),
    "present.output": ("Drawing", "JobResult", "run_job", "write_job", "write_pair_outputs"),
    "present.plot": ("prepare_pictures",),
    "present.html_report": ("write_report", "report_html", "verdicts", "index_html"),
})

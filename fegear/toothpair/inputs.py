"""The inputs of a tooth-pair solve: one schema for the command line, study files and keys.

``fegear solve`` builds its options from :data:`SOLVE_INPUTS`, a study file's keys are its
names, and a study case's cache key hashes every input at its value or default, so the three
cannot drift apart; the allowable stresses, which only read the results, stay out of the key
(:meth:`~fegear.checks.InputTable.keyed`). Each row carries its kind, default, unit, static
range and help; ranges that depend on other inputs are checked by the objects the inputs build
(:class:`~fegear.geometry.PairParameters`, :class:`~fegear.toothpair.SolveCase`).
"""

from __future__ import annotations

from typing import Literal, get_args

from ..checks import Input, InputTable, require_range
from ..errors import ParameterError
from ..fe import ALLOWABLE_INPUTS, MATERIAL_INPUTS
from ..geometry import PAIR_INPUTS, RENAMED  # noqa: F401  (RENAMED: for study files)

#: a mesh quality level; :data:`QUALITY` lists them coarsest first (each finer than the last)
Quality = Literal["coarse", "fast", "standard", "fine"]
QUALITY: tuple[str, ...] = get_args(Quality)
TIP_ROUND = 0.125        # default tip-edge round of gear 1, in modules (0.25 mm at m = 2)
#: the largest torque, as a load per face width on gear 1's pitch circle over E m: far past any
#: steel's strength (the seed paper's pair: 4530 N·m, 23 times its 200, roots at ~1.7 GPa) and
#: within what the contact solve settles at (that pair settled at 5e4 N·m, not at 1e5)
LOAD_LIMIT = 0.05

LOAD_INPUTS = (
    Input("torque", float, 200.0, "torque on gear 1 (the upper limit is a load per face width "
          "at gear 1's pitch circle of 5 % of E m: 4532 N·m for the seed paper's pair, where "
          "its roots carry about 1.7 GPa)", "N·m", low=0.0, low_open=True,
          limits="0 < torque <= 0.05 E m b r1"),
    Input("position", float, 0.0, "rolling angle β of gear 2", "deg", low=-180.0, high=180.0),
    Input("positions", int, None, "solve N rolling angles across one tooth pitch from "
          "--position on one mesh; writes cycle.csv, cycle.png and mesh_stiffness.json/.csv",
          low=2, high=360, rule="none (one position)"),
    Input("revolution", bool, False, "solve every pitch of one turn of gear 1 (z1 pitches, "
          "--positions in each, 24 if not given): the worst of each stress with its tooth, the "
          "stresses per tooth and the transmission error's spectrum; writes revolution.csv, "
          "revolution.png, revolution_teeth.png and revolution.pvd; with --grade, each pair "
          "of the class over the whole turn, its worst there its row (screened: every pitch "
          "at two places, then about each pair's largest; docs/tolerance.md)"),
)

MODEL_INPUTS = (
    Input("quality", str, "standard", "mesh quality", choices=QUALITY, metavar="LEVEL"),
    Input("tip-round", float, None, "gear-1 tip-edge round radius", "mm", low=0.0,
          limits="0 <= tip-round <= m/2 and fitting the tip edges",
          rule=f"{TIP_ROUND:g} m, or half the largest round that fits where that does not"),
    Input("rim1", float, None, "gear-1 rim below the roots, to the bore", "mm", low=0.0,
          low_open=True, limits="m/2 <= rim1 <= 20 m and at most 0.6 of gear 1's root radius",
          rule="3 m, at most 0.6 of gear 1's root radius"),
    Input("rim2", float, None, "gear-2 rim beyond the roots, to the fixed rim", "mm", low=0.0,
          low_open=True, limits="m/2 <= rim2 <= 20 m", rule="3 m"),
    Input("extra-pairs", int, 0, "pair this many more teeth on each side than the closure "
          "needs (a safety check)", low=0, high=5),
    Input("no-estimate", bool, False, "skip the second mesh level (no discretisation-error "
          "estimate)"),
)

def tooth_input(name: str, help: str) -> Input:
    """An input of the ``GEAR:TOOTH=µm`` grammar (:mod:`fegear.geometry.deviation_inputs`
    reads it), named ``name``: none by default, given more than once or comma-separated."""
    return Input(name, str, None, help, limits="GEAR 1 or 2, an existing tooth, |µm| <= 1000",
                 rule="none", repeat=True, metavar="GEAR:TOOTH=µm")


#: a real pair's manufacturing and assembly deviations (docs/geometry.md, "Deviations"): + moves
#: a tooth's loaded flank towards its mate
DEVIATION_INPUTS = (
    tooth_input("pitch-deviation", "teeth turned along their pitch circle (a tooth's position "
              "deviation), GEAR:TOOTH=µm, comma-separated, e.g. 1:11=5"),
    tooth_input("slope-deviation", "profile slope deviations: the loaded flank's normal "
              "departure growing from its root to the value at its tip, GEAR:TOOTH=µm"),
    tooth_input("form-deviation", "profile form deviations: a parabola along the loaded flank, "
              "the value at its middle, GEAR:TOOTH=µm"),
    Input("centre-distance-deviation", float, 0.0, "the centres farther apart than "
          "m (z2 - z1)/2 by this", "µm", low=-1000.0, high=1000.0),
    Input("runout", str, None, "radial runout F_r of a gear and the angle of its high point "
          "from tooth 0, GEAR=µm[@deg], comma-separated, e.g. 1=10@90 (without @deg, 0°: the "
          "high point at tooth 0)",
          limits="GEAR 1 or 2, 0 <= µm <= 1000", rule="none", repeat=True,
          metavar="GEAR=µm[@deg]"),
    Input("deviations", str, None, "a CSV file of measured deviations, a row per tooth: gear, "
          "tooth and any of fp, fpt, fHa, ffa, fHb, ffb with their units, e.g. fp [µm] (fHb "
          "and ffb, the helix's, are read across the face)",
          limits="a readable file (docs/geometry.md)", rule="none", metavar="FILE"),
)
#: a tolerance class's sampled pairs (docs/tolerance.md): what most gears of the class carry
TOLERANCE_INPUTS = (
    Input("grade", int, None, "ISO 1328-1:2013 flank tolerance class of both gears: solve "
          "--samples pairs whose deviations that class admits, beside the exact pair, and "
          "report each stress's quantiles and the safety factors at --quantile; writes "
          "samples.csv and samples.png", low=1, high=11, rule="none (the pair as given)"),
    Input("samples", int, 200, "how many pairs of the --grade are drawn", low=1,
          high=100000),
    Input("seed", int, 0, "the draw's seed: sample k is the same pair whatever --samples is",
          low=0, high=2**63 - 1),
    Input("quantile", float, 0.95, "the share of the --grade's pairs the verdict's safety "
          "factors hold for", low=0.5, high=1.0, high_open=True),
    Input("centre-distance-tolerance", float, 0.0, "the ± tolerance of the centre distance "
          "drawn with --grade (0: exact)", "µm", low=0.0, high=1000.0),
    Input("misalignment-band", float, None, "with --grade across the face: each pair's "
          "misalignment drawn within ±B about --misalignment (normal, σ = B/3), as the "
          "class's deviations are", "µm", low=0.0, high=200.0,
          limits="0 <= misalignment-band, |misalignment| + misalignment-band <= 200 µm",
          rule="none (every pair at --misalignment)"),
    Input("sensitivities", bool, False, "each stress's rate with each deviation of the teeth "
          "in mesh (MPa/µm) at the position of the largest gear-1 root stress, and with "
          "--grade what one tolerance of each moves; writes sensitivities.csv and "
          "sensitivities.png"),
)

#: across the face width (docs/model.md, "Across the face"): any of them solves the pair at
#: sections across the face, coupled by the gears' stiffness, with their offsets
FACE_INPUTS = (
    Input("misalignment", float, None, "gear 1's axis displaced against gear 2's across the "
          "line of centres, from the face's first end to its second; + in the direction gear "
          "1's loaded flanks push at the pitch point, so that the second end closes first",
          "µm", low=-200.0, high=200.0, rule="none (the 2D pair, unless another face input "
          "is given)"),
    Input("tilt", float, None, "the same along the line of centres: + the centre distance "
          "grows towards the face's second end", "µm", low=-200.0, high=200.0, rule="0"),
    Input("crowning", float, None, "lead crowning C_β of gear 1's teeth: a parabola across "
          "the face, C_β thinner at each end", "µm", low=0.0,
          limits="0 <= crowning, crowning + end-relief <= 50 m µm", rule="0"),
    Input("end-relief", float, None, "end relief C_I of gear 1's teeth at each end of the "
          "face, linear over --end-length", "µm", low=0.0,
          limits="0 <= end-relief, crowning + end-relief <= 50 m µm", rule="0"),
    Input("end-length", float, None, "the end relief's length from each end", "mm",
          low=0.0, low_open=True, limits="0 < end-length <= face-width / 2",
          rule="a fifth of the face width"),
    tooth_input("helix-slope-deviation", "helix slope deviations f_Hβ: a tooth's loaded flank "
              "towards its mate at the face's second end and as much away at its first, "
              "GEAR:TOOTH=µm (a deviations file's fHb column too)"),
    tooth_input("helix-form-deviation", "helix form deviations f_fβ: a tooth's loaded flank "
              "towards its mate at mid-face, a parabola zero at the ends, GEAR:TOOTH=µm (a "
              "deviations file's ffb column too)"),
    Input("lead", str, None, "measured leads: a CSV file, a row a point of a tooth's trace, "
          "columns gear, tooth, z [mm] from the face's first end and deviation [µm] (+: its "
          "loaded flank towards its mate), each trace linear between its points",
          limits="a readable file (docs/deviations.md)", rule="none", metavar="FILE"),
    Input("face-sections", int, None, "sections across the face the line load is linear "
          "between, both ends among them", low=3, high=65, rule="9"),
)

#: a rating for a life (docs/rating.md): a load spectrum on the material's S-N lines
RATING_INPUTS = (
    Input("spectrum", str, None, "a load spectrum, CSV or TOML: torque (N·m) with cycles "
          "(revolutions of gear 1 against gear 2), or with a share of the time and --speed, "
          "--life; each level solved at KA·KV·torque at the positions, each tooth's damage by "
          "Miner's rule on the --material's S-N lines, the life and the safety factors at the "
          "required life; writes rating.csv", rule="none (no life rating)", metavar="FILE"),
    Input("speed", float, None, "gear 1's speed against gear 2 (turns a spectrum's shares "
          "and its life into cycles; with cycles, the life in hours)", "rpm", low=0.0,
          low_open=True, high=1e5, rule="none"),
    Input("life", float, None, "the required life (with --spectrum's shares and --speed)",
          "h", low=0.0, low_open=True, high=1e7, rule="none"),
    Input("KA", float, 1.0, "application factor: every level's torque is solved times it "
          "(ISO 6336-1: 1.0 uniform driver and load to 2.25 and more for heavy shocks)",
          low=1.0, high=5.0),
    Input("KV", float, 1.0, "dynamic factor: every level's torque is solved times it too "
          "(`fegear drive dynamics` gives the dynamic factor max F/T at a speed)", low=1.0,
          high=5.0),
    Input("material", str, "42CrMo", "the gears' material for the life rating: 42CrMo (the "
          "seed paper's, default), 42CrMo-QT, 42CrMo-nitrided, 20CrMnTi, 18CrNiMo7-6, or a "
          "TOML file with treatment, sigma_Hlim and sigma_FE (MPa)", metavar="NAME|FILE"),
)

#: the inputs that only a feature reads, and the input that turns it on: given without it,
#: they are refused by name (a class's draw, a life rating)
REQUIRES = {**dict.fromkeys(("samples", "seed", "quantile", "centre-distance-tolerance",
                             "misalignment-band"), "grade"),
            **dict.fromkeys(("speed", "life", "KA", "KV", "material"), "spectrum"),
            "end-length": "end-relief"}

#: every input of ``fegear solve`` (and of a study case), in the order of ``--help``
SOLVE_INPUTS = InputTable(PAIR_INPUTS, LOAD_INPUTS[:2], LOAD_INPUTS[2:], MATERIAL_INPUTS,
                          ALLOWABLE_INPUTS, MODEL_INPUTS, DEVIATION_INPUTS)
#: ``fegear solve``'s inputs: a solve's and a tolerance class's samples (not yet a study's)
JOB_INPUTS = InputTable(SOLVE_INPUTS.values(), TOLERANCE_INPUTS, RATING_INPUTS, FACE_INPUTS)


def torque_limit(E: float, m: float, face_width: float, r1: float) -> float:
    """The largest torque a solve takes (N·m): :data:`LOAD_LIMIT` E m b r1, with E in MPa, the
    module, face width and gear 1's pitch radius in mm."""
    return LOAD_LIMIT * E * m * face_width * r1 * 1e-3


def check_torque(torque: object, E: float, m: float, face_width: float, r1: float) -> float:
    """``torque`` (N·m) checked against ``0 < torque <= 0.05 E m b r1`` at the given E, m, b
    and r1 (checked already), which a refusal states whatever is wrong with the value."""
    return require_range("torque", torque, 0.0, torque_limit(E, m, face_width, r1),
                         lo_open=True, unit=f"N·m (0.05 E m b r1 at E={E:g} MPa, m={m:g}, "
                                            f"b={face_width:g}, r1={r1:g} mm)")


def check_band(band: object, misalignment: float, across: bool) -> float:
    """A misalignment band (µm, ``--misalignment-band``; None: none) checked against ``0 <=
    band`` and ``|misalignment| + band <= 200 µm`` (every pair drawn within
    ``--misalignment``'s range), and refused where the class is not ``across`` the face:
    0 where none is given."""
    if band is None:
        return 0.0
    if not across:
        raise ParameterError("misalignment-band", band, "with --grade across the face only "
                             "(with --misalignment or another face input)")
    return require_range("misalignment-band", band, 0.0, 200.0 - abs(misalignment),
                         unit="µm (200 µm less |misalignment|)")


def check_tip_round(radius: object, m: float) -> float:
    """A tip round (mm) checked against ``0 <= tip-round <= m/2`` at the module ``m`` (whether
    it fits the tip edges is the rounded profile's check)."""
    return require_range("tip_round", radius, 0.0, 0.5 * m, unit="mm (m/2)")

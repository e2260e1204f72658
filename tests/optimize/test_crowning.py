"""The lead crowning search (fegear.optimize.crowning) on a band whose K_Hβ is known, then on
the baseline pair solved across the face (coarse, one position), and its refusals."""

import json

import pytest

from fegear.cli import main
from fegear.errors import ParameterError
from fegear.optimize.crowning import (
    BandPoint,
    CrowningSearch,
    band_point,
    size_crowning,
    sizing_table,
)

BAND = 8.0   # within the baseline's room (it jams beyond 9.95 µm)
#: the known band: K_Hβ at ±F falls to 1.1 at C = 3 µm and rises again; aligned, 1 + 0.03 C
END_LEAST_UM, END_LEAST = 3.0, 1.1


def _known(calls: list):
    """A band point of the known band, each call recorded as (crowning, misalignment)."""

    def solve(values, crowning, misalignment, search, executor):
        calls.append((crowning, misalignment))
        if misalignment == 0.0:
            k = 1.0 + 0.03 * crowning
        else:
            k = END_LEAST + 0.02 * (crowning - END_LEAST_UM) ** 2
        return BandPoint(misalignment, k, k, k, k)

    return solve


def _sized(target: float, tolerance: float = 0.5, values=None, calls=None):
    calls = [] if calls is None else calls
    return size_crowning(values or {}, CrowningSearch(BAND, target, positions=1,
                                                      tolerance_um=tolerance),
                         solve=_known(calls))


def test_the_smallest_crowning_that_keeps_the_band_under_the_target():
    calls = []
    s = _sized(1.15, calls=calls)
    # K_Hβ at ±F is 1.15 at C = 3 - √2.5 = 1.419 µm; the aligned pair stays under to 5 µm
    smallest = END_LEAST_UM - 2.5 ** 0.5
    assert s.reached
    assert smallest <= s.amount_um <= smallest + 0.5
    assert s.chosen.K_Hbeta <= 1.15
    failed = max(t.amount_um for t in s.trials if t.K_Hbeta > 1.15
                 and t.amount_um < s.amount_um)
    assert s.amount_um - failed <= 0.5           # a crowning within the tolerance below misses
    # a mirrored pair: +F and the aligned pair solved, −F mirrored; the even face not solved
    assert {f for _, f in calls} == {BAND, 0.0} and (0.0, 0.0) not in calls
    assert s.solves == len(calls) == 2 * len(s.trials) - 1
    assert [p.misalignment_um for p in s.chosen.points] == [-BAND, 0.0, BAND]
    summary = json.loads(json.dumps(s.summary(), allow_nan=False))   # what --json prints
    assert summary["amount_um"] == s.amount_um and summary["reached"]
    assert "--crowning" in summary["command"] and len(summary["trials"]) == len(s.trials)


def test_an_end_relief_is_sized_by_the_same_search_and_solved_by_its_own_options():
    calls = []
    s = size_crowning({}, CrowningSearch(BAND, 1.15, positions=1, modification="end-relief",
                                         end_length_mm=1.0), solve=_known(calls))
    crowned = _sized(1.15)
    assert s.amount_um == crowned.amount_um and s.solves == crowned.solves
    assert "--end-relief" in s.command() and "--end-length 1" in s.command()
    assert "--crowning" not in s.command()
    assert sizing_table(s).startswith(f"end relief C_I {s.amount_um:.2f} µm over 1 mm from "
                                      "each end: the smallest")


def test_a_band_met_without_crowning_takes_one_solve():
    s = _sized(1.3)
    assert s.reached and s.amount_um == 0.0 and s.solves == 1
    assert "no lead crowning needed" in sizing_table(s)


def test_an_unreachable_target_gives_the_crowning_that_minimises_the_band():
    s = _sized(1.05, tolerance=0.25)
    assert not s.reached
    assert s.amount_um == pytest.approx(END_LEAST_UM, abs=0.25)
    assert s.chosen.K_Hbeta == min(t.K_Hbeta for t in s.trials)
    assert s.solves <= 20
    assert "no lead crowning keeps K_Hβ at most 1.05" in sizing_table(s)


def test_helix_deviations_break_the_mirror_and_the_band_takes_three_solves():
    calls = []
    s = _sized(1.15, values={"helix-slope-deviation": ["1:11=1"]}, calls=calls)
    assert not s.mirrored
    assert {f for _, f in calls} == {BAND, -BAND, 0.0}
    assert s.solves == len(calls) == 3 * len(s.trials)


def test_the_baseline_sized_across_the_face_meets_the_target_at_both_ends_and_aligned():
    values = {"torque": 200.0}
    before = band_point(values, 0.0, -5.0, CrowningSearch(5.0, positions=1))
    # a target a fifth of the way down from the uncrowned pair's K_Hβ towards 1, set from the
    # model's own number: one that crowning reaches (1.34 → 1.15 at 1.25 µm on the baseline
    # at one position)
    target = 1.0 + 0.8 * (before.K_Hbeta - 1.0)
    search = CrowningSearch(5.0, target=target, positions=1, quality="coarse",
                            tolerance_um=1.0)
    s = size_crowning(values, search)
    assert s.reached and s.amount_um > 0.0
    assert before.K_Hbeta > target
    failed = max(t.amount_um for t in s.trials if t.K_Hbeta > target
                 and t.amount_um < s.amount_um)
    assert s.amount_um - failed <= search.tolerance_um
    # the −F end, which the search mirrors from +F, solved: the same K_Hβ, under the target
    other = band_point(values, s.amount_um, -5.0, search)
    for k, solved in ((0.0, before), (s.amount_um, other)):
        assert solved.K_Hbeta == pytest.approx(s.trial(k).ends[0].K_Hbeta, rel=1e-6)
    assert other.K_Hbeta <= target
    assert s.chosen.aligned.K_Hbeta <= target and s.chosen.ends[1].K_Hbeta <= target
    assert f"--crowning {s.amount_um:g} --misalignment 5" in s.command()
    # an end relief (its own option, solved) opens the closing end: the worst root stress
    # there falls (1.14 → 1.09 times the 2D pair's at 2 µm on the baseline at one position)
    relieved = band_point(values, 2.0, -5.0, CrowningSearch(5.0, positions=1,
                                                            modification="end-relief"))
    assert relieved.root_ratio < before.root_ratio - 0.02


@pytest.mark.parametrize("argv,told", [
    (["--misalignment-band", "12"], "misalignment-band <= 9.95 µm"),   # the pair jams
    ([], "(required: the band ±F the crowning must cover)"),
    (["--misalignment-band", "0"], "0 < misalignment-band <= 200 µm"),
    (["--misalignment-band", "5", "--target", "1"], "1 < target <= 3"),
    (["--misalignment-band", "5", "--positions", "0"], "1 <= positions <= 360"),
    (["--misalignment-band", "5", "--h1", "9"], "0.0500 <= h1 <= 0.8310"),
    (["--misalignment-band", "5", "--end-length", "1"], "with --modification end-relief"),
    (["--misalignment-band", "5", "--modification", "end-relief", "--end-length", "3"],
     "0 < end-length <= half the face width (2.5 mm)"),
    (["--misalignment-band", "5", "--modification", "lead"], "crowning / end-relief"),
])
def test_bad_inputs_are_refused_in_one_line_by_name(argv, told, capsys):
    assert main(["crowning", *argv]) == 2
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 1 and told in lines[0], lines
    name = next((w for w in argv[::-1] if w.startswith("--")), "--misalignment-band")
    assert lines[0].startswith(f"fegear: error: {name} = ")


def test_the_search_is_refused_without_its_band():
    with pytest.raises(ParameterError) as err:
        CrowningSearch(None)
    assert err.value.name == "misalignment-band"


def test_a_design_searched_across_the_face_is_measured_at_its_worst_section(tmp_path, capsys):
    """`fegear optimize --misalignment 8 --vary crowning=…`: a design's stresses are its
    worst section's (the solve across the face, its K_Hβ beside them), above the 2D pair's,
    and a crowning brings the root stress down; crowning is a variable of the space."""
    from fegear.optimize.design import evaluate
    from fegear.optimize.space import VARIABLES
    from fegear.toothpair import prepare_job, solve_job

    base = {"torque": 200.0, "quality": "coarse"}
    flat = evaluate(base, 2, {})
    tilted = evaluate({**base, "misalignment": 8.0}, 2, {})
    crowned = evaluate({**base, "misalignment": 8.0, "crowning": 3.0}, 2, {})
    face = solve_job(prepare_job({**base, "misalignment": 8.0, "positions": 2,
                                  "no-estimate": True})).summary["face"]
    key = "root_stress_gear1_MPa"
    assert tilted[key] == pytest.approx(face["worst"][key]["value"], rel=1e-12)
    assert tilted["K_Hbeta"] == face["K_Hbeta"] and "K_Hbeta" not in flat
    assert crowned[key] < tilted[key] and tilted[key] > 1.1 * flat[key]
    assert "crowning" in VARIABLES
    out = tmp_path / "search"
    assert main(["optimize", "--misalignment", "-30", "--trials", "1", "--out",
                 str(out)]) == 2     # a face that jams: refused by name before any trial
    assert "--misalignment = -30.0" in capsys.readouterr().err and not out.exists()

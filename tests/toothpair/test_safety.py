"""Safety factors: allowable / stress for every tooth, the pair's the smallest over its teeth,
the tip round's pressure not hidden behind the flank's, new allowables changing the factors
and nothing else."""

import json
import math
from dataclasses import replace

import pytest

from fegear.cli import main
from fegear.errors import ParameterError
from fegear.toothpair import (
    SAFETY,
    TOOTH_SAFETY,
    Allowables,
    cycle_rows,
    cycle_summary,
    cycle_table,
    pair_summary,
    pair_table,
    prepare_job,
    solve_positions,
    with_safety,
)


@pytest.fixture(scope="module")
def cycle(baseline_ring):
    """The baseline at 200 N·m (coarse) at two rolling angles half a gear-2 pitch apart: its
    loaded tip rounds carry the peak pressure."""
    case = replace(baseline_ring.case, torque=200.0)
    return solve_positions(case, (0.0, math.pi / case.params.z2), model=baseline_ring)


@pytest.fixture(scope="module")
def summary(cycle):
    return pair_summary(cycle[0])


def test_defaults_are_42CrMo():
    a = Allowables()
    assert (a.bending, a.contact) == (558.0, 745.0)
    job = prepare_job({"quality": "coarse"})
    assert job.allowables == a
    assert prepare_job({"allowable-bending": 400.0}).allowables == Allowables(400.0, 745.0)


def test_every_tooth_has_allowable_over_its_stress(summary):
    assert summary["inputs"]["allowable_bending_MPa"] == 558.0
    assert summary["inputs"]["allowable_contact_MPa"] == 745.0
    loaded = [t for t in summary["teeth"] if t["load_N"] > 0]
    assert len(loaded) >= 2
    for t in summary["teeth"]:
        for gear in (1, 2):
            root, factor = t[f"root_stress_gear{gear}_MPa"], t[f"safety_bending_gear{gear}"]
            if t["load_N"] > 0:
                assert root > 0
            # a fillet outside the computed sectors of an open tooth reads 0: no factor
            assert factor == (pytest.approx(558.0 / root) if root > 0 else None)
        if t["load_N"] > 0:
            assert t["safety_contact"] == pytest.approx(745.0 / t["p_max_MPa"])
            assert t["safety_contact_flank"] == pytest.approx(745.0 / t["flank_pressure_MPa"])
        else:
            assert t["safety_contact"] is None  # no contact, no limit
    # the pair's factors divide its headline stresses, the largest over the teeth: they are
    # the smallest over the teeth
    for key, (which, stress) in SAFETY.items():
        allowable = 558.0 if which == "bending" else 745.0
        assert summary[key] == pytest.approx(allowable / summary[stress])
        values = [t[key] for t in loaded if t[key] is not None]
        assert summary[key] == pytest.approx(min(values), rel=1e-12), key


def test_the_tip_round_sets_the_contact_factor(summary):
    # the peak sits on a tip round (1900 MPa at coarse, 3× the flank's): S_H is the round's,
    # S_H flank the flank's own
    assert summary["contact_peak_on_tip_round"]
    edge = summary["edge_contact"]["max_pressure_MPa"]
    assert summary["safety_contact"] == pytest.approx(745.0 / edge)
    assert summary["safety_contact"] < 0.5 < 1.0 < summary["safety_contact_flank"]
    text = pair_table(summary)
    assert (f"| S_H (p_max)             | {summary['safety_contact']:5.2f} |           745 | "
            f"{summary['contact_pressure_MPa']:9.1f}e |") in text
    assert "S_H below 1: the stress exceeds the allowable" in text
    assert "e: the peak pressure, and so S_H, sits on a tip round" in text


def test_other_allowables_change_the_factors_and_nothing_else(cycle, summary):
    other = pair_summary(cycle[0], allowables=Allowables(400.0, 1000.0))
    assert other["safety_bending_gear1"] == pytest.approx(
        summary["safety_bending_gear1"] * 400.0 / 558.0)
    assert other["safety_contact"] == pytest.approx(summary["safety_contact"] * 1000.0 / 745.0)
    assert other["inputs"]["allowable_contact_MPa"] == 1000.0

    def stresses(s):
        keys = set(SAFETY) | set(TOOTH_SAFETY)
        return ({k: v for k, v in s.items() if k not in keys | {"inputs", "teeth", "wall_s"}},
                [{k: v for k, v in t.items() if k not in keys} for t in s["teeth"]])

    assert stresses(other) == stresses(summary)
    # a summary's factors recomputed from its stresses (what a study table does) are the
    # ones the solve gave at those allowables
    assert with_safety(summary, Allowables(400.0, 1000.0)) == other


def test_a_cycle_gives_each_position_its_factors_and_the_smallest(cycle):
    rows = cycle_rows(cycle, Allowables(500.0, 700.0))
    for r in rows:
        assert r["safety_bending_gear1"] == pytest.approx(500.0 / r["root_stress_gear1_MPa"])
        assert r["safety_contact"] == pytest.approx(700.0 / r["contact_pressure_MPa"])
    extremes = cycle_summary(rows)
    for key in SAFETY:
        worst = min(rows, key=lambda r, k=key: r[k])
        assert extremes[key] == {"min": worst[key], "at_position_deg": worst["position_deg"]}
    assert "smallest safety factors over the cycle: S_F gear 1 " in cycle_table(rows)
    # and recomputed from a summary's cycle block at other allowables
    block = {"cycle": {"positions": 2, **cycle_summary(cycle_rows(cycle)),
                       "rows": cycle_rows(cycle)}}
    again = with_safety(block, Allowables(500.0, 700.0))["cycle"]
    assert again["rows"] == rows
    assert all(again[k] == extremes[k] for k in SAFETY)


@pytest.mark.parametrize("field, value", [("bending", 0.0), ("bending", -558.0),
                                          ("contact", float("nan")), ("contact", 1e300)])
def test_bad_allowable_names_it(field, value):
    with pytest.raises(ParameterError) as err:
        Allowables(**{field: value})
    assert err.value.name == f"allowable-{field}"


def test_solve_takes_the_allowables_from_the_command_line(tmp_path, capsys):
    argv = ["solve", "--z2", "25", "--z1", "24", "--shift", "0.016", "--rotation", "0.002",
            "--torque", "20", "--quality", "coarse", "--no-estimate", "--json",
            "--allowable-bending", "300", "--allowable-contact", "1500",
            "--out", str(tmp_path)]
    assert main(argv) == 0
    s = json.loads(capsys.readouterr().out)
    assert s["safety_bending_gear1"] == pytest.approx(300.0 / s["root_stress_gear1_MPa"])
    assert s["safety_contact"] == pytest.approx(1500.0 / s["contact_pressure_MPa"])
    written = json.loads((tmp_path / "summary.json").read_text())
    assert written["safety_bending_gear2"] == s["safety_bending_gear2"]
    assert written["inputs"]["allowable_bending_MPa"] == 300.0


def test_a_cycle_table_marks_the_von_mises_estimates(cycle):
    # positions away from the cycle's peaks give the surface estimate of von Mises: the table
    # says which, and what that means
    rows = [dict(r) for r in cycle_rows(cycle)]
    rows[0]["von_mises_estimated"], rows[-1]["von_mises_estimated"] = True, False
    lines = cycle_table(rows).splitlines()
    first, last = lines[2], lines[1 + len(rows)]
    assert f"| {'~' + format(rows[0]['von_mises_max_MPa'], '.0f'):>6} |" in first
    assert f"| {rows[-1]['von_mises_max_MPa']:6.0f} |" in last and "~" not in last
    assert any(line.startswith("~ von Mises from the surface estimate") for line in lines)
    assert not any(line.startswith("~") for line in cycle_table(
        [{**r, "von_mises_estimated": False} for r in rows]).splitlines())


@pytest.mark.parametrize("s, cell", [(0.4, "0.40"), (1.954, "1.95"), (9.996, "10.0"),
                                     (43.45, "43.5"), (151.95, "152"), (999.4, "999"),
                                     (999.6, ">999"), (16381.83, ">999"), (None, "-")])
def test_a_safety_factor_takes_at_most_four_characters(s, cell):
    from fegear.toothpair.present.tables import factor_cell

    assert factor_cell(s) == cell


def _columns(table: str) -> set[tuple[int, ...]]:
    """The positions of the column bars of each table line (one set member: aligned)."""
    return {tuple(i for i, c in enumerate(line) if c == "|")
            for line in table.splitlines() if line.startswith("|")}


def test_the_solve_tables_keep_their_columns_aligned_for_any_value(cycle, summary):
    """A lightly loaded tooth's S of 16381.83 or 151.95, a stress past 10000 MPa, stiffnesses
    of 5.5e5 and 5.676e5: every line of each table has its bars where its header has them,
    and the stiffness is written in one format."""
    teeth = [dict(t) for t in summary["teeth"]]
    loaded = [t for t in teeth if t["load_N"] > 0]
    loaded[0].update(safety_bending_gear1=151.95, safety_bending_gear2=16381.83)
    loaded[-1].update(p_max_MPa=12345.6, safety_contact=0.06)
    wild = {**summary, "teeth": teeth, "safety_bending_gear2": 16381.83,
            "contact_pressure_MPa": 12345.6}
    table = pair_table(wild)
    for block in table.split("\n\n"):
        if block.startswith("|"):
            assert len(_columns(block)) == 1, block
    assert ">999" in table and "152" in table
    rows = [dict(r) for r in cycle_rows(cycle)]
    rows[0].update(mesh_stiffness_Nm_per_rad=5.5e5, safety_bending_gear2=16381.83,
                   contact_pressure_MPa=12345.6)
    rows[1].update(mesh_stiffness_Nm_per_rad=5.676e5, safety_bending_gear1=151.95)
    table = cycle_table(rows)
    assert len(_columns(table.split("\n\n")[0])) == 1
    assert "| 5.500e+05 |" in table and "| 5.676e+05 |" in table

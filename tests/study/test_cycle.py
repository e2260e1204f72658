"""A study with ``positions``: the cycle's largest stresses and smallest safety factors as
named columns, the factors at the allowables the file gives now (from the stored stresses of
every position), the markdown table and the plots' data."""

from __future__ import annotations

import json
import shutil

import pytest

from fegear.study import load_results, load_study
from fegear.study.plot import study_png
from fegear.study.results import markdown, rows, study_plot, write_results
from fegear.toothpair import HEADLINE

# three cheap cycles (the 25/24 pair at coarse, no second level, 2 positions; one model:
# only the torque and the position change): 10 and 20 N·m from β0 = 0, 20 N·m from β0 = 2°
CYCLE = """
[study]
name = "cycle"
[base]
quality = "coarse"
z2 = 25
z1 = 24
shift = 0.016
rotation = 0.002
no-estimate = true
positions = 2
torque = 20
[[sweep]]
torque = [10, 20]
[[sweep]]
position = [0, 2]
"""
#: each safety factor's allowable (the defaults, 42CrMo) and the stress it divides
FACTORS = {"safety_bending_gear1": ("allowable-bending", "root_stress_gear1_MPa"),
           "safety_bending_gear2": ("allowable-bending", "root_stress_gear2_MPa"),
           "safety_contact": ("allowable-contact", "contact_pressure_MPa")}


@pytest.fixture(scope="module")
def cycle_run(tmp_path_factory):
    """The three cycles solved into a study directory (about 10 s)."""
    from fegear.study.runner import run_study

    tmp = tmp_path_factory.mktemp("cycle")
    (tmp / "cycle.toml").write_text(CYCLE)
    study = load_study(tmp / "cycle.toml")
    report = run_study(study, tmp / "out", workers=1, progress=False)
    assert (report.computed, report.failed) == (3, 0)
    return {"study": study, "out": tmp / "out"}


def test_the_cycle_s_worst_are_columns_with_their_position(cycle_run):
    df = load_results(cycle_run["out"])
    assert list(df["status"]) == ["ok"] * 3 and list(df["cycle.positions"]) == [2] * 3
    for _, r in df.iterrows():
        cycle = json.loads(r["cycle.rows"])
        assert len(cycle) == 2 and cycle[0]["position_deg"] == pytest.approx(r["position"])
        for k in HEADLINE:
            worst = max(cycle, key=lambda p, k=k: p[k])
            assert r[f"cycle.{k}.max"] == worst[k], k
            assert r[f"cycle.{k}.at_position_deg"] == worst["position_deg"], k
            assert worst[k] >= cycle[0][k]
        for k, (allowable, stress) in FACTORS.items():
            assert r[f"cycle.{k}.min"] == pytest.approx(
                r[allowable] / r[f"cycle.{stress}.max"], rel=1e-12), k
            assert r[f"cycle.{k}.at_position_deg"] == r[f"cycle.{stress}.at_position_deg"]
        # the summary's own columns are at the position of the largest gear-1 root stress
        assert r["root_stress_gear1_MPa"] == r["cycle.root_stress_gear1_MPa.max"]
        assert r["inputs.position_deg"] == r["cycle.root_stress_gear1_MPa.at_position_deg"]
    # the trend a coarse run must show: the cycle's root stresses about double with the torque
    low, high = df.iloc[0], df.iloc[1]
    for k in ("root_stress_gear1_MPa", "root_stress_gear2_MPa"):
        assert high[f"cycle.{k}.max"] / low[f"cycle.{k}.max"] == pytest.approx(2.0, rel=0.1)
    # 10 N·m: 40.0 MPa at β0 = 0 with two teeth in contact (as in test_study.py), half a
    # pitch (7.2°) on one tooth carries it all: 50 % more
    assert json.loads(low["cycle.rows"])[0]["root_stress_gear1_MPa"] == pytest.approx(
        40.0, abs=0.5)
    assert low["cycle.root_stress_gear1_MPa.max"] == pytest.approx(60.4, abs=0.6)
    assert low["cycle.root_stress_gear1_MPa.at_position_deg"] == pytest.approx(7.2)


def test_the_table_shows_the_cycle_s_worst_beside_its_first_position(cycle_run):
    md = (cycle_run["out"] / "results.md").read_text()
    head, _, first = md.splitlines()[:3]
    cols = [c.strip() for c in head.strip("|").split("|")]
    cells = dict(zip(cols, (c.strip() for c in first.strip("|").split("|"))))
    for name in ("σ1 g1 cycle", "p_max cycle", "vM max cycle", "S_F1 cycle", "S_F2 cycle",
                 "S_H cycle"):
        assert name in cols, name
    r = load_results(cycle_run["out"]).iloc[0]
    start = json.loads(r["cycle.rows"])[0]
    assert cells["σ1 g1"] == f"{start['root_stress_gear1_MPa']:.1f}"
    assert cells["S_H"] == f"{start['safety_contact']:.2f}"
    assert cells["σ1 g1 cycle"] == (f"{r['cycle.root_stress_gear1_MPa.max']:.1f} "
                                    f"({r['cycle.root_stress_gear1_MPa.at_position_deg']:.3g}°)")
    assert cells["S_H cycle"].startswith(f"{r['cycle.safety_contact.min']:.2f} (")
    assert "first position β0" in md


def test_the_cycle_s_factors_follow_the_file_s_allowables_not_the_record(cycle_run, tmp_path):
    """Other allowables in the file and every stored factor spoilt: the table, rebuilt
    without a solve, divides the allowables of the file by each position's stored stresses."""
    out = tmp_path / "out"
    shutil.copytree(cycle_run["out"], out)
    for path in (out / "cases").glob("*.json"):
        rec = json.loads(path.read_text())
        cycle = rec["summary"]["cycle"]
        for k in FACTORS:
            cycle[k]["min"] = 99.0
            for p in cycle["rows"]:
                p[k] = 99.0
        path.write_text(json.dumps(rec))
    text = CYCLE.replace("[base]", "[base]\nallowable-bending = 400\nallowable-contact = 1000")
    (tmp_path / "cycle.toml").write_text(text)
    study = load_study(tmp_path / "cycle.toml")
    assert [c.key for c in study.cases] == [c.key for c in cycle_run["study"].cases]
    write_results(study, out)
    before, after = load_results(cycle_run["out"]), load_results(out)
    for (_, old), (_, new) in zip(before.iterrows(), after.iterrows()):
        assert new["cycle.root_stress_gear1_MPa.max"] == old["cycle.root_stress_gear1_MPa.max"]
        for k, (allowable, stress) in FACTORS.items():
            assert new[f"cycle.{k}.min"] == pytest.approx(
                new[allowable] / new[f"cycle.{stress}.max"], rel=1e-12), k
            assert new[f"cycle.{k}.min"] / old[f"cycle.{k}.min"] == pytest.approx(
                new[allowable] / old[allowable], rel=1e-12), k
        for p in json.loads(new["cycle.rows"]):
            assert p["safety_bending_gear1"] == pytest.approx(400.0 / p["root_stress_gear1_MPa"])
    assert (after["allowable-bending"] == 400.0).all()
    r = after.iloc[0]
    assert f"| {r['cycle.safety_contact.min']:.2f} (" in (out / "results.md").read_text()


def test_the_plots_show_the_cycle_s_worst_its_factors_and_the_torque(cycle_run, tmp_path):
    study = cycle_run["study"]
    table = rows(study, cycle_run["out"])
    plot = study_plot(study, table, "position")
    assert plot.title.splitlines()[1].startswith("T = 20 N·m; σ_FP 558 MPa, σ_HP 745 MPa")
    assert plot.positions == (2,) and plot.allowables == (558.0, 745.0)
    assert plot.x_label == "position [deg]"
    [line] = plot.lines   # 20 N·m: β0 0 and 2°; 10 N·m has one position alone, no line
    assert line.x == (0.0, 2.0) and line.label == "torque 20 N·m"
    cases = [r for r in table if r["torque"] == 20.0]
    for k in HEADLINE:
        assert line.stress[k] == tuple(r[f"cycle.{k}.max"] for r in cases)
        assert line.start[k] == tuple(json.loads(r["cycle.rows"])[0][k] for r in cases)
        assert line.error[k] == (0.0, 0.0)   # no estimate
    for k in FACTORS:
        assert line.safety[k] == tuple(r[f"cycle.{k}.min"] for r in cases)
    assert line.edge_N == tuple(max(p["edge_load_N"] for p in json.loads(r["cycle.rows"]))
                                for r in cases)
    by_torque = study_plot(study, table, "torque")
    assert by_torque.torque is None and "T =" not in by_torque.title   # T is the axis
    assert by_torque.lines[0].x == (10.0, 20.0)
    # cases that differ in an allowable: no single S to draw, and none is stated
    mixed = [dict(r, **{"allowable-bending": 300.0}) if r["case"] == 0 else r for r in table]
    assert study_plot(study, mixed, "torque").allowables is None
    assert "σ_FP" not in study_plot(study, mixed, "torque").title
    png = study_png(tmp_path / "position.png", plot, {k: k for k in HEADLINE})
    assert png.stat().st_size > 10_000


def test_a_table_without_cycles_has_no_cycle_columns(cycle_run):
    table = [{k: v for k, v in r.items() if not k.startswith("cycle.")}
             for r in rows(cycle_run["study"], cycle_run["out"])]
    head = markdown(cycle_run["study"], table).splitlines()[0]
    assert "cycle" not in head and "S_H" in head
    plot = study_plot(cycle_run["study"], table, "torque")
    assert plot.positions == () and plot.lines[0].start is None
    assert plot.lines[0].stress["root_stress_gear1_MPa"] == tuple(
        r["root_stress_gear1_MPa"] for r in table if r["position"] == 0.0)

"""The benchmark's arithmetic: Richardson references, errors, targets; one tiny ladder end to
end (the benchmark itself times things; no test does)."""

import json
import math

import pytest

from fegear.verify.bench import (
    Ladder,
    Rung,
    disk_ladder,
    ladder_json,
    ladder_table,
    ladder_targets,
    richardson,
)
from fegear.verify.plot import Series, ladder_png


@pytest.mark.parametrize("order", [1.0, 2.0, 3.5])
def test_richardson_recovers_the_limit_of_a_power_law(order):
    h = [1.0, 0.5, 0.25, 0.125]
    limit, p = richardson([7.0 + 3.0 * x**order for x in h])
    assert p == pytest.approx(order, rel=1e-12)
    assert limit == pytest.approx(7.0, rel=1e-12)


def test_richardson_falls_back_to_order_2_when_changes_do_not_shrink():
    # oscillating, or stalled: the last two levels with P2's nominal order 2
    for values in ([1.0, 1.2, 1.1], [1.0, 1.1, 1.2], [1.0, 1.01]):
        limit, p = richardson(values)
        assert p == 2.0
        assert limit == pytest.approx(values[-1] + (values[-1] - values[-2]) / 3.0)
    with pytest.raises(ValueError):
        richardson([1.0])


def _rung(level, seconds, value):
    return Rung(level, 10, {"mesh": 0.5 * seconds, "contact": 0.5 * seconds}, {"p": value})


def test_targets_take_the_cheapest_level_within_the_error():
    # p = 100 + 15 h²: reference 100; errors 15, 3.75, 0.94, 0.23 %
    ladder = Ladder("case", tuple(_rung(f"L{k}", 0.1 * 4**k, 100 + 15 / 4**k)
                                  for k in range(4)))
    assert ladder.reference["p"] == pytest.approx(100.0)
    assert ladder.error_pct(ladder.rungs[2].values) == pytest.approx(0.9375)
    (hertz,) = ladder_targets(ladder)
    assert hertz.rung.level == "L3" and not hertz.met     # 0.5 %: only L3, 6.4 s > 0.3 s
    assert ladder.rungs[2].solve_s == pytest.approx(0.8)  # meshing left out
    fast = Ladder("case", tuple(_rung(f"L{k}", 0.01 * 2**k, 100 + 4 / 4**k)
                                for k in range(4)))
    assert ladder_targets(fast)[0].met                    # 0.5 %: L2 (0.25 %) in 0.04 s


def test_tiny_disk_ladder_writes_table_json_and_png(tmp_path):
    ladder = disk_ladder((4, 8), repeat=1, peer=False)
    assert [r.level for r in ladder.rungs] == ["4 per b", "8 per b"]
    assert ladder.order["p_max_MPa"] == 2.0
    # the reference lies near Hertz (the FE converges to it within 0.3 %)
    assert ladder.reference["p_max_MPa"] == pytest.approx(ladder.analytic["p_max_MPa"],
                                                           rel=0.01)
    table = ladder_table(ladder)
    assert table.count("\n| 4 per b |") == 1 and "reference: p_max_MPa" in table
    targets = ladder_targets(ladder)
    data = json.loads(json.dumps(ladder_json([ladder], targets)))
    assert data["machine"]["libraries"]["scikit-fem"]
    assert data["ladders"][0]["rungs"][1]["error_pct"] >= 0
    assert all(math.isfinite(v) for v in data["ladders"][0]["rungs"][0]["timings_s"].values())
    series = [Series("disks", [(r.total_s, ladder.error_pct(r.values), r.level)
                               for r in ladder.rungs], target=(0.5, 0.3))]
    png = ladder_png(tmp_path / "bench.png", series)
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_a_failed_calculix_run_is_reported_and_the_ladder_goes_on(monkeypatch):
    # `fegear bench --torque 1` stopped at the `fast` pair: ccx refused a mesh, and the
    # finished disk ladder was never written
    import fegear.verify.calculix as peer
    from fegear.verify.ccx_files import PeerError

    def refuse(case, workdir, **kwargs):
        raise PeerError("body 'disk1': node 4 is not on edge 1-2")

    monkeypatch.setattr(peer, "ccx_available", lambda: True)
    monkeypatch.setattr(peer, "ccx_disks", refuse)
    ladder = disk_ladder((4, 8), repeat=1, peer=True)
    assert [r.peer_failure for r in ladder.rungs] == ["body 'disk1': node 4 is not on edge 1-2"] * 2
    assert all(r.peer_s is None for r in ladder.rungs)
    table = ladder_table(ladder)
    assert "ccx failed at `4 per b`: body 'disk1'" in table
    row = next(line for line in table.splitlines() if line.startswith("| 4 per b |"))
    assert row.endswith("| – | – |")  # ccx time and ratio: none
    assert ladder_json([ladder], [])["ladders"][0]["rungs"][0]["peer_failure"]


def test_the_peer_is_compared_at_equal_error_on_the_stresses_it_gives():
    """CalculiX's root stresses against the references pick the cheapest ring level at no
    larger error; its contact value (a pointwise penalty pressure) is not compared."""
    from types import SimpleNamespace

    from fegear.verify import ring_bench as rb
    from fegear.verify.pair_targets import PairRuns, pair_targets

    ref = rb.SECTOR_REFERENCE

    def run(label, seconds, err_pct):
        values = {k: v * (1 + err_pct / 100) for k, v in ref.items()}
        return rb.RingRun(label, {"mesh": seconds}, seconds, 500.0, 1, 1, values, {})

    ring = [run("coarse", 2.0, 1.0), run("fast", 3.0, 0.4), run("standard", 5.0, 0.1)]
    peer = {k: v * 1.003 for k, v in ref.items()}
    peer["contact_pressure_MPa"] = 2.3 * ref["contact_pressure_MPa"]
    sector = SimpleNamespace(rungs=[SimpleNamespace(level="coarse", peer_s=100.0,
                                                    peer_values=peer)])
    lines = pair_targets(PairRuns(ring[1], ring[1], ring, sector=sector), 20.0)
    (line,) = [x for x in lines if x.startswith("* CalculiX")]
    assert "`standard` (0.10 %), 5.00 s: 20.0×" in line and line.endswith(": met")
    peer.update({k: v * 1.0001 for k, v in ref.items() if k.startswith("root")})
    lines = pair_targets(PairRuns(ring[1], ring[1], ring, sector=sector), 20.0)
    assert [x for x in lines if x.startswith("* CalculiX")][0].endswith("MISSED")


def test_the_model_cache_targets_judge_the_model_read_back_and_the_whole_command():
    from fegear.verify import ring_bench as rb
    from fegear.verify.pair_targets import PairRuns, pair_targets

    ref = dict(rb.SECTOR_REFERENCE, von_mises_max_MPa=rb.VON_MISES_RESOLVED)

    def run(label, seconds, err_pct):
        values = {k: v * (1 + err_pct / 100) for k, v in ref.items()}
        return rb.RingRun(label, {"mesh": seconds}, seconds, 500.0, 1, 1, values, {})

    built = run("standard", 2.0, 0.3)

    def lines(read_s, command_s):
        commands = {"without the cache": 3.9, "models read from the cache": command_s}
        cached = rb.CacheRuns(run("read", read_s, 0.3), run("read, estimate", 1.2, 0.3),
                              commands)
        out = pair_targets(PairRuns(built, built, [built], cached=cached), 20.0)
        return [x for x in out if "cache" in x]

    position, command = lines(0.75, 1.8)
    assert "0.75 s after import" in position and ": met; built: 2.00 s (2.0× the goal)" \
        in position
    assert command.endswith("MISSED built, met read back")
    position, command = lines(1.05, 2.1)
    assert "MISSED; built" in position and command.endswith("MISSED built, MISSED read back")


def test_each_run_is_kept_and_the_last_one_printed_beside_the_next(tmp_path):
    """The history: a folder with only an old bench.json gives that run's numbers; each run
    appends a line; the next run's table puts the last line's numbers beside its own."""
    import json

    from fegear.verify import history

    def record(one, cycle):
        run = {"label": "standard", "timings_s": {"mesh": 0.3, "cache": 0.0}, "total_s": one,
               "peak_mb": 460.0, "extra": {"output_s": 1.0}}
        return {"ladders": [{"name": "disks", "rungs": [{"level": "4 per b", "total_s": 0.15}]}],
                "ring": {"ring": [run], "default": run, "extras": None,
                         "cycle": {"label": "standard, 24-position cycle",
                                   "extra": {"cycle_s": cycle}}}}

    kept = tmp_path / history.HISTORY
    assert history.last_run(kept) is None
    (tmp_path / "bench.json").write_text(json.dumps(record(2.0, 8.0)))
    old = history.last_run(kept)
    assert old["metrics"]["cycle / one position [×]"] == 4.0
    assert "ring `standard`, cache [s]" not in old["metrics"]          # a stage not run
    history.remember(kept, history.bench_metrics(record(1.0, 3.0)), "0.1.0+abc; numpy 2",
                     {"cpus": 2})
    last = history.last_run(kept)
    assert last["code"].startswith("0.1.0+abc") and last["metrics"]["cycle / one position [×]"] \
        == 3.0
    now = history.bench_metrics(record(0.5, 1.0))
    now["a number the last run did not measure [s]"] = 1.0
    table = history.beside_table(last, now)
    assert "| ring `standard`, one position [s] | 1 | 0.5 | 0.50 |" in table
    assert "| cycle / one position [×] | 3 | 2 | 0.67 |" in table
    assert "| a number the last run did not measure [s] | – | 1 | – |" in table
    assert len(kept.read_text().splitlines()) == 1
    # the history printed as a table: a column a run, a row a number
    history.remember(kept, now, "0.1.0+def; numpy 2", {"cpus": 2})
    shown = history.history_table(history.runs(kept))
    assert shown.splitlines()[0].count("0.1.0+") == 2
    assert "| cycle / one position [×] | 3 | 2 |" in shown
    assert "| a number the last run did not measure [s] | – | 1 |" in shown


def test_show_history_prints_the_history_as_a_table(tmp_path, capsys):
    """``fegear bench --show-history``: the kept runs as a table, a column a run (the last
    eight), their notes beneath the dates, nothing run; none kept, one line saying so. The
    repository's history ends with a bench run, so that the next ``make bench`` is printed
    beside a run of its own kind; its ``--against`` lines (two a run: the other checkout's,
    with its commit as the code, and this one's) sit among the day's runs."""
    from pathlib import Path

    from fegear.cli import main
    from fegear.verify import history

    repository = Path(__file__).parents[2] / "docs" / "bench" / "history.jsonl"
    assert main(["bench", "--show-history", "--history", str(repository)]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].count("|") == min(len(history.runs(repository)), 8) + 2
    assert history.runs(repository)[-1]["code"].startswith("0.1.0+")
    against = [line for line in repository.read_text().splitlines() if "--against" in line]
    assert len(against) >= 12 and len(against) % 2 == 0
    kept = tmp_path / "history.jsonl"
    kept.write_text("\n".join(against[-2:]) + "\n")
    assert main(["bench", "--show-history", "--history", str(kept)]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].count("|") == 4 and lines[2].startswith("| note | ")
    assert lines[2].count("--against") == 2
    assert any(line.startswith("| one position: fegear solve --no-estimate [s] |")
               for line in lines)
    assert main(["bench", "--show-history", "--history", str(tmp_path / "none.jsonl")]) == 0
    assert capsys.readouterr().out.strip() == "(no bench run kept there yet)"


def test_commands_are_timed_here_and_in_another_checkout_alternately(tmp_path):
    """``fegear bench --against``: each command here and there, as many times each, the
    ratio of the medians; a checkout without its fegear, or a command failing there, is one
    line naming it."""
    import stat

    from fegear.errors import FegearError
    from fegear.verify.against import against_table, checkout, time_against

    fake = tmp_path / ".venv" / "bin" / "fegear"
    fake.parent.mkdir(parents=True)
    fake.write_text("#!/bin/sh\necho \"$@\" >> \"$0.log\"\n")
    fake.chmod(fake.stat().st_mode | stat.S_IEXEC)
    rows = time_against(checkout(tmp_path), 3, commands=(("version", ("--version",)),))
    (row,) = rows
    assert len(row.here) == len(row.there) == 3 and row.ratio > 0
    assert (tmp_path / ".venv/bin/fegear.log").read_text().splitlines() == ["-q --version"] * 3
    assert "| version |" in against_table(rows, tmp_path)
    with pytest.raises(FegearError, match="no fegear checkout"):
        checkout(tmp_path / "nowhere")
    # a command the other checkout does not have is a line saying so; the others still run
    fake.write_text("#!/bin/sh\ncase \"$*\" in *--help*) exit 0;; esac\necho broken >&2\n"
                    "exit 1\n")
    rows = time_against(checkout(tmp_path), 2, commands=(("version", ("--version",)),
                                                         ("help", ("--help",))))
    assert rows[0].there == () and "`fegear --version` failed in" in rows[0].failed_there
    assert len(rows[0].here) >= 1 and rows[0].ratio != rows[0].ratio   # NaN
    assert len(rows[1].there) == 2 and not rows[1].failed_there
    assert "| version |" in against_table(rows, tmp_path) and "failed there" in against_table(
        rows, tmp_path)


def test_a_tolerance_class_is_judged_by_its_whole_command_with_what_its_pairs_came_to():
    from fegear.verify import ring_bench as rb
    from fegear.verify.pair_targets import PairRuns, pair_targets

    ref = dict(rb.SECTOR_REFERENCE, von_mises_max_MPa=rb.VON_MISES_RESOLVED)
    one = rb.RingRun("standard", {"mesh": 1.0}, 1.0, 500.0, 1, 1, ref, {})
    counts = {"solved": 161, "jammed": 839, "failed": 0}

    def line(seconds):
        out = pair_targets(PairRuns(one, one, [one], tolerance=(seconds, counts)), 20.0)
        return next(x for x in out if "--grade 6" in x)

    assert line(19.6).endswith("161 pairs solved at every position, 839 jammed, 0 failed "
                               "(target <= 20 s): met")
    assert line(20.4).endswith("MISSED")


def test_whole_revolutions_are_judged_by_their_seconds_with_their_multiple_of_one_position():
    from fegear.verify import ring_bench as rb
    from fegear.verify.history import bench_metrics
    from fegear.verify.pair_targets import PairRuns, pair_targets

    ref = dict(rb.SECTOR_REFERENCE, von_mises_max_MPa=rb.VON_MISES_RESOLVED)
    one = rb.RingRun("standard", {"mesh": 1.0}, 1.0, 500.0, 1, 1, ref, {})

    def lines(pair, every):
        run = {"solve_s": 2.0, "pair_s": pair, "class_s": every,
               "positions_solved_per_pair": 234.4}
        out = pair_targets(PairRuns(one, one, [one], revolution=run), 20.0)
        return [x for x in out if "--revolution" in x]

    pair, every = lines(4.9, 59.0)
    assert pair.startswith("* `fegear solve --revolution --pitch-deviation 1:11=5")
    assert pair.endswith("4.9 s, 2.5× one position's 2.00 s (target <= 5 s): met")
    assert "--samples 200" in every and "--shift 0.03" in every
    assert every.endswith("59.0 s, 30× one position, 234 positions solved a pair "
                          "(target <= 60 s): met")
    assert [x.endswith("MISSED") for x in lines(5.1, 61.0)] == [True, True]
    assert [x.endswith("met") for x in lines(4.0, 61.0)] == [True, False]
    got = bench_metrics({"ring": {"revolution": {"solve_s": 2.0, "pair_s": 8.0,
                                                 "class_s": 120.0}}})
    assert got["one deviated pair's revolution [s]"] == 8.0
    assert got["200 class-5 pairs over a revolution [s]"] == 120.0


def test_the_design_search_over_a_turn_is_judged_by_its_seconds_with_what_it_found():
    from fegear.verify import ring_bench as rb
    from fegear.verify.history import bench_metrics
    from fegear.verify.pair_targets import PairRuns, pair_targets

    ref = dict(rb.SECTOR_REFERENCE, von_mises_max_MPa=rb.VON_MISES_RESOLVED)
    one = rb.RingRun("standard", {"mesh": 1.0}, 1.0, 500.0, 1, 1, ref, {})

    def line(seconds, best):
        run = {"seconds": seconds, "trials": 200, "feasible": 1, "best_trial": best}
        out = pair_targets(PairRuns(one, one, [one], search=run), 20.0)
        return [x for x in out if "fegear optimize" in x]

    [met] = line(350.0, 6)
    assert "--trials 200" in met and "--samples 50" in met and "--revolution" in met
    assert met.endswith("350 s, 200 trials, 1 feasible, best trial 6 (target <= 1800 s): met")
    [missed] = line(1801.0, None)
    assert missed.endswith("best none (target <= 1800 s): MISSED")
    got = bench_metrics({"ring": {"search": {"seconds": 350.0}}})
    assert got["design search over a turn, 200 trials of 50 pairs [s]"] == 350.0


def test_a_spectrum_is_judged_against_its_cycle_alone():
    from fegear.verify import ring_bench as rb
    from fegear.verify.history import bench_metrics
    from fegear.verify.pair_targets import PairRuns, pair_targets

    ref = dict(rb.SECTOR_REFERENCE, von_mises_max_MPa=rb.VON_MISES_RESOLVED)
    one = rb.RingRun("standard", {"mesh": 1.0}, 1.0, 500.0, 1, 1, ref, {})

    def line(alone, rated):
        out = pair_targets(PairRuns(one, one, [one], spectrum=(alone, rated)), 20.0)
        return next(x for x in out if "--spectrum" in x)

    assert line(2.5, 4.9).endswith("1.96× (target <= 2×): met")
    assert line(2.5, 5.1).endswith("MISSED")
    got = bench_metrics({"ring": {"spectrum": {"cycle_s": 2.0, "spectrum_s": 3.0}}})
    assert got["4-level spectrum / its cycle, whole commands [×]"] == 1.5


def test_the_face_is_judged_against_the_2d_pair():
    from fegear.verify import ring_bench as rb
    from fegear.verify.history import bench_metrics
    from fegear.verify.pair_targets import PairRuns, pair_targets

    ref = dict(rb.SECTOR_REFERENCE, von_mises_max_MPa=rb.VON_MISES_RESOLVED)
    one = rb.RingRun("standard", {"mesh": 1.0}, 1.0, 500.0, 1, 1, ref, {})
    runs = PairRuns(one, one, [one], face={"one position": (2.0, 3.9),
                                           "24 positions": (3.0, 9.3)})
    lines = [x for x in pair_targets(runs, 20.0) if "across the face" in x]
    assert lines[0].startswith("* one position across the face")
    assert lines[0].endswith("1.95× (target <= 2×): met")
    assert lines[1].endswith("3.10× (target <= 3×): MISSED")
    got = bench_metrics({"ring": {"face": {"one position": {"flat_s": 2.0, "face_s": 3.0}}}})
    assert got["across the face / 2D, one position, whole commands [×]"] == 1.5

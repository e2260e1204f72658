"""`fegear bench`'s row for the files of `fegear solve --out`: whole commands without and with
the files, alternated in pairs, judged by the median of the pairs' differences."""

from pathlib import Path

import pytest

from fegear.verify.bench import FILES_TARGET_S, FilesRun, files_run


def test_the_files_cost_the_median_of_the_pairs_differences():
    run = FilesRun(("--quality", "standard"), (1.6, 1.7, 2.4), (2.0, 2.3, 2.8))
    assert run.costs == pytest.approx([0.4, 0.6, 0.4])
    assert run.cost_s == pytest.approx(0.4) and run.met
    line = run.lines()[-1]
    assert line.endswith(f"0.40 s over the solve (median of 3 pairs, 0.40-0.60 s) (target <= "
                         f"{FILES_TARGET_S:g} s): met")
    table = "\n".join(run.lines())
    assert "`fegear solve --quality standard`, 3 alternated pairs" in table
    assert "| without `--out` | 1.70 | 1.60-2.40 |" in table
    slow = FilesRun((), (1.6, 1.6), (2.2, 2.4))
    assert not slow.met and slow.lines()[-1].endswith("MISSED")


def test_the_commands_alternate_and_every_other_one_writes_its_files(monkeypatch):
    from fegear.verify import ring_bench

    ran = []

    def command_s(args, env):
        ran.append(list(args))
        assert env == {"FEGEAR_CACHE": "off"}       # a first solve: the model built
        if "--out" in args:
            out = args[args.index("--out") + 1]
            Path(out).mkdir()
            return 3.0
        return 2.0

    monkeypatch.setattr(ring_bench, "command_s", command_s)
    run = files_run(["--torque", "200"], 3)
    assert [("--out" in a) for a in ran] == [False, True, True, False, False, True]
    assert all(a[:2] == ["--torque", "200"] for a in ran)
    outs = [a[a.index("--out") + 1] for a in ran if "--out" in a]
    assert len(set(outs)) == 3                      # a fresh folder each time
    assert not any(Path(o).exists() for o in outs)   # removed after
    assert run.without == (2.0, 2.0, 2.0) and run.written == (3.0, 3.0, 3.0)
    assert run.cost_s == 1.0


def test_bench_files_only_runs_the_files_row_alone(monkeypatch, tmp_path):
    from fegear.cli import main
    from fegear.verify import bench

    asked = []

    def fake(args, runs):
        asked.append((list(args), runs))
        return FilesRun(tuple(args), (1.5,) * runs, (1.9,) * runs)

    monkeypatch.setattr(bench, "files_run", fake)
    assert main(["bench", "--files-only", "--files", "2", "--out", str(tmp_path)]) == 0
    assert asked == [(["--torque", "200", "--quality", "standard"], 2)]

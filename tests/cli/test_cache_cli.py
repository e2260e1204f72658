"""``fegear cache`` and the solving commands' ``--cache``: the entry a cached solve keeps, the
listing, clearing, and a bad size cap refused in one line before anything is computed."""

import pytest

from fegear.cli import main
from fegear.toothpair.ring import cache
from fegear.toothpair.ring.model import KEPT

LIGHT = ["--z2", "25", "--z1", "24", "--torque", "20", "--quality", "coarse", "--no-estimate",
         "-q"]


@pytest.fixture
def folder(tmp_path, monkeypatch):
    monkeypatch.setenv(cache.ENV_DIR, str(tmp_path / "cache"))
    monkeypatch.delenv(cache.ENV, raising=False)
    KEPT.clear()
    yield tmp_path / "cache"
    KEPT.clear()


def test_solve_keeps_its_model_only_with_cache_and_the_command_lists_and_clears(folder,
                                                                                capsys):
    assert main(["solve", *LIGHT]) == 0
    assert cache.entries() == []                       # off by default for a one-off solve
    KEPT.clear()
    assert main(["solve", *LIGHT, "--cache"]) == 0
    (entry,) = cache.entries()
    capsys.readouterr()
    assert main(["cache"]) == 0
    listing = capsys.readouterr().out
    assert str(folder) in listing and entry[0].name in listing and "1 entries" in listing
    assert main(["cache", "--clear"]) == 0
    assert "removed 1 entries" in capsys.readouterr().out
    assert cache.entries() == []


def test_a_bad_cap_is_one_line_before_any_solve(folder, tmp_path, monkeypatch, capsys):
    monkeypatch.setenv(cache.ENV_CAP, "lots")
    out = tmp_path / "never-made"
    assert main(["solve", *LIGHT, "--cache", "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "FEGEAR_CACHE_GB = 'lots'" in err[0] and "above 0" in err[0]
    assert not out.exists() and not folder.exists()


def test_a_bad_cap_does_not_keep_the_cache_from_being_cleared(folder, monkeypatch, capsys):
    from fegear.toothpair.ring import cache

    cache.keep("an entry", {"x": 1})
    monkeypatch.setenv(cache.ENV_CAP, "lots")
    assert main(["cache", "--clear"]) == 0
    assert "removed 1 entries" in capsys.readouterr().out and cache.entries() == []
    assert main(["cache"]) == 2
    assert "FEGEAR_CACHE_GB = 'lots'" in capsys.readouterr().err


def test_the_help_states_the_cap_the_cache_holds():
    from fegear.cli import build_parser
    from fegear.cli.cache import CAP_TEXT

    assert CAP_TEXT == f"{cache.ENV_CAP} ({cache.CAP_GB:g} GB unless set)"
    for command in ("solve", "relief", "study"):
        parser = build_parser()
        help_text = " ".join(parser._subparsers._group_actions[0].choices[command]
                             .format_help().split())
        assert f"held under {CAP_TEXT}" in help_text and "220 MB" in help_text, command

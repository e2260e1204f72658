"""The examples are pinned by their values, as scikit-fem's tests/test_examples.py pins its
examples: every stage's walkthrough (the docstring of its ``__init__``), every Python example of the
README and every Python session (``>>>``) of docs/ run as doctests."""

import doctest
import importlib
import re
from pathlib import Path

import pytest

README = Path(__file__).parents[1] / "README.md"
STAGES = ("geometry", "tolerance", "fe", "contact", "toothpair", "toothpair.ring",
          "toothpair.analyses", "study",
          "verify",
          "verify.penalty", "verify.sector", "drive", "optimize", "cli", "api")
FLAGS = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE


def _run(test: doctest.DocTest) -> doctest.TestResults:
    runner = doctest.DocTestRunner(optionflags=FLAGS)
    runner.run(test)  # prints each failure: pytest shows it
    return runner.summarize(verbose=False)


@pytest.mark.parametrize("stage", STAGES)
def test_stage_walkthrough(stage):
    module = importlib.import_module(f"fegear.{stage}")
    tests = [t for t in doctest.DocTestFinder(recurse=False).find(module) if t.examples]
    assert tests, f"fegear.{stage} has no walkthrough"
    result = _run(tests[0])
    assert result.failed == 0
    assert result.attempted >= 3


BLOCKS = re.findall(r"```python\n(.*?)```", README.read_text(), flags=re.S)
#: the docs' Python examples written as sessions (``>>>``); the others show code to adapt
DOCS = [(path.name, block) for path in sorted((README.parent / "docs").glob("*.md"))
        for block in re.findall(r"```python\n(.*?)```", path.read_text(), flags=re.S)
        if block.lstrip().startswith(">>> ")]


def test_every_readme_python_example_is_pinned():
    assert BLOCKS
    for block in BLOCKS:
        assert block.lstrip().startswith(">>> "), block[:80]


@pytest.mark.parametrize("block", BLOCKS, ids=[f"block{i}" for i in range(len(BLOCKS))])
def test_readme_example(block):
    test = doctest.DocTestParser().get_doctest(block, {}, "README", str(README), 0)
    assert _run(test).failed == 0


def test_the_moved_examples_are_still_pinned():
    assert {name for name, _ in DOCS} >= {"geometry.md", "validation.md"}


@pytest.mark.parametrize("name, block", DOCS, ids=[f"{n}-{i}" for i, (n, _) in enumerate(DOCS)])
def test_docs_example(name, block):
    path = README.parent / "docs" / name
    test = doctest.DocTestParser().get_doctest(block, {}, name, str(path), 0)
    assert _run(test).failed == 0

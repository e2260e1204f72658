"""A study with ``[outputs] report = true``: each case's one-page report in its folder (its
pictures inside it, no PNG files kept beside), and the study's index page with a row a case,
its verdict and a link that finds the page."""

import re

from fegear.study import run_study
from fegear.study.file import Outputs, case_key, load_study

STUDY = """
[study]
name = "reported"
[outputs]
report = true
[base]
quality = "coarse"
z2 = 25
z1 = 24
no-estimate = true
positions = 2
[[sweep]]
torque = [10, 400]
"""


def test_each_case_has_its_page_and_the_index_finds_them(tmp_path):
    (tmp_path / "s.toml").write_text(STUDY)
    study = load_study(tmp_path / "s.toml")
    report = run_study(study, tmp_path / "out", workers=1, progress=False)
    assert report.computed == 2
    index = (tmp_path / "out" / "report.html").read_text(encoding="utf-8")
    links = re.findall(r"href='([^']+)'", index)
    assert len(links) == 2
    for link in links:
        page = tmp_path / "out" / link
        assert page.exists()
        assert not list(page.parent.glob("*.png"))   # the pictures are in the page
        assert "data:image/png;base64," in page.read_text(encoding="utf-8")
    # 10 N·m on a small pair passes, 400 N·m does not: each row says its own
    assert index.count(">PASS<") == 1 and index.count(">FAIL<") == 1


def test_a_report_changes_no_key_of_a_study_without_one():
    values = {"torque": 10.0}
    assert case_key(values, Outputs(), "c") == case_key(values, Outputs(report=False), "c")
    assert case_key(values, Outputs(report=True), "c") != case_key(values, Outputs(), "c")

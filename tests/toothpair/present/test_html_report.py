"""The report (``fegear solve --report``): one page that refers to nothing outside itself,
the verdict first, every table the summary has; opened in headless Chromium, it renders with
every picture loaded and no error on the console (the screenshot is kept beside the page)."""

import html.parser
import re

import pytest
from browser import find_chromium, look

SPECTRUM = "torque,cycles\n60,1e8\n120,5e6\n160,3e5\n200,2e4\n"


@pytest.fixture(scope="module")
def page(tmp_path_factory):
    """The report of a solve run in this process (a process of its own: 1 s more)."""
    from fegear.cli import main

    folder = tmp_path_factory.mktemp("report")
    (folder / "duty.csv").write_text(SPECTRUM)
    out = folder / "out"
    assert main(["solve", "--quality", "coarse", "--positions", "4", "--spectrum",
                 str(folder / "duty.csv"), "--speed", "1500", "--KA", "1.25", "--report",
                 "--out", str(out)]) == 0
    return out / "report.html"


class _Refs(html.parser.HTMLParser):
    def __init__(self):
        super().__init__()
        self.refs, self.tags = [], []

    def handle_starttag(self, tag, attrs):
        self.tags.append(tag)
        self.refs += [(tag, k, v) for k, v in attrs if k in ("src", "href", "srcset",
                                                            "action", "data")]


def test_the_page_refers_to_nothing_outside_itself(page):
    text = page.read_text(encoding="utf-8")
    refs = _Refs()
    refs.feed(text)
    assert refs.refs, "the pictures are there"
    for tag, key, value in refs.refs:
        assert value.startswith("data:image/png;base64,") or value.startswith("#"), \
            (tag, key, value[:80])
    assert not {"link", "iframe", "object", "embed"} & set(refs.tags)
    assert "url(" not in text and "@import" not in text and "<script" not in text
    assert not re.search(r"https?://", text)


def test_the_verdict_comes_first_and_every_part_is_there(page):
    text = page.read_text(encoding="utf-8")
    body = text[text.index("<body>"):]
    assert body.index("id='verdict'") < body.index("<h2>")
    assert re.search(r"<strong>(PASS|FAIL)</strong>", body)
    for part in ("Safety factors", "For the life", "Stresses", "The load spectrum",
                 "The design and its inputs", "Pictures", "Where the numbers come from"):
        assert f">{part}<" in body, part
    assert "fegear solve --quality coarse --positions 4 --spectrum" in body   # the command
    assert "S_H" in body and "pitting gear 1" in body


@pytest.fixture
def chromium():
    """Headless Chromium, installed from Debian's chromium where it is missing and can be."""
    browser, why = find_chromium()
    if browser is None:
        pytest.skip(why)
    return browser


def test_the_page_renders_in_headless_chromium(page, chromium):
    seen = look(chromium, page)
    assert seen.errors == []
    assert len(seen.images) >= 3 and all(seen.images), seen.images
    assert seen.title.startswith("fegear: m 2")
    assert seen.screenshot.startswith(b"\x89PNG") and len(seen.screenshot) > 50_000
    (page.parent / "screenshot.png").write_bytes(seen.screenshot)

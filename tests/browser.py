"""Headless Chromium for the tests that look at a page: the system's browser (installed with
apt-get where it is missing and the tests run as root: tests/system.py), driven through the
DevTools protocol over a websocket (tornado's client, which Dask already brings): the page's
console errors, whether every picture loaded, and a screenshot."""

from __future__ import annotations

import base64
import json
import os
import re
import signal
import subprocess
import tempfile
import urllib.request
from dataclasses import dataclass
from pathlib import Path

from system import installed, why_not


def find_chromium() -> tuple[str | None, str]:
    """The browser's path, installing Debian's ``chromium`` where none is found and the tests
    can (tests/system.py); else None and why."""
    found = installed("chromium")
    return (found, "") if found else (None, why_not("chromium"))


@dataclass
class Looked:
    """What the browser saw: the console's errors, each picture's having loaded, the page's
    title and a screenshot (PNG bytes)."""

    errors: list[str]
    images: list[bool]
    title: str
    screenshot: bytes


def look(browser: str, page: Path, width: int = 1200, height: int = 2400) -> Looked:
    """Open ``page`` in headless ``browser`` and look at it (:class:`Looked`)."""
    from tornado.ioloop import IOLoop

    # the browser's helper processes may still write its profile as it ends: its whole
    # process group is ended, and what they leave behind does not fail the test
    with tempfile.TemporaryDirectory(ignore_cleanup_errors=True) as profile:
        proc = subprocess.Popen(
            [browser, "--headless=new", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
             "--remote-debugging-port=0", f"--user-data-dir={profile}",
             f"--window-size={width},{height}", "about:blank"],
            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
            start_new_session=True)
        try:
            port = _port(proc)
            target = _page_target(port)
            return IOLoop.current().run_sync(
                lambda: _drive(target, page.resolve().as_uri(), width, height), timeout=120)
        finally:
            try:
                os.killpg(proc.pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
            proc.wait()


def _port(proc) -> int:
    for line in proc.stderr:
        found = re.search(r"DevTools listening on ws://[^:]+:(\d+)/", line)
        if found:
            return int(found.group(1))
    raise RuntimeError("the browser did not open its DevTools port")


def _page_target(port: int) -> str:
    with urllib.request.urlopen(f"http://127.0.0.1:{port}/json/list", timeout=30) as r:
        pages = [t for t in json.load(r) if t["type"] == "page"]
    return pages[0]["webSocketDebuggerUrl"]


async def _drive(target: str, url: str, width: int, height: int) -> Looked:
    from tornado.websocket import websocket_connect

    ws = await websocket_connect(target, max_message_size=256 * 1024 * 1024)
    ids = iter(range(1, 10 ** 6))
    errors: list[str] = []
    loaded = False

    async def call(method: str, **params):
        nonlocal loaded
        k = next(ids)
        ws.write_message(json.dumps({"id": k, "method": method, "params": params}))
        while True:
            msg = json.loads(await ws.read_message())
            if msg.get("id") == k:
                if "error" in msg:
                    raise RuntimeError(f"{method}: {msg['error']}")
                return msg.get("result", {})
            _event(msg)

    def _event(msg: dict) -> None:
        nonlocal loaded
        method, p = msg.get("method"), msg.get("params", {})
        if method == "Page.loadEventFired":
            loaded = True
        elif method == "Runtime.exceptionThrown":
            errors.append(p["exceptionDetails"].get("text", "exception"))
        elif method == "Runtime.consoleAPICalled" and p.get("type") in ("error", "assert"):
            errors.append(" ".join(str(a.get("value", a.get("description", "")))
                                   for a in p.get("args", [])))
        elif method == "Log.entryAdded" and p["entry"].get("level") == "error":
            errors.append(p["entry"].get("text", ""))

    for domain in ("Page", "Runtime", "Log"):
        await call(f"{domain}.enable")
    await call("Emulation.setDeviceMetricsOverride", width=width, height=height,
               deviceScaleFactor=1, mobile=False)
    await call("Page.navigate", url=url)
    while not loaded:
        _event(json.loads(await ws.read_message()))
    images = (await call("Runtime.evaluate", returnByValue=True, expression=(
        "Array.from(document.images).map(i => i.complete && i.naturalWidth > 0)")))
    title = (await call("Runtime.evaluate", expression="document.title",
                        returnByValue=True))["result"]["value"]
    shot = await call("Page.captureScreenshot", format="png")
    ws.close()
    return Looked(errors, images["result"]["value"], title, base64.b64decode(shot["data"]))

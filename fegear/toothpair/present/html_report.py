"""One page a designer hands on (``fegear solve --report``, docs/outputs.md, "The report"):
report.html, self-contained (the pictures embedded, the style inline, nothing fetched), the
verdict first, then the design, the safety factors static and for the life, the stresses with
their error estimate and a class's band, the spectrum's damage, the pictures and where the
numbers come from.

It reads a solved job's summary and the pictures already written beside it; it solves
nothing.
"""

from __future__ import annotations

import base64
import hashlib
import json
import math
from datetime import UTC, datetime
from pathlib import Path

from ...provenance import code_version
from ...quantities import FACTORS, HEADLINES
from ..analyses import Verdict, shown
from ..safety import ALLOWABLE_KEYS
from .html_parts import escape, safety_cell, table
from .tables import deviations_words

#: the pair's own pictures on a page, in order, with a caption each (the files' keys); each
#: analysis's follow (:attr:`~.analyses.Analysis.pictures`)
PICTURES = {"png": "Von Mises stress on the loaded teeth and at the contact peak",
            "root_png": "Root stresses: each fillet's largest σ1",
            "flank_png": "Contact pressure along the flank against Hertz"}

STYLE = """
body { font-family: system-ui, sans-serif; max-width: 60rem; margin: 1.5rem auto;
       padding: 0 1rem; color: #1b1b1b; }
h1 { font-size: 1.4rem; margin-bottom: 0.2rem; }
h2 { font-size: 1.1rem; margin-top: 2rem; border-bottom: 1px solid #ccc; }
.design { color: #444; }
.verdict { padding: 0.8rem 1rem; border-radius: 6px; font-size: 1.05rem; margin: 1rem 0; }
.verdict.pass { background: #e3f3e6; border: 2px solid #1e6b2f; }
.verdict.fail { background: #fbe4e2; border: 2px solid #b0201a; }
.verdict strong { font-size: 1.3rem; }
table { border-collapse: collapse; margin: 0.5rem 0; }
th, td { border: 1px solid #ccc; padding: 0.2rem 0.6rem; text-align: right; }
th:first-child, td:first-child { text-align: left; }
td.bad { color: #b0201a; font-weight: bold; }
td.text, th.text { text-align: left; }
figure { margin: 1rem 0; }
figure img { max-width: 100%; border: 1px solid #ddd; }
figcaption { color: #444; font-size: 0.9rem; }
code { background: #f3f3f3; padding: 0.1rem 0.3rem; word-break: break-all; }
"""


def write_report(summary: dict, files: dict[str, Path], out: Path, command: str) -> Path:
    """report.html in ``out`` from a job's ``summary`` and the pictures among ``files``;
    ``command``: the command that gives the numbers again."""
    path = Path(out) / "report.html"
    path.write_text(report_html(summary, files, command), encoding="utf-8")
    return path


def report_html(summary: dict, files: dict[str, Path], command: str) -> str:
    """The page (module docstring)."""
    i = summary["inputs"]
    title = (f"m {i['m']:g}, z {i['z2']}/{i['z1']}, h1 {i['h1']:g}, f1 {i['f1']:g}, "
             f"T {i['torque_Nm']:g} N·m")
    parts = [f"<h1>fegear report: {escape(title)}</h1>",
             f"<p class='design'>{escape(_design_words(i))}</p>",
             _verdict(summary),
             "<h2>Safety factors</h2>",
             f"<h3>Static, at {i['torque_Nm']:g} N·m</h3>", _static_table(summary)]
    slots = [(slot, part) for a in shown(summary) for slot, part in a.page(summary[a.key])]
    parts += [part for slot, part in slots if slot == "safety"]
    parts += ["<h2>Stresses</h2>", _stress_table(summary)]
    parts += [part for slot, part in slots if slot == "sections"]
    parts += ["<h2>The design and its inputs</h2>", _inputs_table(i)]
    captions = PICTURES | {k: c for a in shown(summary) for k, c in a.pictures.items()}
    pictures = [_figure(files[key], caption) for key, caption in captions.items()
                if key in files and Path(files[key]).exists()]
    if pictures:
        parts += ["<h2>Pictures</h2>", *pictures]
    parts += ["<h2>Where the numbers come from</h2>", _provenance(summary, command)]
    return ("<!DOCTYPE html>\n<html lang='en'><head><meta charset='utf-8'>"
            f"<title>fegear: {escape(title)}</title><style>{STYLE}</style></head><body>\n"
            + "\n".join(parts) + "\n</body></html>\n")


def index_html(title: str, cases: list[dict]) -> str:
    """A study's index page: a row a case (``case``, ``values``: what tells it apart,
    ``status``, ``summary`` where solved, ``link``: its page, relative) with its verdict."""
    rows = []
    for c in cases:
        found = verdicts(c["summary"]) if c.get("summary") else []
        passed = bool(found) and all(v.passed for v in found)
        word = ("PASS" if passed else "FAIL") if found else c["status"]
        link = (f"<a href='{escape(c['link'])}'>case {c['case']}</a>" if c.get("link")
                else f"case {c['case']}")
        what = ", ".join(f"{k} {_value(v)}" for k, v in c["values"].items())
        lines = "; ".join(v.line for v in found) or escape(c.get("error") or "")
        cls = " class='bad'" if found and not passed else ""
        rows.append(f"<tr><td>{link}</td><td class='text'>{escape(what)}</td><td{cls}>{word}</td>"
                    f"<td class='text'>{escape(lines)}</td></tr>")
    return ("<!DOCTYPE html>\n<html lang='en'><head><meta charset='utf-8'>"
            f"<title>fegear study: {escape(title)}</title><style>{STYLE}</style></head><body>\n"
            f"<h1>fegear study: {escape(title)}</h1>\n<table><tr><th>case</th>"
            "<th class='text'>inputs</th><th>verdict</th><th class='text'>why</th></tr>\n"
            + "\n".join(rows)
            + "</table>\n</body></html>\n")


def verdicts(summary: dict) -> list[Verdict]:
    """Each verdict the summary holds: the static one (the smallest safety factor over the
    positions, where, and on which tooth), then each analysis's (the life's, the class's)."""
    out = []
    factors = _static_minima(summary)
    if factors:
        key, (value, at) = min(factors.items(), key=lambda kv: kv[1][0])
        label = FACTORS[key].label
        tooth = _tooth_of(summary, key, at)
        where = f" at β {at:.3g}°" if at is not None else ""
        edge = ""
        if key == "safety_contact" and summary.get("contact_peak_on_tip_round"):
            flank = factors.get("safety_contact_flank", (None,))[0]
            edge = (" on the tip round (edge contact" + (f"; S_H flank {flank:.2f}"
                                                         if flank else "") + ")")
        out.append(Verdict(value >= 1.0, f"static: {label} {value:.2f}{where}{tooth}{edge} "
                                         f"limits ({'at least 1' if value >= 1 else 'below 1'})"))
    found = [a.verdict(summary[a.key]) for a in shown(summary)]
    return out + [v for v in found if v is not None]


def _verdict(summary: dict) -> str:
    found = verdicts(summary)
    passed = all(v.passed for v in found)
    word = "PASS" if passed else "FAIL"
    lines = "".join(f"<li>{'✔' if v.passed else '✘'} {escape(v.line)}</li>" for v in found)
    return (f"<div class='verdict {'pass' if passed else 'fail'}' id='verdict'>"
            f"<strong>{word}</strong><ul>{lines}</ul></div>")


def _static_minima(summary: dict) -> dict[str, tuple[float, float | None]]:
    """Each static safety factor's smallest over the positions and where (β, degrees)."""
    cycle = summary.get("cycle")
    out = {}
    for key in FACTORS:
        if cycle is not None and isinstance(cycle.get(key), dict):
            out[key] = (cycle[key]["min"], cycle[key]["at_position_deg"])
        elif summary.get(key) is not None:
            out[key] = (summary[key], summary["inputs"].get("position_deg"))
    return {k: v for k, v in out.items() if v[0] is not None}


def _tooth_of(summary: dict, key: str, at: float | None) -> str:
    """On which tooth the factor ``key`` is smallest, where the summary's teeth are of that
    position."""
    here = summary["inputs"].get("position_deg")
    if at is None or here is None or abs(at - here) > 1e-9 or not summary.get("teeth"):
        return ""
    teeth = [t for t in summary["teeth"] if t.get(key) is not None]
    if not teeth:
        return ""
    t = min(teeth, key=lambda t: t[key])
    if key == "safety_bending_gear2" and t.get("gear2_tooth") is not None:
        return f", gear 2 tooth {t['gear2_tooth']}"
    return f", gear 1 tooth {t['tooth']}"


def _static_table(summary: dict) -> str:
    i = summary["inputs"]
    rows = []
    for key, (value, at) in _static_minima(summary).items():
        allowable = i[ALLOWABLE_KEYS[FACTORS[key].stress.allowable]]
        stress = allowable / value
        rows.append([FACTORS[key].label, safety_cell(value), f"{allowable:g}", f"{stress:.1f}",
                     "" if at is None else f"{at:.3g}"])
    return table(["factor", "S", "allowable MPa", "stress MPa", "at β °"], rows)


def _stress_table(summary: dict) -> str:
    estimate = summary.get("error_estimate_by_stress_pct") or {}
    cycle = summary.get("cycle") or {}
    head = ["stress", "FE MPa", "error estimate %"]
    beside = []     # each analysis's columns: its cells by headline key, and how many
    for a in shown(summary):
        heads, cells = a.stress_columns(summary[a.key])
        head += heads
        beside.append((cells, len(heads)))
    rows = []
    for headline in HEADLINES:
        key = headline.key
        value = cycle[key]["max"] if isinstance(cycle.get(key), dict) else summary.get(key)
        if value is None:
            continue
        err = estimate.get(key)
        row = [headline.label, f"{value:.1f}", "–" if err is None else f"±{err:.1f}"]
        for cells, n in beside:
            row += cells.get(key, ["–"] * n)
        rows.append(row)
    note = ("<p>The largest over the positions solved. The error estimate compares the solve "
            "with a second mesh level (docs/model.md); a dash where it was not run "
            "(<code>--no-estimate</code>).</p>")
    return table(head, rows) + note


def _inputs_table(i: dict) -> str:
    rows = [[escape(k), escape(_value(v))] for k, v in i.items() if k != "deviations"]
    rows.append(["deviations", escape(deviations_words(i.get("deviations"))
                                  or "none (a perfect pair)")])
    return table(["input", "value"], rows, raw=True)


def _provenance(summary: dict, command: str) -> str:
    key = json.dumps(summary["inputs"], sort_keys=True, separators=(",", ":"))
    digest = hashlib.sha256(key.encode()).hexdigest()[:16]
    when = datetime.now(UTC).strftime("%Y-%m-%d %H:%M UTC")
    return table(["", ""], [["fegear", escape(code_version())],
                             ["the inputs' hash (SHA-256 of summary.json's inputs)", digest],
                             ["the command that gives these numbers again",
                              f"<code>{escape(command)}</code>"],
                             ["written", when]], raw=True)


def _figure(path: Path, caption: str) -> str:
    data = base64.b64encode(Path(path).read_bytes()).decode("ascii")
    return (f"<figure><img src='data:image/png;base64,{data}' alt='{escape(caption)}'>"
            f"<figcaption>{escape(caption)}</figcaption></figure>")


def _value(v) -> str:
    if isinstance(v, float):
        return f"{v:g}" if math.isfinite(v) else str(v)
    return "–" if v is None else str(v)


def _design_words(i: dict) -> str:
    return (f"torque {i['torque_Nm']:g} N·m, face width {i['thickness_mm']:g} mm, E "
            f"{i['E_MPa']:g} MPa, ν {i['nu']:g}, shift {i['shift']:g}, tip relief "
            f"{i['relief_um']:g} µm, quality {i['quality']}")



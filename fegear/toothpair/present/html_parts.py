"""The pieces of HTML the report page and the analyses' sections share: a table, a safety
factor's cell, escaped text."""

from __future__ import annotations

import html


def table(head: list[str], rows: list[list[str]], raw: bool = False) -> str:
    """A table of ``head`` and ``rows`` (cells as text, escaped unless ``raw``: HTML already;
    a cell that is a whole ``<td class=…>`` stands as it is)."""
    def cell(tag: str, text: str) -> str:
        if text.startswith("<td class="):
            return text
        return f"<{tag}>{text if raw else escape(text)}</{tag}>"

    lines = ["<table><tr>" + "".join(f"<th>{escape(h)}</th>" for h in head) + "</tr>"]
    lines += ["<tr>" + "".join(cell("td", c) for c in row) + "</tr>" for row in rows]
    return "\n".join(lines) + "</table>"


def safety_cell(value) -> str:
    """A safety factor's cell, marked where it is below 1."""
    if value == "inf" or value is None:
        return "∞" if value == "inf" else "–"
    text = f"{value:.2f}"
    return f"<td class='bad'>{text}</td>" if value < 1.0 else text


def escape(text) -> str:
    """``text`` safe in HTML, quotes too."""
    return html.escape(str(text), quote=True)

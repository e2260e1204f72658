"""The tornado picture of the sensitivities (``fegear solve --sensitivities``, matplotlib):
which deviation moves each stress most."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ....figures import margins, pyplot, save_png
from ....quantities import FLANK, ROOT1, ROOT2

#: deviations a panel shows, the largest first
TOP = 12


def sensitivities_png(path: Path, s: dict, title: str) -> Path:
    """:func:`sensitivities_figure` written to ``path``."""
    return save_png(sensitivities_figure(s, title), path, 110)


def sensitivities_figure(s: dict, title: str):
    """A panel a headline (the root stresses and the flank pressure): the :data:`TOP`
    deviations that move it most as horizontal bars, the largest on top, what one tolerance
    of each moves it with a class (``--grade``), else its rate per µm; red where the stress
    rises with the deviation, blue where it falls (a runout's bar is a size: grey)."""
    plt = pyplot()
    graded = s["grade"] is not None
    fig, axes = plt.subplots(1, 3, figsize=(14, 6.2))
    for ax, q in zip(axes, (ROOT1, ROOT2, FLANK)):
        stem = q.key.removesuffix("_MPa")
        col = f"{stem}_at_tolerance" if graded else f"{stem}_per_um"
        rows = [r for r in s["rows"] if r.get(col) is not None]
        rows = sorted(rows, key=lambda r: abs(r[col]), reverse=True)[:TOP][::-1]
        values = np.array([r[col] for r in rows])
        colours = ["0.55" if r["kind"] == "runout" else "tab:red" if v > 0 else "tab:blue"
                   for r, v in zip(rows, values)]
        y = np.arange(len(rows))
        ax.barh(y, values, color=colours)
        ax.set_yticks(y)
        ax.set_yticklabels([r["deviation"] for r in rows], fontsize=8)
        ax.axvline(0.0, color="black", lw=0.8)
        ax.set_xlabel(f"{q.label} [{q.unit}" + (" at one tolerance]" if graded else " per µm]"))
        ax.grid(axis="x", alpha=0.3)
        ax.set_title(q.label, fontsize=10)
    how = (f"one class-{s['grade']} tolerance of each deviation" if graded
           else "per µm of each deviation")
    fig.suptitle(f"{title}\nwhat {how} moves, at β = {s['position_deg']:.4g}°; red: the "
                 "stress rises with it, blue: falls, grey: a runout at its worst phase",
                 fontsize=10)
    margins(fig, left=1.6, right=0.25, bottom=0.7, top=0.95, wspace=1.9)
    return fig

"""The picture of a tolerance class's samples (``fegear solve --grade``, matplotlib): the
distribution of each safety factor over the class's pairs, with S = 1, the exact pair's and
the factor at the verdict's quantile marked."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ....figures import margins, pyplot, save_png
from ....figures.labels import place_legend
from ....quantities import FACTORS


def samples_png(path: Path, samples: dict, allowables, title: str) -> Path:
    """:func:`samples_figure` written to ``path``."""
    return save_png(samples_figure(samples, allowables, title), path, 110)


def samples_figure(samples: dict, allowables, title: str):
    """A panel a safety factor: the solved pairs' factors as a histogram (the jammed pairs,
    which have none, counted in the title), S = 1 (the allowable), the exact pair's factor and
    the factor the ``quantile`` share of the pairs meet."""
    plt = pyplot()
    rows = [r for r in samples["rows"] if r["status"] == "solved"]
    fig, axes = plt.subplots(2, 2, figsize=(10, 8.5))
    q = samples["quantile"]
    for ax, (key, f) in zip(axes.ravel(), FACTORS.items()):
        allowable, stress = getattr(allowables, f.stress.allowable), f.stress.key
        s = np.array([allowable / r[stress] for r in rows if r[stress] > 0])
        v = samples["safety"][key]
        if len(s):
            ax.hist(s, bins=min(40, max(8, len(s) // 8)), color="tab:blue", alpha=0.6,
                    label=f"{len(s)} pair{'' if len(s) == 1 else 's'} solved")
            ax.set_ylim(0, 1.45 * ax.get_ylim()[1])   # room for the legend above the bars
        ax.axvline(1.0, color="tab:red", lw=1.5, label="S = 1 (the allowable)")
        if v["nominal"] is not None:
            ax.axvline(v["nominal"], color="black", lw=1.5, ls="--",
                       label=f"exact pair {v['nominal']:.2f}")
        at = v["at_quantile"]
        if at:
            ax.axvline(at, color="tab:orange", lw=1.8,
                       label=f"{100 * (1 - q):g} % of pairs below {at:.2f}")
        ax.set_title(f.label, fontsize=10)
        ax.set_xlabel("safety factor S [-]")
        ax.set_ylabel("pairs")
        ax.grid(alpha=0.3)
        place_legend(ax, fontsize=7)
    g = samples["grade"]["grade"]
    across = samples.get("across")
    if across:   # the stresses are each pair's worst section's: the title says so
        band = across["misalignment_band_um"]
        title += (f"\nacross the face at its worst section, misalignment "
                  f"{across['misalignment_um']:g}" + (f" ± {band:g}" if band else "") + " µm, "
                  "each tooth's helix drawn")
    n = samples["samples"]
    fig.suptitle(f"{title}\n{n} pair{'' if n == 1 else 's'} of ISO 1328-1 class {g}: "
                 f"{samples['solved']} solved, {samples['jammed']} jammed "
                 f"({100 * samples['jammed_share']:.3g} %), {samples['failed']} failed; "
                 f"{samples['verdict'].split(':', 1)[0]} at P{100 * q:g}", fontsize=10)
    margins(fig, left=0.75, right=0.25, bottom=0.6, top=1.0, hspace=0.8, wspace=0.75)
    return fig

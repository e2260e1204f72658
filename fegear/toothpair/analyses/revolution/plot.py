"""Pictures of a whole revolution (``fegear solve --revolution``, matplotlib): the loaded
transmission error over one turn of gear 1 and its spectrum, and the largest stresses each
tooth carried, as bars."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ....figures import margins, pyplot, save_png
from ....figures.labels import place_legend
from ....quantities import PEAK, ROOT1, ROOT2
from .solve import median_tooth

#: the per-tooth panels, each over its gear's teeth against its allowable
TOOTH_PANELS = (ROOT1, ROOT2, PEAK)


def revolution_png(path: Path, revolution: dict, rows: list[dict], turn: np.ndarray,
                   amplitudes: np.ndarray, title: str) -> Path:
    """:func:`revolution_figure` written to ``path``."""
    return save_png(revolution_figure(revolution, rows, turn, amplitudes, title), path, 110)


def revolution_figure(revolution: dict, rows: list[dict], turn: np.ndarray,
                      amplitudes: np.ndarray, title: str):
    """Above, gear 1's loaded rotation from its kinematic position over one turn (the
    transmission error, deviations and all) and the unloaded one (first touch), against
    gear 1's ``turn`` (deg) from the revolution's summary and rows; below, the loaded one's
    spectrum (``amplitudes`` by order of gear 1's turn), the mesh order z1 and its harmonics
    marked, the largest orders named."""
    plt = pyplot()
    z1 = revolution["pitches"]
    fig, ax = plt.subplots(2, 1, figsize=(9, 8.5))
    ax[0].plot(turn, [r["rotation_urad"] for r in rows], lw=1.2,
               label="loaded (transmission error)")
    ax[0].plot(turn, [r["first_touch_urad"] for r in rows], lw=1.0, ls="--",
               label="unloaded (first touch)")
    ax[0].set_xlim(0, 360)
    ax[0].set_xticks(np.arange(0, 361, 45))
    ax[0].set_xlabel("turn of gear 1 [deg]")
    ax[0].set_ylabel("gear-1 rotation from kinematic [µrad]")
    te = revolution["rotation_urad"]
    ax[0].set_title(f"loaded rotation (transmission error): {te['peak_to_peak']:.1f} µrad peak "
                    "to peak",
                    fontsize=10)
    _spectrum_panel(ax[1], revolution["spectrum"], amplitudes, z1)
    for a in ax:
        a.grid(alpha=0.3)
    fig.suptitle(title, fontsize=10)
    margins(fig, left=0.85, right=0.25, bottom=0.6, top=0.85, hspace=0.75)
    place_legend(ax[0], fontsize=8)
    return fig


def _spectrum_panel(ax, largest: list[dict], amplitudes: np.ndarray, z1: int) -> None:
    """Every harmonic up to 2.5 mesh orders as a stem, the mesh order's harmonics marked
    and the largest harmonics named by order."""
    orders = np.arange(1, len(amplitudes))
    shown = orders <= min(len(amplitudes) - 1, int(2.5 * z1))
    a = np.asarray(amplitudes)[1:]
    ax.vlines(orders[shown], 0, a[shown], color="C0", lw=1.5)
    for k in range(1, 3):
        if k * z1 <= orders[shown][-1]:
            ax.axvline(k * z1, color="C3", ls=":", lw=1.0)
            ax.text(k * z1, 0.99, f"mesh ×{k} ", transform=ax.get_xaxis_transform(),
                    va="top", ha="right", fontsize=8, color="C3")
    top = max(a[shown].max(), 1e-12)
    for h in sorted(largest, key=lambda h: -h["amplitude_urad"])[:6]:
        if h["order"] <= orders[shown][-1] and h["amplitude_urad"] > 0.05 * top:
            ax.annotate(str(h["order"]), (h["order"], h["amplitude_urad"]),
                        textcoords="offset points", xytext=(0, 3), ha="center", fontsize=7)
    ax.set_ylim(0, 1.15 * top)
    ax.set_xlim(0, orders[shown][-1] + 1)
    ax.set_xlabel(f"order (harmonics per turn of gear 1; the mesh is order z1 = {z1})")
    ax.set_ylabel("amplitude [µrad]")


def revolution_teeth_png(path: Path, per_tooth: dict, worst: dict, allowables,
                         title: str) -> Path:
    """:func:`revolution_teeth_figure` written to ``path``."""
    return save_png(revolution_teeth_figure(per_tooth, worst, allowables, title), path, 110)


def revolution_teeth_figure(per_tooth: dict, worst: dict, allowables, title: str):
    """One bar per tooth of the largest stress it carried over the revolution: gear 1's and
    gear 2's root stress and gear 1's teeth's contact pressure; on each panel the median
    tooth (what a perfect pair gives every tooth) dashed, the allowable where it is within
    twice the largest bar, the worst tooth in red with its value, and the teeth seen in part
    (whose pass the revolution's ends cut: :func:`~.revolution.per_tooth`) pale."""
    plt = pyplot()
    fig, ax = plt.subplots(len(TOOTH_PANELS), 1, figsize=(9, 10))
    for a, q in zip(ax, TOOTH_PANELS):
        values = per_tooth[q.key]
        teeth = np.array([int(t) for t in values])
        v = np.array(list(values.values()))
        if not len(v):
            a.text(0.5, 0.5, "no tooth loaded", transform=a.transAxes, ha="center")
            continue
        cut = per_tooth["cut"][f"gear{q.gear}"]
        k = int(np.argmax(v))
        colours = ["C3" if i == k else "#b9c7d6" if t in cut else "C0"
                   for i, t in enumerate(teeth)]
        a.bar(teeth, v, width=0.8, color=colours)
        median = median_tooth(values, cut)
        a.axhline(median, color="k", ls="--", lw=1.0, label=f"median tooth {median:.0f} MPa")
        if cut:   # a zero bar: the legend's swatch in the pale colour
            a.bar([teeth[0]], [0.0], color="#b9c7d6", label="seen in part (the revolution's "
                  "ends cut its pass)")
        limit = getattr(allowables, q.allowable)
        if limit <= 2 * v.max():
            a.axhline(limit, color="C3", ls=":", lw=1.2, label=f"allowable {limit:g} MPa")
        part = " (seen in part)" if teeth[k] in cut else ""
        a.annotate(f"tooth {teeth[k]}: {v[k]:.0f} MPa{part}", (teeth[k], v[k]),
                   textcoords="offset points", xytext=(0, 4), ha="center", fontsize=8,
                   color="C3")
        a.set_ylim(0, 1.2 * max(v.max(), limit if limit <= 2 * v.max() else 0))
        a.set_xlim(teeth.min() - 1, teeth.max() + 1)
        a.set_xlabel(f"gear-{q.gear} tooth")
        a.set_ylabel(q.axis, fontsize=9)
        a.grid(alpha=0.3, axis="y")
    fig.suptitle(title, fontsize=10)
    margins(fig, left=0.85, right=0.25, bottom=0.6, top=0.6, hspace=0.55)
    for a in ax:
        if a.get_legend_handles_labels()[0]:
            place_legend(a, fontsize=8)
    return fig

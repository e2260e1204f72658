"""Study plots: the headline stresses against each varied input."""

from __future__ import annotations

from pathlib import Path

from ..figures import pyplot, save_png


def study_png(path: Path, x: str, lines, stresses: dict[str, str], title: str) -> Path:
    """One panel per headline stress (``stresses``: key → label) against study input ``x``;
    ``lines``: (label, x values, {key: (values, error bars)}, whether the contact peak sits
    on gear 1's tip round) per level of the other inputs; such peaks get an open red ring."""
    plt = pyplot()

    fig, axes = plt.subplots(2, 2, figsize=(10, 7.5), sharex=True)
    for ax, (k, label) in zip(axes.ravel(), stresses.items()):
        for n, (name, xs, series, edge) in enumerate(lines):
            ys, err = series[k]
            ax.errorbar(xs, ys, yerr=err, marker="o", ms=4, capsize=3, label=name)
            if k == "contact_pressure_MPa" and any(edge):
                ax.plot([a for a, e in zip(xs, edge) if e], [b for b, e in zip(ys, edge) if e],
                        "o", ms=11, mfc="none", color="red",
                        label="peak on gear-1 tip round" if n == 0 else None)
                ax.legend(fontsize=7)
        ax.set_ylabel(f"{label} [MPa]")
        ax.grid(alpha=0.3)
    for ax in axes[-1]:
        ax.set_xlabel(x)
    if len(lines) > 1 or lines[0][0] != "all":  # the contact panel has its own legend
        axes[0, 0].legend(fontsize=7, title="other inputs", title_fontsize=7)
    fig.suptitle(f"{title}\n(error bars: the case's discretisation-error estimate)", fontsize=10)
    fig.tight_layout()
    return save_png(fig, path, 100)

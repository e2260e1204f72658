"""Study plots: the headline stresses against each varied input."""

from __future__ import annotations

from pathlib import Path

from ..figures import pyplot, save_png


def study_png(path: Path, x: str, lines, stresses: dict[str, str], title: str) -> Path:
    """One panel per headline stress (``stresses``: key → label) against study input ``x``,
    and one of the load on gear 1's tip rounds (series key ``edge``, % of the normal load);
    ``lines``: (label, x values, {key: (values, error bars)}, whether a tip round carries load)
    per level of the other inputs; such cases get an open red ring on the contact panels."""
    plt = pyplot()

    panels = {**{k: f"{label} [MPa]" for k, label in stresses.items()},
              "edge": "load on the tip rounds [% of normal load]"}
    fig, axes = plt.subplots(2, 3, figsize=(14, 7.5), sharex=True)
    for ax, (k, label) in zip(axes.ravel(), panels.items()):
        for n, (name, xs, series, edge) in enumerate(lines):
            ys, err = series[k]
            ax.errorbar(xs, ys, yerr=err, marker="o", ms=4, capsize=3, label=name)
            if k in ("contact_pressure_MPa", "edge") and any(edge):
                ax.plot([a for a, e in zip(xs, edge) if e], [b for b, e in zip(ys, edge) if e],
                        "o", ms=11, mfc="none", color="red",
                        label="tip round carries load" if n == 0 else None)
                ax.legend(fontsize=7)
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
    for ax in axes[-1]:
        ax.set_xlabel(x)
    if len(lines) > 1 or lines[0][0] != "all":  # the contact panel has its own legend
        axes[0, 0].legend(fontsize=7, title="other inputs", title_fontsize=7)
    fig.suptitle(f"{title}\n(error bars: the case's discretisation-error estimate)", fontsize=10)
    fig.tight_layout()
    return save_png(fig, path, 100)

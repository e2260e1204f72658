"""The contact pattern across the face (``fegear solve --misalignment …``, matplotlib): what a
designer reads off a marking-compound check, from the solve."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ....figures import margins, pyplot, save_png


def face_png(path: Path, s: dict, title: str, width: float) -> Path:
    """:func:`face_figure` written to ``path``."""
    return save_png(face_figure(s, title, width), path, 110)


def face_figure(s: dict, title: str, width: float):
    """Left: each loaded tooth's line load along the face at the position of the largest
    K_Hβ, its mean across the face dashed. Right, over a cycle: the pattern of the tooth that
    carries most, its line load over the face (across) and the rolling angle (up), as a
    marking compound would show it; over one position, the teeth's mean line loads."""
    plt = pyplot()
    fig, (left, right) = plt.subplots(1, 2, figsize=(13, 5.2))
    z = (np.asarray(s["zeta"]) + 0.5) * width
    share = np.gradient(z) / width
    rows = s["positions"]
    top = max(rows, key=lambda r: r["K_Hbeta"])
    for tooth, loads in sorted(top["line_loads_N_per_mm"].items(), key=lambda kv: -max(kv[1])):
        line, = left.plot(z, loads, marker="o", ms=3, label=f"gear 1 tooth {tooth}")
        mean = float(np.asarray(loads) @ share / share.sum())
        left.axhline(mean, color=line.get_color(), ls="--", lw=0.8)
    left.set_xlabel("across the face from its first end [mm]")
    left.set_ylabel("line load [N/mm]")
    left.set_title(f"at β {top['position_deg']:.3g}°: K_Hβ {top['K_Hbeta']:.3f} "
                   f"(method C {top['K_Hbeta_method_c']:.3f}); dashed: each tooth's mean",
                   fontsize=10)
    left.set_xlim(0, width)
    left.set_ylim(bottom=0)
    left.legend(fontsize=8)
    left.grid(alpha=0.3)
    if len(rows) > 1:
        _pattern(fig, right, rows, z)
    else:
        means = {t: float(np.asarray(v) @ share / share.sum())
                 for t, v in top["line_loads_N_per_mm"].items()}
        right.bar([str(t) for t in means], list(means.values()), color="0.55")
        right.set_xlabel("gear 1 tooth")
        right.set_ylabel("mean line load [N/mm]")
        right.set_title("one position: the teeth's mean line loads", fontsize=10)
    fig.suptitle(title, fontsize=10)
    margins(fig, left=0.8, right=0.3, bottom=0.6, top=0.9, wspace=0.9)
    return fig


def _pattern(fig, ax, rows: list[dict], z: np.ndarray) -> None:
    """The most loaded tooth's line load over the face and the rolling angle."""
    totals: dict[str, float] = {}
    for r in rows:
        for t, v in r["line_loads_N_per_mm"].items():
            totals[t] = totals.get(t, 0.0) + float(np.sum(v))
    tooth = max(totals, key=totals.get)
    beta = np.array([r["position_deg"] for r in rows])
    grid = np.array([r["line_loads_N_per_mm"].get(tooth, np.zeros(len(z))) for r in rows])
    mesh = ax.pcolormesh(z, beta, grid, shading="nearest", cmap="viridis")
    fig.colorbar(mesh, ax=ax, label="line load [N/mm]")
    ax.set_xlabel("across the face from its first end [mm]")
    ax.set_ylabel("rolling angle β [°]")
    ax.set_title(f"the contact pattern of gear 1 tooth {tooth} over the cycle", fontsize=10)

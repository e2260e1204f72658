"""Drive-level pictures: the bearing forces (seed 000's Fig. 6) and the dynamic response."""

from __future__ import annotations

from pathlib import Path

from ..figures import pyplot, save_png


def bearings_png(path: Path, phi, curves: dict) -> Path:
    """Eccentric-bearing forces against crank angle, like seed 000's Fig. 6: ``curves`` maps
    F_A1 … F_B3 to arrays over ``phi`` (deg)."""
    plt = pyplot()

    fig, ax = plt.subplots(figsize=(9, 5.5))
    styles = {"1": ":", "2": "--", "3": "-"}
    for name, f in curves.items():
        ax.plot(phi, f, styles[name[-1]], color="C0" if name[2] == "A" else "C3", label=name)
    ax.set_xlabel("crank angle φ [deg]")
    ax.set_ylabel("eccentric-bearing force [N]")
    ax.set_xlim(0, 360)
    ax.set_xticks(range(0, 361, 45))
    ax.grid(alpha=0.3)
    ax.legend(ncol=2, fontsize=8, title="1: no gravity, no inertia; 2: inertia; 3: both",
              title_fontsize=8)
    fig.tight_layout()
    return save_png(fig, path, 110)


def dynamics_png(path: Path, rows: list[dict], natural_hz: float) -> Path:
    """Dynamic factor and dynamic transmission error against mesh frequency, with the
    natural frequency and half of it marked (rows of ``fegear drive dynamics``)."""
    plt = pyplot()

    f = [r["mesh_frequency_Hz"] for r in rows]
    fig, ax = plt.subplots(2, 1, figsize=(8, 7), sharex=True)
    ax[0].plot(f, [r["dynamic_factor"] for r in rows], "o-", ms=3)
    ax[0].set_ylabel("dynamic factor max F / T")
    ax[1].plot(f, [r["dynamic_q_peak_to_peak_urad"] for r in rows], "o-", ms=3)
    ax[1].set_ylabel("dynamic q peak to peak [µrad]")
    ax[1].set_xlabel("mesh frequency [Hz]")
    for a in ax:
        for x, label in ((natural_hz, "f_n"), (natural_hz / 2, "f_n / 2")):
            if min(f) <= x <= max(f):
                a.axvline(x, color="grey", ls="--", lw=1)
                a.text(x, a.get_ylim()[1], label, ha="center", va="bottom", fontsize=8)
        a.grid(alpha=0.3)
    fig.tight_layout()
    return save_png(fig, path, 110)

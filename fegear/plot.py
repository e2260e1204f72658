"""Pictures (matplotlib, imported lazily)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .output import write_atomic


def pair_png(path: Path, gear1: np.ndarray, gear2: np.ndarray, e: float, r0: float,
             title: str, zoom_half_width: float) -> Path:
    """Draw the assembled pair at β = 0 (fixed frame) with a zoom on the pitch-point teeth.

    ``gear1``, ``gear2``: closed profiles in their own frames (mm); gear 1 is drawn about
    ``(0, e)``.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import PathPatch
    from matplotlib.path import Path as MplPath

    g1 = gear1 + np.array([0.0, e])
    # gear-2 material lies outside its curve: draw it as a ring up to a rim circle
    rim = 1.08 * np.hypot(gear2[:, 0], gear2[:, 1]).max()
    t = np.linspace(0, 2 * np.pi, 361)
    outer = np.stack([rim * np.cos(t), rim * np.sin(t)], -1)
    inner = np.vstack([gear2, gear2[:1]])[::-1]
    verts = np.vstack([outer, inner])
    codes = np.full(len(verts), MplPath.LINETO)
    codes[0] = codes[len(outer)] = MplPath.MOVETO
    fig, (ax, az) = plt.subplots(1, 2, figsize=(13, 6.2))
    for a in (ax, az):
        a.add_patch(PathPatch(MplPath(verts, codes), facecolor="#c9d6e8", edgecolor="none",
                              zorder=0))
        a.plot(*np.vstack([gear2, gear2[:1]]).T, color="#1f4e8c", lw=0.8, label="gear 2 (internal)")
        a.fill(*np.vstack([g1, g1[:1]]).T, color="#f3d9c4", zorder=1)
        a.plot(*np.vstack([g1, g1[:1]]).T, color="#a34a16", lw=0.8, label="gear 1 (external)",
               zorder=2)
        a.set_aspect("equal")
        a.set_xlabel("x [mm]")
        a.set_ylabel("y [mm]")
    lim = r0 * 1.12
    ax.set_xlim(-lim, lim)
    ax.set_ylim(-lim, lim)
    ax.plot([0, 0], [0, e], "k+", ms=8)
    ax.set_title(title, fontsize=9)
    ax.legend(loc="lower right", fontsize=8)
    ax.add_patch(plt.Rectangle((-zoom_half_width, r0 - 0.6 * zoom_half_width),
                               2 * zoom_half_width, 1.2 * zoom_half_width, fill=False,
                               ls="--", color="k", lw=0.7))
    az.set_xlim(-zoom_half_width, zoom_half_width)
    az.set_ylim(r0 - 0.6 * zoom_half_width, r0 + 0.6 * zoom_half_width)
    az.plot([0], [r0], "k.", ms=5)
    az.annotate("pitch point", (0, r0), textcoords="offset points", xytext=(6, 6), fontsize=8)
    az.set_title("zoom on the pitch-point teeth (β = 0)", fontsize=9)
    fig.tight_layout()

    return _save_png(fig, path, 130)


def cycle_png(path: Path, rows: list[dict], title: str, stresses: dict[str, str]) -> Path:
    """Load share per tooth, the ``stresses`` (row key → label) and gear 1's rotation against
    position, from the rows of :func:`fegear.pairout.cycle_rows`."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    beta = [r["position_deg"] for r in rows]
    fig, ax = plt.subplots(3, 1, figsize=(8, 10), sharex=True)
    for k in (k for k in rows[0] if k.startswith("share_")):
        v = [r[k] for r in rows]
        if any(x > 0 for x in v):
            ax[0].plot(beta, v, marker="o", ms=3, label=f"tooth {k[6:]}")
    ax[0].set_ylabel("load share")
    ax[0].legend(fontsize=8, ncol=3)
    for k, label in stresses.items():
        ax[1].plot(beta, [r[k] for r in rows], marker="o", ms=3, label=label)
    ax[1].set_yscale("log")
    ax[1].set_ylabel("stress [MPa]")
    ax[1].legend(fontsize=8)
    ax[2].plot(beta, [r["rotation_urad"] for r in rows], marker="o", ms=3,
               label="loaded rotation θ (from kinematic)")
    ax[2].plot(beta, [r["first_touch_urad"] for r in rows], marker="o", ms=3,
               label="unloaded (first touch)")
    ax[2].plot(beta, [r["transmission_error_urad"] for r in rows], marker="o", ms=3,
               label="elastic part θ − θ_touch")
    ax[2].set_ylabel("gear-1 rotation [µrad]")
    ax[2].set_xlabel("rolling angle β of gear 2 [deg]")
    ax[2].legend(fontsize=8)
    for a in ax:
        a.grid(alpha=0.3)
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()

    return _save_png(fig, path, 110)


def ladder_png(path: Path, ladders, targets) -> Path:
    """Run time against error, log-log: one line per ladder (:class:`fegear.bench.Ladder`)
    through its levels, CalculiX on the same meshes as crosses, each target as a box."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(8, 5.5))
    for k, (ladder, target) in enumerate(zip(ladders, targets)):
        colour = f"C{k}"
        t = [r.total_s for r in ladder.rungs]
        e = [max(ladder.error_pct(r.values, ladder.judged), 1e-4) for r in ladder.rungs]
        name = ladder.name.split(",")[0]
        ax.plot(t, e, "o-", color=colour, label=f"fegear: {name}")
        for r, x, y in zip(ladder.rungs, t, e):
            ax.annotate(r.level, (x, y), textcoords="offset points", xytext=(4, 4), fontsize=7)
        peer = [(r.peer_s, max(ladder.error_pct(
            r.peer_values, [k for k in ladder.judged if k in r.peer_values]), 1e-4))
            for r in ladder.rungs if r.peer_s]
        if peer:
            ax.plot(*zip(*peer), "x--", color=colour, label=f"CalculiX: {name}")
        ax.add_patch(plt.Rectangle((1e-3, 1e-4), target.seconds - 1e-3,
                                   target.error_pct - 1e-4, fill=False, ls=":",
                                   color=colour))
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("run time [s] (fegear: all stages after import; CalculiX: its wall time)")
    ax.set_ylabel("error against the Richardson reference [%]")
    ax.set_title("run time against error (dotted boxes: targets)", fontsize=10)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    fig.tight_layout()
    return _save_png(fig, path, 120)


def study_png(path: Path, x: str, lines, stresses: dict[str, str], title: str) -> Path:
    """One panel per headline stress (``stresses``: key → label) against study input ``x``;
    ``lines``: (label, x values, {key: (values, error bars)}, whether the contact peak sits
    on gear 1's tip round) per level of the other inputs; such peaks get an open red ring."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

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
    return _save_png(fig, path, 100)


def bearings_png(path: Path, phi, curves: dict) -> Path:
    """Eccentric-bearing forces against crank angle, like seed 000's Fig. 6: ``curves`` maps
    F_A1 … F_B3 to arrays over ``phi`` (deg)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

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
    return _save_png(fig, path, 110)


def dynamics_png(path: Path, rows: list[dict], natural_hz: float) -> Path:
    """Dynamic factor and dynamic transmission error against mesh frequency, with the
    natural frequency and half of it marked (rows of ``fegear drive dynamics``)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

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
    return _save_png(fig, path, 110)


def _save_png(fig, path: Path, dpi: int) -> Path:
    """Write a matplotlib figure as PNG (atomically) and close it."""
    import matplotlib.pyplot as plt

    def w(tmp: Path) -> None:
        fig.savefig(tmp, dpi=dpi, format="png")

    try:
        return write_atomic(path, w)
    finally:
        plt.close(fig)

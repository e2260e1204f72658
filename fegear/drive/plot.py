"""Drive-level pictures: the bearing forces (seed 000's Fig. 6) and the dynamic response."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..figures import pyplot, save_png
from .beams import DOF, TZ, X, Y
from .reducer import RESPONSES, SHAFTS


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


BUILD_STYLE = {"1": ("C0", "1 plate"), "2": ("C1", "2 plates at 180°"),
               "3": ("C2", "3 plates (¼, ½ at 180°, ¼)")}


def reducer_campbell_png(path: Path, s: dict) -> Path:
    """Campbell-style diagram of the reducer: the three builds' natural frequencies (no
    gyroscopic terms: flat in speed) against crank speed, with the unbalance line (1×), the
    mesh frequency (z_plate ×) and the working speed; where a line meets a frequency is
    marked."""
    plt = pyplot()

    speeds = np.array(s["speeds_rpm"])
    top = speeds.max()
    n = np.linspace(0.0, top, 400)
    w = n * np.pi / 30.0
    z = s["inputs"]["z_plate"]
    fig, ax = plt.subplots(figsize=(9, 6))
    for p, b in s["builds"].items():
        color, label = BUILD_STYLE[p]
        for k, m in enumerate(b["modes"]):
            ax.axhline(m["rad_s"], color=color, lw=1.0, alpha=0.8,
                       ls=("-", "--", ":")[int(p) - 1], label=label if k == 0 else None)
    ax.plot(n, w, "k-", lw=1.5, label="unbalance 1×")
    ax.plot(n, z * w, "k-.", lw=1.5, label=f"mesh frequency {z}×")
    for c in s["campbell"]:
        for key, mult in (("unbalance_rpm", 1), ("mesh_rpm", z)):
            if c.get(key) and c[key] <= top:
                ax.plot(c[key], c[key] * np.pi / 30 * mult, "o", ms=4, mfc="none",
                        color=BUILD_STYLE[str(c["plates"])][0])
    work = s["inputs"]["speed_rpm"]
    ax.axvline(work, color="grey", lw=1.2)
    ax.text(work, 0.02, f" working speed {work:g} r/min", transform=ax.get_xaxis_transform(),
            fontsize=8, color="grey", rotation=90, va="bottom", ha="right")
    hi = max(m["rad_s"] for b in s["builds"].values() for m in b["modes"])
    lo = min(m["rad_s"] for b in s["builds"].values() for m in b["modes"])
    ax.set_yscale("log")
    ax.set_ylim(0.3 * min(lo, top * np.pi / 30 / 10), 3 * hi)
    ax.set_xlim(0, top)
    ax.set_xlabel("crank (input) speed [r/min]")
    ax.set_ylabel("frequency [rad/s]")
    ax.set_title("Natural frequencies of the three builds and what excites them", fontsize=10)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8, loc="lower right")
    fig.tight_layout()
    return save_png(fig, path, 110)


def reducer_modes_png(path: Path, model, modes) -> Path:
    """The mode shapes of one build: each shaft's lateral amplitude sqrt(x² + y²) along it
    (solid) and its torsion times its lever (dashed: the eccentricity on a crank, the base
    radius on the output), each plate's translation (square) and rotation times the crank
    circle's radius (triangle), every mode scaled to its largest displacement."""
    plt = pyplot()
    ip = model.inputs
    lever = [1e-3 * ip.eccentricity_mm] * 3 + [ip.base_radius]
    rows = (len(modes) + 1) // 2
    fig, axes = plt.subplots(rows, 2, figsize=(11, 2.4 * rows + 1.0), sharex=True)
    axes = np.atleast_2d(axes)
    for k, (ax, m) in enumerate(zip(axes.flat, modes)):
        v = m.shape
        lines = []
        for j, name in enumerate(SHAFTS):
            base = model.dof(j, 0, 0) + DOF * np.arange(len(model.z[j]))
            lines.append((j, name, 1e3 * model.z[j], np.hypot(v[base + X], v[base + Y]),
                          lever[j] * v[base + TZ]))
        plates = [(1e3 * s.z, np.hypot(v[model.plate_dof(i, 0)], v[model.plate_dof(i, 1)]),
                   1e-3 * ip.crank_radius_mm * v[model.plate_dof(i, 2)])
                  for i, s in enumerate(model.stations)]
        scale = max([np.abs(a).max() for *_, a, b in lines] + [np.abs(b).max()
                    for *_, a, b in lines] + [max(abs(a), abs(b)) for _, a, b in plates])
        for j, name, z, lat, tor in lines:
            ax.plot(z, lat / scale, color=f"C{j}", lw=1.2, label=f"{name} lateral")
            ax.plot(z, tor / scale, color=f"C{j}", lw=1.0, ls="--", label=f"{name} torsion")
        for i, (z, tr, rot) in enumerate(plates):
            ax.plot(z, tr / scale, "s", color="k", ms=5,
                    label="plate translation" if i == 0 else None)
            ax.plot(z, rot / scale, "^", color="k", mfc="none", ms=5,
                    label="plate rotation" if i == 0 else None)
        ax.axhline(0, color="grey", lw=0.5)
        ax.set_ylim(-1.1, 1.1)
        ax.set_title(f"mode {k + 1}: {m.omega:.0f} rad/s ({m.hz:.1f} Hz)\n{m.kind}",
                     fontsize=7.5)
        ax.grid(alpha=0.3)
    for ax in axes.flat[len(modes):]:
        ax.axis("off")
    for ax in axes[-1]:
        ax.set_xlabel("axial position z [mm]")
    handles, labels = axes.flat[0].get_legend_handles_labels()
    top = 1.0 - 0.9 / fig.get_figheight()
    fig.legend(handles, labels, loc="upper center", ncol=5, fontsize=7, frameon=False,
               bbox_to_anchor=(0.5, top + 0.45 / fig.get_figheight()))
    fig.suptitle(f"Mode shapes, {model.plates} plate{'s' if model.plates > 1 else ''}: "
                 "lateral amplitude (solid), torsion × lever (dashed), plates (markers); "
                 "each mode scaled to its largest displacement", y=0.995, fontsize=9)
    fig.tight_layout(rect=(0, 0, 1, top))
    return save_png(fig, path, 100)


def reducer_response_png(path: Path, s: dict, key: str) -> Path:
    """One of the seed's Figs. 2–6: the amplitude of ``key`` against crank speed for the three
    builds, the turning mechanism (solid) and the seed's frozen model (dashed), with the
    working speed and the natural frequencies below 1.5× it marked."""
    plt = pyplot()
    n = np.array(s["speeds_rpm"])
    fig, ax = plt.subplots(figsize=(8, 5))
    torsion = "urad" in key
    for p in s["builds"]:
        color, label = BUILD_STYLE[p]
        frozen = np.array(s["response"]["frozen"][p][key])
        turning = np.array(s["response"]["turning"][p][key])
        if not torsion:
            ax.plot(n, turning, color=color, lw=1.6, label=f"{label}, turning mechanism")
        ax.plot(n, frozen, color=color, lw=1.2, ls="--", label=f"{label}, frozen (the seed's)")
        for m in s["builds"][p]["modes"]:
            rpm = m["rad_s"] * 30 / np.pi
            if rpm <= n.max():
                ax.axvline(rpm, color=color, lw=0.6, ls=":")
    work = s["inputs"]["speed_rpm"]
    ax.axvline(work, color="grey", lw=1.2)
    ax.text(work, 0.98, "working speed ", transform=ax.get_xaxis_transform(), fontsize=8,
            color="grey", rotation=90, va="top", ha="right")
    ax.set_yscale("log")
    ax.set_xlim(0, n.max())
    ax.set_xlabel("crank (input) speed [r/min]")
    ax.set_ylabel(("twist" if torsion else "x amplitude") + (" [µrad]" if torsion else " [µm]"))
    note = ("\nthe turning mechanism's twist does not vibrate at 1× (docs/drive.md)"
            if torsion else "")
    ax.set_title(RESPONSES[key] + note, fontsize=9)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7, loc="best")
    fig.tight_layout()
    return save_png(fig, path, 110)

"""Picture of a pair's deviations (``fegear profile --out`` with deviations given:
deviations.png): the deviated teeth drawn over the exact ones about the pitch point, their
departures enlarged to be seen, and each deviated flank's departure along its roll in µm."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..figures import pyplot, save_png
from ..planar import rotate
from .deviations import Deviations

#: the largest departure drawn, in modules: the enlargement brings the largest to this
DRAWN_M = 0.4


def deviations_png(path: Path, gear1: np.ndarray, gear2: np.ndarray, params, profile,
                   deviations: Deviations, title: str) -> Path:
    """:func:`deviations_figure` written to ``path``."""
    return save_png(deviations_figure(gear1, gear2, params, profile, deviations, title),
                    path, 130)


def enlargement(params, deviations: Deviations) -> float:
    """The factor the left panel draws departures at: the largest tooth deviation (µm) shown
    as :data:`DRAWN_M` modules, rounded down to 1, 2 or 5 times a power of ten."""
    largest = max([abs(v) for g in (1, 2) for d in deviations.teeth(g).values()
                   for v in (d.pitch, d.slope, d.form)] + [1e-9])
    raw = DRAWN_M * params.m * 1e3 / largest
    power = 10.0 ** math.floor(math.log10(raw))
    return max(f * power for f in (1, 2, 5) if f * power <= raw)


def deviations_figure(gear1: np.ndarray, gear2: np.ndarray, params, profile,
                      deviations: Deviations, title: str):
    """Left: gear 2 and gear 1 at β = 0 about the pitch point, each deviated tooth's outline
    (gear 1's turned by its pitch deviation and its loaded flank moved along its normal by its
    profile departure; gear 2's turned) dashed over the exact one, enlarged by
    :func:`enlargement`, and gear 1's turn under the + torque. Right: each deviated gear-1
    flank's departure (µm, + adds material) against its roll fraction, root end 0."""
    plt = pyplot()
    x = enlargement(params, deviations)
    fig, (ax, ar) = plt.subplots(1, 2, figsize=(13, 6.2), gridspec_kw={"width_ratios": [1.2, 1]})
    half = 5.5 * params.m
    below, above = params.r0 - 0.75 * half, params.r0 + 0.35 * half
    ax.fill_between([-half, half], [above, above], [below, below], color="#c9d6e8", zorder=0)
    ax.fill(*np.vstack([gear2, gear2[:1]]).T, color="white", zorder=0)
    ax.fill(*np.vstack([gear1, gear1[:1]]).T + np.array([[0.0], [params.e]]), color="#f3d9c4")
    ax.plot(*np.vstack([gear1, gear1[:1]]).T + np.array([[0.0], [params.e]]), color="#a34a16",
            lw=0.8, label="gear 1, exact")
    ax.plot(*np.vstack([gear2, gear2[:1]]).T, color="#1f4e8c", lw=0.8, label="gear 2, exact")
    for tooth, line in _gear1_teeth(gear1, params, profile, deviations, x):
        ax.plot(line[:, 0], line[:, 1] + params.e, color="C3", ls="--", lw=1.3)
        tip = line[np.argmax(np.hypot(line[:, 0], line[:, 1]))] * 0.97
        ax.text(tip[0], tip[1] + params.e, f"1:{tooth}", ha="center", va="top", fontsize=8,
                color="C3", clip_on=True)
    for tooth, line in _gear2_teeth(gear2, params, deviations, x):
        ax.plot(line[:, 0], line[:, 1], color="C0", ls="--", lw=1.3)
        tip = line[np.argmin(np.hypot(line[:, 0], line[:, 1]))] * 1.03
        ax.text(tip[0], tip[1], f"2:{tooth}", ha="center", va="bottom", fontsize=8,
                color="C0", clip_on=True)
    ax.plot([], [], color="C3", ls="--", label=f"gear 1 deviated (departures ×{x:g})")
    ax.plot([], [], color="C0", ls="--", label=f"gear 2 deviated (departures ×{x:g})")
    ax.annotate("", xy=(-0.5 * half, params.r0 - 0.5 * half),
                xytext=(0.5 * half, params.r0 - 0.56 * half),
                arrowprops={"arrowstyle": "->", "color": "k", "connectionstyle": "arc3,rad=0.1"})
    ax.text(0.0, params.r0 - 0.47 * half, "gear 1 turns this way under the + torque: a + "
            "deviation\nmoves a loaded flank towards its mate", ha="center", va="bottom",
            fontsize=8)
    ax.set_xlim(-half, half)
    ax.set_ylim(below, above)
    ax.set_aspect("equal")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.legend(loc="upper right", fontsize=8, framealpha=0.9)
    ax.set_title("about the pitch point at β = 0 (gear 2's material shaded blue)", fontsize=9)
    _flank_chart(ar, deviations)
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    return fig


def _gear1_teeth(gear1: np.ndarray, params, profile, deviations: Deviations, x: float):
    """(tooth, outline (n, 2) in gear 1's frame) of each deviated gear-1 tooth: the exact
    outline between its space centres turned by ``x`` times its pitch deviation, its loaded
    (+) flank moved along the outward normal by ``x`` times its profile departure."""
    phi = np.arctan2(gear1[:, 1], gear1[:, 0])
    rho = np.hypot(gear1[:, 0], gear1[:, 1])
    normal = _outward_normals(gear1)
    # the roll fraction as the solve takes it (geometry.deviations.Placed)
    roots = float(profile.radius(np.array([profile.phi_space]))[0])
    tips = float(profile.radius(np.array([profile.tooth_center]))[0])
    for tooth, d in deviations.teeth(1).items():
        centre = profile.tooth_center + tooth * profile.pitch
        rel = (phi - centre + np.pi) % (2 * np.pi) - np.pi
        sel = np.abs(rel) <= 0.5 * profile.pitch
        order = np.argsort(rel[sel])
        pts, rel_t, rho_t = gear1[sel][order], rel[sel][order], rho[sel][order]
        # the loaded flank runs from the tip's peak down the side gear 1 turns towards
        loaded = rel_t > rel_t[np.argmax(rho_t)]
        um = np.where(loaded, d.normal_um((rho_t - roots) / (tips - roots)), 0.0)
        pts = pts + 1e-3 * x * um[:, None] * normal[sel][order]
        yield tooth, rotate(pts, x * 1e-3 * d.pitch / params.r1)


def _gear2_teeth(gear2: np.ndarray, params, deviations: Deviations, x: float):
    """(tooth, outline) of each deviated gear-2 tooth: the exact outline within half a pitch
    of its centre (polar angle k 2π/z2) turned clockwise by ``x`` times its pitch
    deviation."""
    phi = np.arctan2(gear2[:, 1], gear2[:, 0])
    pitch = 2 * np.pi / params.z2
    for tooth, d in deviations.teeth(2).items():
        rel = (phi - tooth * pitch + np.pi) % (2 * np.pi) - np.pi
        sel = np.abs(rel) <= 0.5 * pitch
        pts = gear2[sel][np.argsort(rel[sel])]
        yield tooth, rotate(pts, -x * 1e-3 * d.pitch / params.r0)


def _outward_normals(outline: np.ndarray) -> np.ndarray:
    """Unit normals of a closed outline pointing out of the material it bounds."""
    t = np.roll(outline, -1, axis=0) - np.roll(outline, 1, axis=0)
    n = np.column_stack([t[:, 1], -t[:, 0]]) / np.hypot(t[:, 0], t[:, 1])[:, None]
    area = 0.5 * np.sum(outline[:, 0] * np.roll(outline[:, 1], -1)
                        - np.roll(outline[:, 0], -1) * outline[:, 1])
    return n if area > 0 else -n


def _flank_chart(ax, deviations: Deviations) -> None:
    """Each gear-1 tooth's profile departure on its loaded flank against its roll fraction."""
    u = np.linspace(0.0, 1.0, 101)
    shown = [(t, d) for t, d in deviations.teeth(1).items() if d.profiled]
    for tooth, d in shown:
        ax.plot(u, d.normal_um(u), lw=1.5, label=f"gear 1 tooth {tooth}")
    if not shown:
        ax.text(0.5, 0.5, "no profile deviation on gear 1's flanks", ha="center",
                transform=ax.transAxes)
    else:
        ax.legend(fontsize=8)
    ax.axhline(0.0, color="k", lw=0.8)
    ax.set_xlim(0, 1)
    ax.set_xlabel("roll fraction along the active profile (0: root end, 1: tip end)")
    ax.set_ylabel("departure along the normal [µm] (+: material added)")
    ax.set_title("gear 1's loaded flanks: slope and form deviations", fontsize=9)
    ax.grid(alpha=0.3)

"""Picture of the assembled pair (``fegear profile``'s pair.png)."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..figures import pyplot, save_png
from ..figures.labels import place_legend


def pair_png(path: Path, gear1: np.ndarray, gear2: np.ndarray, e: float, r0: float,
             title: str, zoom_half_width: float, relief=(), teeth=(),
             tip_radius: float | None = None) -> Path:
    """:func:`pair_figure` written to ``path``."""
    return save_png(pair_figure(gear1, gear2, e, r0, title, zoom_half_width, relief, teeth,
                                tip_radius), path, 130)


def pair_figure(gear1: np.ndarray, gear2: np.ndarray, e: float, r0: float, title: str,
                zoom_half_width: float, relief=(), teeth=(), tip_radius: float | None = None):
    """Draw the assembled pair at β = 0 (fixed frame) with a zoom on the pitch-point teeth,
    and with a tip relief (``relief``: :meth:`~.gear1.Gear1Profile.relief_chart`) its profile
    chart.

    ``gear1``, ``gear2``: closed profiles in their own frames (mm); gear 1 is drawn about
    ``(0, e)``. ``teeth``: (tooth number, angle of its centre from +y about gear 1's centre,
    deg) of gear 1's teeth, numbered in the zoom inside their tips (``tip_radius``, mm).
    """
    plt = pyplot()
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
    if relief:
        fig, (ax, az, ar) = plt.subplots(1, 3, figsize=(19, 6.2),
                                         gridspec_kw={"width_ratios": [1, 1, 0.8]})
        _relief_chart(ar, relief)
    else:
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
    # every tooth of gear 1 numbered a little inside its tip, as the solve's tables count them
    numbers = [ax.text(*x, str(number), ha="center", va="center", fontsize=5.5,
                       color="#a34a16", zorder=3)
               for number, x in tooth_labels(teeth, e, tip_radius or r0, 0.09 * r0)]
    # the zoom window reaches deeper into gear 1 than out into the ring: the rim ends the ring
    window = ZoomWindow(zoom_half_width, r0 - 0.75 * zoom_half_width,
                        r0 + 0.4 * zoom_half_width)
    az.plot([0], [r0], "k.", ms=5)
    az.annotate("pitch point", (0, r0), textcoords="offset points", xytext=(6, 6), fontsize=8)
    az.set_title("zoom on the teeth about the pitch point (β = 0), gear 1's teeth numbered",
                 fontsize=9)
    az.text(0.02, 0.04, "gear 1 (external)", transform=az.transAxes, fontsize=9,
            color="#a34a16")
    az.text(0.02, 0.94, "gear 2 (internal)", transform=az.transAxes, fontsize=9,
            color="#1f4e8c")
    az.set_xlim(-window.half_width, window.half_width)
    az.set_ylim(window.below, window.above)
    fig.tight_layout()
    # the window's outline passes between the numbers, not through one: it grows to take in
    # a number it would cut; the legend in a corner clear of the gears, once laid out
    window = window.clear_of(ax, numbers)
    ax.add_patch(plt.Rectangle((-window.half_width, window.below), 2 * window.half_width,
                               window.above - window.below, fill=False, ls="--", color="k",
                               lw=0.7))
    az.set_xlim(-window.half_width, window.half_width)
    az.set_ylim(window.below, window.above)
    for number, x in tooth_labels(teeth, e, tip_radius or r0, 0.35 * zoom_half_width / 4):
        if abs(x[0]) < 0.95 * window.half_width and window.below < x[1] < window.above:
            az.text(*x, str(number), ha="center", va="center", fontsize=9, color="#a34a16",
                    weight="bold", zorder=3, clip_on=True)
    place_legend(ax, fallback="outside", fontsize=8)
    return fig


@dataclass(frozen=True)
class ZoomWindow:
    """The zoom's window on the overview (mm, fixed frame): x within ± ``half_width``, y from
    ``below`` to ``above``."""

    half_width: float
    below: float
    above: float

    def clear_of(self, ax, texts) -> ZoomWindow:
        """This window grown until its outline cuts none of ``texts`` (drawn in ``ax``, laid
        out) with a margin of 2 px: a side moves out past a number it cuts, the bottom and
        top move past one they cut."""
        ax.apply_aspect()
        renderer = ax.figure.canvas.get_renderer()
        to_data = ax.transData.inverted().transform
        margin = abs(to_data([2.0, 0.0])[0] - to_data([0.0, 0.0])[0])
        boxes = [to_data(t.get_window_extent(renderer).get_points()) for t in texts]
        w, lo, hi = self.half_width, self.below, self.above
        for _ in range(8):
            moved = False
            for (x0, y0), (x1, y1) in boxes:
                x0, y0, x1, y1 = x0 - margin, y0 - margin, x1 + margin, y1 + margin
                across = x1 > -w and x0 < w
                if y1 > lo and y0 < hi and (x0 < w < x1 or x0 < -w < x1):
                    w, moved = max(abs(x0), abs(x1)), True
                elif across and y0 < lo < y1:
                    lo, moved = y0, True
                elif across and y0 < hi < y1:
                    hi, moved = y1, True
            if not moved:
                break
        return ZoomWindow(w, lo, hi)


def tooth_labels(teeth, e: float, tip_radius: float, depth: float):
    """(number, where) of each gear-1 tooth's label: ``depth`` (mm) inside its tip on its
    centre line, fixed frame at β = 0 (``teeth``: (number, angle from +y, deg))."""
    out = []
    for number, deg in teeth:
        a = np.radians(deg)
        r = tip_radius - depth
        out.append((number, np.array([-r * np.sin(a), e + r * np.cos(a)])))
    return out


def _relief_chart(ax, charts) -> None:
    """Tip relief depth against the arc length from the tip corner, one line per flank."""
    for side, c in zip(("first flank", "second flank"), charts):
        ax.plot(c["arc_mm"], c["depth_um"], lw=1.2, label=side)
    c = charts[0]
    ax.axvline(0.0, color="k", lw=0.6, ls=":")
    ax.plot([c["end_arc_mm"]], [c["amount_um"]], "ko", ms=4)
    ax.annotate(f"conjugate tip end: {c['amount_um']:.3g} µm", (c["end_arc_mm"], c["amount_um"]),
                textcoords="offset points", xytext=(-8, 4), ha="right", fontsize=8)
    ax.annotate(f"tip corner (r {c['corner_radius_mm']:.3f} mm):\n"
                f"{c['corner_depth_um']:.2f} µm", (0.0, c["corner_depth_um"]),
                textcoords="offset points", xytext=(-8, -36), ha="right", fontsize=8)
    ax.annotate(f"relief starts\n(r {c['start_radius_mm']:.3f} mm)",
                (float(c["arc_mm"][max(int(np.argmax(c["depth_um"] > 0)) - 1, 0)]), 0.0),
                textcoords="offset points", xytext=(4, 14), fontsize=8)
    ax.set_xlabel("arc length along gear 1's flank from the tip corner [mm]")
    ax.set_ylabel("material removed normal to the conjugate flank [µm]")
    ax.set_title("tip relief (profile chart)", fontsize=9)
    ax.grid(True, lw=0.3)
    ax.legend(loc="upper left", fontsize=8)


#: the colours and legend words of a design-space map's regions
MAP_KINDS = {
    "": ("#cfe8c8", "admissible"),
    "loop": ("#f2b8a2", "loop: the gear-2 curve folds back"),
    "undercut": ("#c9b3e0", "undercut: gear 1's working flank is cut"),
    "no conjugate": ("#b7c6d9", "no conjugate point for gear 1's tip"),
    "interference": ("#f5e08a", "interference: not clear before any load"),
    "relief": ("#e0c49e", "the tip relief does not fit"),
    "range": ("#dddddd", "outside the input's range"),
}
LABELS = {"h1": "h1, tooth-height coefficient (e1 = m h1)",
          "f1": "f1, tooth-shape coefficient (e2 = f1 e1)", "m": "module m [mm]",
          "shift": "shift Δ1 [mm]", "rotation": "rotation Δ2 [mm]",
          "tip-clearance": "tip clearance [mm]", "relief": "tip relief [µm]",
          "relief-extent": "tip relief extent [mm]"}


def map_png(path: Path, dm, title: str, here: tuple[float, float] | None = None,
            here_label: str = "this design", box=None) -> Path:
    """Draw a design-space map (:class:`~.space.DesignMap`): each grid design coloured by its
    defect, the admissible interval's edges a refusal states drawn as lines with the reason
    past each, ``here`` (x, y) marked and ``box`` ((x0, x1), (y0, y1), label) outlined."""
    plt = pyplot()
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch

    order = list(MAP_KINDS)
    xs, ys = np.asarray(dm.xs), np.asarray(dm.ys)
    codes = np.vectorize(lambda k: order.index(k))(dm.kinds()).astype(float)
    fig, ax = plt.subplots(figsize=(9.5, 7.2))
    dx, dy = xs[1] - xs[0], ys[1] - ys[0]
    ax.pcolormesh(np.r_[xs - dx / 2, xs[-1] + dx / 2], np.r_[ys - dy / 2, ys[-1] + dy / 2],
                  codes, cmap=ListedColormap([c for c, _ in MAP_KINDS.values()]),
                  vmin=-0.5, vmax=len(order) - 0.5, shading="flat")
    for side in ("lower", "upper"):
        pts = [(getattr(r, side), r.y, getattr(r, f"{side}_reason")) for r in dm.rows
               if getattr(r, side) is not None and getattr(r, f"{side}_reason")]
        if not pts:
            continue
        ax.plot([p[0] for p in pts], [p[1] for p in pts], "k-", lw=1.4)
        # name the reason once per stretch of equal reasons, at its middle
        runs, start = [], 0
        for i in range(1, len(pts) + 1):
            if i == len(pts) or pts[i][2] != pts[start][2]:
                runs.append(pts[(start + i - 1) // 2])
                start = i
        for x, y, why in runs:
            ax.annotate(why, (x, y), textcoords="offset points",
                        xytext=(8 if side == "upper" else -8, 0),
                        ha="left" if side == "upper" else "right", va="center", fontsize=9,
                        bbox={"boxstyle": "round,pad=0.2", "fc": "white", "ec": "0.6",
                              "alpha": 0.85})
    if box is not None:
        (x0, x1), (y0, y1), label = box
        ax.add_patch(plt.Rectangle((x0, y0), x1 - x0, y1 - y0, fill=False, ls="--", lw=1.2,
                                   color="#1f4e8c", zorder=4))
        ax.annotate(label, (x0, y1), textcoords="offset points", xytext=(2, 4), fontsize=8,
                    color="#1f4e8c")
    if here is not None:
        ax.plot(*here, marker="*", ms=16, color="#c0392b", mec="k", zorder=5)
        ax.annotate(here_label, here, textcoords="offset points", xytext=(10, -14),
                    fontsize=9, color="#c0392b", weight="bold")
    present = {k for r in dm.rows for k in r.kinds}
    ax.legend(handles=[Patch(color=c, label=w) for k, (c, w) in MAP_KINDS.items()
                       if k in present] + [plt.Line2D([], [], color="k", lw=1.4,
                                                      label="edge a refusal states")],
              loc="upper right", fontsize=8, framealpha=0.9)
    ax.set_xlim(xs[0] - dx / 2, xs[-1] + dx / 2)
    ax.set_ylim(ys[0] - dy / 2, ys[-1] + dy / 2)
    ax.set_xlabel(LABELS.get(dm.x, dm.x))
    ax.set_ylabel(LABELS.get(dm.y, dm.y))
    ax.set_title(title, fontsize=10)
    fig.tight_layout()
    return save_png(fig, path, 120)

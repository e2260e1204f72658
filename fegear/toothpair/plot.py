"""Pictures of a tooth-pair solve (matplotlib): von Mises on the loaded teeth and at the contact
peak, the pressure along each loaded flank, the root stress per tooth, and the mesh cycle."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..figures import margins, pyplot, save_png
from .case import PairSolution
from .edge import flank_centre

#: the verdict drawn on a cycle's stress panels: safety factor key, its stress, its label
CYCLE_VERDICT = {1: (("safety_bending_gear1", "root_stress_gear1_MPa", "S_F gear 1"),
                     ("safety_bending_gear2", "root_stress_gear2_MPa", "S_F gear 2")),
                 2: (("safety_contact", "contact_pressure_MPa", "S_H"),)}


def cycle_png(path: Path, rows: list[dict], title: str, stresses: dict[str, str],
              allowables=None) -> Path:
    """Load share per tooth, the root stresses, the contact stresses (``stresses``: row key →
    label) and gear 1's rotation against position, on linear axes, from the rows of
    :func:`fegear.toothpair.report.cycle_rows`. With ``allowables`` the stress panels carry
    the verdict: the allowable as a line (or, where it is over twice the largest stress, in
    the legend) and the smallest S_F and S_H marked at their β."""
    plt = pyplot()

    beta = [r["position_deg"] for r in rows]
    fig, ax = plt.subplots(4, 1, figsize=(8, 12), sharex=True)
    for k in (k for k in rows[0] if k.startswith("share_")):
        v = [r[k] for r in rows]
        if any(x > 0 for x in v):
            ax[0].plot(beta, v, marker="o", ms=3, label=f"tooth {k[6:]}")
    ax[0].set_ylabel("load share")
    ax[0].legend(fontsize=8, ncol=3)
    # the root stresses on their own axis: beside the contact pressures they would be flat
    for panel, keys in ((1, [k for k in stresses if "root" in k]),
                        (2, [k for k in stresses if "root" not in k])):
        for k in keys:
            line, = ax[panel].plot(beta, [r[k] for r in rows], marker="o", ms=3,
                                   label=stresses[k])
            estimated = [i for i, r in enumerate(rows) if r.get("von_mises_estimated")] \
                if k == "von_mises_max_MPa" else []
            if estimated:   # open markers: the surface estimate, no submodel at that position
                line.set_label(f"{stresses[k]} (open: surface estimate)")
                ax[panel].plot([beta[i] for i in estimated], [rows[i][k] for i in estimated],
                               "o", ms=3, color="white", markeredgecolor=line.get_color(),
                               zorder=line.get_zorder() + 0.1)
        ax[panel].legend(fontsize=8)
    if allowables is not None:
        for panel, limit, name in ((1, allowables.bending, "σ_FP"),
                                   (2, allowables.contact, "σ_HP")):
            _verdict(ax[panel], rows, limit, name, CYCLE_VERDICT[panel])
    ax[1].set_ylabel("root stress [MPa]")
    ax[2].set_ylabel("contact stress [MPa]")
    ax[3].plot(beta, [r["rotation_urad"] for r in rows], marker="o", ms=3,
               label="loaded rotation θ (from kinematic)")
    ax[3].plot(beta, [r["first_touch_urad"] for r in rows], marker="o", ms=3,
               label="unloaded (first touch)")
    ax[3].plot(beta, [r["transmission_error_urad"] for r in rows], marker="o", ms=3,
               label="elastic part θ − θ_touch")
    ax[3].set_ylabel("gear-1 rotation [µrad]")
    ax[3].set_xlabel("rolling angle β of gear 2 [deg]")
    ax[3].legend(fontsize=8)
    for a in ax:
        a.grid(alpha=0.3)
    fig.suptitle(title, fontsize=10)
    margins(fig, left=0.85, right=0.2, bottom=0.6, top=0.55, hspace=0.15)
    return save_png(fig, path, 110)


def _verdict(ax, rows: list[dict], limit: float, name: str, factors) -> None:
    """The allowable ``limit`` (MPa) on a cycle's stress panel and each of ``factors``
    (safety key, stress key, label) marked where it is smallest, its value in the legend."""
    top = max(r[stress] for _, stress, _ in factors for r in rows)
    if limit <= 2.0 * top:
        ax.axhline(limit, color="C3", ls="--", lw=1.2, label=f"allowable {name} {limit:g} MPa")
    else:
        ax.plot([], [], " ", label=f"allowable {name} {limit:g} MPa (off the scale)")
    for key, stress, label in factors:
        have = [r for r in rows if r.get(key) is not None]
        if not have:
            continue
        worst = min(have, key=lambda r: r[key])
        ax.plot(worst["position_deg"], worst[stress], "v", mfc="none", mec="C3", mew=1.5,
                ms=9, label=f"smallest {label} {worst[key]:.2f}, at β "
                            f"{worst['position_deg']:.3g}°")
    ax.legend(fontsize=8)


def von_mises_png(path: Path, sol: PairSolution, bodies, peaks=()) -> Path:
    """Von Mises on the loaded teeth and at the contact peak (matplotlib).

    Left, the loaded teeth of both gears, the colours clipped at twice the larger root stress
    so that the bending shows beside the contact; the gears and the loaded teeth labelled,
    each gear's root hot spot marked with its root stress, the maximum marked. Right, the
    contact peak with the submodels that resolve it (``peaks``; the ring model) over the
    bodies, on the full range, its maximum marked. A length scale in each. ``bodies`` and
    ``peaks``: :class:`~.case.BodyField` s."""
    plt = pyplot()
    p, case = sol.case.params, sol.case
    flanks = sol.detail.flank_pressures()
    loaded = [t for t in sol.teeth if t.load_N > 0]
    spots = root_hot_spots(sol, bodies)
    clip = 2.0 * max(sol.root_stress)
    fine = list(peaks)
    # where the submodels resolve the peak, the bodies' nodes under them are not the answer
    peak_at, peak = field_max(fine or list(bodies), "von_mises")
    contact = [f.points[f.pressure > 0] for f in flanks] or [np.array([peak_at])]
    box = _box(np.vstack([*contact, *[sp.point for sp in spots]]), pad=1.2 * p.m)
    zone = sol.detail.contact_zone()
    if fine:
        near = max(np.ptp(b.points, axis=0).max() for b in fine)
        zoom = min(0.6 * near, max(12.0 * zone.half_width, 0.02 * p.m))
    else:
        zoom = max(8.0 * zone.half_width, 0.05 * p.m)
    zbox = (peak_at[0] - zoom, peak_at[0] + zoom, peak_at[1] - zoom, peak_at[1] + zoom)

    fig, (ax, az) = plt.subplots(1, 2, figsize=(16, 7.4), gridspec_kw={"width_ratios": [1.7, 1]})
    im = _draw(ax, bodies, box, (0.0, clip))
    ax.set_title(f"von Mises, T {case.torque:g} N·m, β {np.degrees(case.beta):.3g}°: the loaded "
                 f"teeth\ncolours clipped at {clip:.0f} MPa (twice the largest root stress); "
                 f"the maximum, {peak:.0f} MPa, is at the contact (right)", fontsize=10)
    c1 = np.array([0.0, p.e])
    mid = np.array([(box[0] + box[1]) / 2, (box[2] + box[3]) / 2])
    out = (mid - c1) / np.linalg.norm(mid - c1)         # from gear 1 towards gear 2
    span = box[3] - box[2]
    ax.text(*(mid - 0.36 * span * out), f"gear 1 (external, z1 = {p.z1})", ha="center",
            va="center", fontsize=11, color="white", weight="bold")
    ax.text(*(mid + 0.36 * span * out), f"gear 2 (internal, z2 = {p.z2})", ha="center",
            va="center", fontsize=11, color="white", weight="bold")
    for f in flanks:
        t = next((t for t in loaded if t.tooth == f.tooth), None)
        if t is None:
            continue
        at = f.points[int(np.argmax(f.pressure))]
        label = at - 0.9 * p.m * out
        ax.annotate(f"tooth {t.tooth}\n{t.load_N:.0f} N", at, label, ha="center", va="center",
                    fontsize=8.5, color="black",
                    bbox={"boxstyle": "round,pad=0.2", "fc": "white", "alpha": 0.8},
                    arrowprops={"arrowstyle": "-", "color": "white", "lw": 0.8})
    for sp in spots:
        ax.plot(*sp.point, "o", ms=11, mfc="none", mec="white", mew=2)
        ax.annotate(f"root σ1 {sp.value:.0f} MPa\n(gear {sp.gear})", sp.point,
                    sp.point + (0.7 if sp.gear == 1 else -0.7) * p.m * out
                    + np.array([0.6 * p.m, 0.0]), fontsize=8.5, color="black",
                    bbox={"boxstyle": "round,pad=0.2", "fc": "white", "alpha": 0.8},
                    arrowprops={"arrowstyle": "->", "color": "white", "lw": 1})
    ax.plot(*peak_at, "x", ms=10, mew=2.5, color="white")
    _scale_bar(ax, box, "mm")
    fig.colorbar(im, ax=ax, orientation="horizontal", fraction=0.05, pad=0.03,
                 label="von Mises [MPa], clipped", extend="max")

    im = _draw(az, list(bodies) + fine, zbox, (0.0, peak))
    az.plot(*peak_at, "x", ms=12, mew=2.5, color="white")
    az.annotate(f"max {peak:.0f} MPa", peak_at, peak_at + np.array([0.25, -0.35]) * zoom,
                color="black", fontsize=10, bbox={"boxstyle": "round,pad=0.2", "fc": "white",
                                                  "alpha": 0.85},
                arrowprops={"arrowstyle": "->", "color": "white", "lw": 1})
    what = "submodels resolve the peak" if fine else "the mesh resolves the contact"
    az.set_title(f"the contact peak ({zone.label}), ±{zoom * 1e3:.3g} µm: {what}\n"
                 f"full range, max {peak:.0f} MPa", fontsize=10)
    _scale_bar(az, zbox, "µm")
    fig.colorbar(im, ax=az, orientation="horizontal", fraction=0.05, pad=0.03,
                 label="von Mises [MPa]")
    margins(fig, left=0.25, right=0.25, bottom=0.55, top=0.55, wspace=0.4)
    return save_png(fig, path, 100)


@dataclass(frozen=True)
class HotSpot:
    """The largest root stress of one gear in the drawn fields: gear (1, 2), where (fixed
    frame, mm) and σ1 there (MPa)."""

    gear: int
    point: np.ndarray
    value: float


def root_hot_spots(sol: PairSolution, bodies) -> tuple[HotSpot, ...]:
    """Each gear's largest σ1 in its fillets: the lower 30 % of its tooth height, where the
    solve reads its root stresses (docs/model.md, "Results")."""
    from ..geometry import Gear1Profile

    p = sol.case.params
    g1 = Gear1Profile(p)
    root1 = float(g1.radius(np.array([g1.phi_space]))[0])
    tip1 = float(g1.radius(np.array([g1.tooth_center]))[0])
    root2, tip2 = p.r0 + 2 * p.e1, p.r0 - 2 * p.e1
    zones = {"gear1": (np.array([0.0, p.e]), lambda r: r <= root1 + 0.3 * (tip1 - root1)),
             "gear2": (np.zeros(2), lambda r: r >= root2 - 0.3 * (root2 - tip2))}
    out = []
    for b in bodies:
        if b.name not in zones:
            continue
        centre, inside = zones[b.name]
        mask = inside(np.hypot(*(b.points - centre).T))
        s1 = np.where(mask, b.data["s1"], -np.inf)
        i = int(np.argmax(s1))
        out.append(HotSpot(int(b.name[-1]), b.points[i], float(s1[i])))
    return tuple(out)


def field_max(bodies, name: str) -> tuple[np.ndarray, float]:
    """Where the largest value of a field lies over ``bodies`` (fixed frame) and its value."""
    best = max(bodies, key=lambda b: b.data[name].max())
    i = int(np.argmax(best.data[name]))
    return best.points[i], float(best.data[name][i])


def _box(points: np.ndarray, pad: float) -> tuple[float, float, float, float]:
    """A box around ``points``, ``pad`` wider on each side, at least 4:3."""
    lo, hi = points.min(axis=0) - pad, points.max(axis=0) + pad
    w, h = hi - lo
    if h < 0.75 * w:
        mid = 0.5 * (lo[1] + hi[1])
        lo[1], hi[1] = mid - 0.375 * w, mid + 0.375 * w
    return float(lo[0]), float(hi[0]), float(lo[1]), float(hi[1])


def _draw(ax, bodies, box, clim):
    """Von Mises over the corner triangles of ``bodies`` that fall in ``box``."""
    from matplotlib.tri import Triangulation

    im = None
    for b in bodies:
        tri = b.cells[:, :3]
        c = b.points[tri].mean(axis=1)
        pad = 0.1 * (box[1] - box[0])
        keep = ((c[:, 0] > box[0] - pad) & (c[:, 0] < box[1] + pad)
                & (c[:, 1] > box[2] - pad) & (c[:, 1] < box[3] + pad))
        if not keep.any():
            continue
        used, local = np.unique(tri[keep], return_inverse=True)
        t = Triangulation(*b.points[used].T, local.reshape(-1, 3))
        im = ax.tripcolor(t, np.minimum(b.data["von_mises"][used], clim[1]), cmap="turbo",
                          vmin=clim[0], vmax=clim[1], shading="gouraud", rasterized=True)
    ax.set_xlim(box[0], box[1])
    ax.set_ylim(box[2], box[3])
    ax.set_aspect("equal")
    ax.set_xticks([])
    ax.set_yticks([])
    ax.set_facecolor("#e8e8e8")
    return im


def _scale_bar(ax, box, unit: str) -> None:
    """A length scale in the lower left: a round length about a fifth of the width."""
    width = box[1] - box[0]
    scale = 1e3 if unit == "µm" else 1.0
    raw = 0.2 * width * scale
    nice = max(v for v in (1, 2, 5, 10, 20, 50, 100, 200, 500, 1000) if v <= max(raw, 1))
    length = nice / scale
    x0, y0 = box[0] + 0.05 * width, box[2] + 0.06 * (box[3] - box[2])
    ax.plot([x0, x0 + length], [y0, y0], color="black", lw=4, solid_capstyle="butt")
    ax.text(x0 + length / 2, y0 + 0.02 * (box[3] - box[2]), f"{nice:g} {unit}", ha="center",
            va="bottom", fontsize=10, bbox={"boxstyle": "round,pad=0.15", "fc": "white",
                                            "alpha": 0.8, "ec": "none"})


def flank_pressure_png(path: Path, sol: PairSolution, summary: dict) -> Path | None:
    """The contact pressure along each loaded tooth's flank, the tip round shaded, with Hertz
    (p0, b at the tooth's contact point, centred on its flank load) and the half-plane
    reference's flank pressure (p ref) beside it. None if the model keeps no grid pressures
    (the sector model)."""
    flanks = sol.detail.flank_pressures()
    if not flanks:
        return None
    plt = pyplot()
    teeth = {t.tooth: t for t in sol.teeth}
    n = len(flanks)
    cols = min(n, 3)
    rows = -(-n // cols)
    fig, axes = plt.subplots(rows, cols, figsize=(5.2 * cols, 3.9 * rows), squeeze=False)
    for a in axes.ravel()[n:]:
        a.set_visible(False)
    for a, f in zip(axes.ravel(), flanks):
        t = teeth[f.tooth]
        curve = pressure_curve(f, t)
        a.plot(curve.s_um, f.pressure, color="C0", lw=1.6, label="FE")
        if curve.round_um is not None:
            a.axvspan(*curve.round_um, color="C3", alpha=0.12, label="tip round")
        a.axvline(0.0, color="k", lw=0.6, ls=":")
        if curve.hertz is not None:
            a.plot(curve.s_um, curve.hertz, "--", color="C1", lw=1.3,
                   label=f"Hertz p0 {t.hertz_p0_MPa:.0f} MPa")
        if t.halfplane_flank_MPa:
            a.axhline(t.halfplane_flank_MPa, color="C2", ls=":", lw=1.3,
                      label=f"p ref (flank) {t.halfplane_flank_MPa:.0f} MPa")
        a.set_xlim(*curve.window_um)
        a.set_ylim(0, curve.top)
        if curve.top < f.pressure.max():       # the edge spike runs off the top: say so
            k = int(np.argmax(f.pressure))
            a.annotate(f"edge peak {f.pressure[k]:.0f} MPa\n(off the scale)",
                       (curve.s_um[k], curve.top), xytext=(12, -30), textcoords="offset points",
                       fontsize=8, ha="left", arrowprops={"arrowstyle": "->", "lw": 0.8})
        where = "on its tip round" if t.peak_on_round else "on the flank"
        a.set_title(f"tooth {t.tooth}: {t.load_N:.0f} N, peak {t.p_max_MPa:.0f} MPa {where}"
                    + (f"\nflank {t.flank_p_MPa:.0f} MPa" if t.edge_contact else ""), fontsize=9)
        a.set_xlabel("distance along gear 1's profile from its tip corner [µm]")
        a.set_ylabel("contact pressure [MPa]")
        a.grid(alpha=0.3)
        a.legend(fontsize=7.5, loc="best")
    i = summary["inputs"]
    fig.suptitle(f"contact pressure along the loaded flanks: T {i['torque_Nm']:g} N·m, β "
                 f"{i['position_deg']:.3g}°, quality {i['quality']}", fontsize=10)
    margins(fig, left=0.75, right=0.2, bottom=0.6, top=0.8, wspace=0.75, hspace=0.9)
    return save_png(fig, path, 100)


@dataclass(frozen=True)
class PressureCurve:
    """A flank's pressure made ready to draw: the distance from the tip corner (µm, > 0 down
    the flank, < 0 on the round), the Hertz ellipse at the same points (MPa; None without a
    Hertz pair), the tip round's span (µm; None if the grid has no round), the window to show
    (µm) and the top of the pressure axis (MPa): the flank's scale when an edge spike would
    flatten the flank into the axis, the whole curve's otherwise."""

    s_um: np.ndarray
    hertz: np.ndarray | None
    round_um: tuple[float, float] | None
    window_um: tuple[float, float]
    top: float


#: an edge spike higher than this many times the flank's own scale is drawn off the axis
SPIKE_CLIP = 1.6


def pressure_curve(f, tooth) -> PressureCurve:
    """:class:`PressureCurve` of one :class:`~.case.FlankPressure` and its tooth result: the
    window spans the loaded stretch and a margin either side, the tip corner kept in view;
    Hertz is centred on the flank's load (the round's left out)."""
    s = f.from_corner * 1e3
    centre = flank_centre(s, f.pressure, f.on_round)
    hertz = None
    if tooth.hertz_p0_MPa and tooth.hertz_b_mm:
        b = tooth.hertz_b_mm * 1e3
        x = np.clip((s - centre) / b, -1.0, 1.0)
        hertz = tooth.hertz_p0_MPa * np.sqrt(1.0 - x * x)
    rnd = (float(s[f.on_round].min()), float(s[f.on_round].max())) if f.on_round.any() else None
    on = s[f.pressure > 0]
    # a margin of three half-widths, at most a third of the loaded stretch (nearly conformal
    # flanks have half-widths of a good part of a millimetre)
    margin = max(min(3 * tooth.half_width_mm * 1e3, np.ptp(on) / 3), 1e-3 * np.ptp(s))
    lo = max(min(float(on.min()) - margin, 0.0 if rnd is None else rnd[0]), float(s.min()))
    window = (lo, min(float(on.max()) + margin, float(s.max())))
    # the flank's scale: its reported pressure (the spike's tail next to the round left out)
    flank_p = tooth.flank_p_MPa if tooth.edge_contact else float(f.pressure.max())
    scale = max(flank_p, tooth.hertz_p0_MPa or 0.0, tooth.halfplane_flank_MPa or 0.0)
    peak = float(f.pressure.max())
    top = 1.1 * max(peak, scale) if peak <= SPIKE_CLIP * scale else SPIKE_CLIP * scale
    return PressureCurve(s, hertz, rnd, window, top)


def root_stress_png(path: Path, sol: PairSolution, summary: dict) -> Path:
    """Root σ1 of each loaded tooth, gear 1 and gear 2 side by side, the allowable bending
    stress as a line and each bar's safety factor on it."""
    plt = pyplot()
    loaded = [t for t in sol.teeth if t.load_N > 0]
    allow = summary["inputs"].get("allowable_bending_MPa")
    x = np.arange(len(loaded))
    fig, ax = plt.subplots(figsize=(max(6.0, 1.3 * len(loaded) + 2.5), 4.6))
    for k, (key, label) in enumerate((("root1_MPa", "gear 1"), ("root2_MPa", "gear 2"))):
        v = np.array([getattr(t, key) for t in loaded])
        bars = ax.bar(x + (k - 0.5) * 0.38, v, 0.36, label=f"root σ1, {label}")
        for b, value in zip(bars, v):
            text = f"{value:.0f}" + (f"\nS_F {allow / value:.2f}" if allow and value > 0 else "")
            ax.text(b.get_x() + b.get_width() / 2, value, text, ha="center", va="bottom",
                    fontsize=8)
    if allow:
        ax.axhline(allow, color="C3", ls="--", lw=1.2, label=f"allowable σ_FP {allow:g} MPa")
    ax.set_xticks(x, [f"tooth {t.tooth}\n{t.load_N:.0f} N" for t in loaded])
    top = max([allow or 0.0] + [max(t.root1_MPa, t.root2_MPa) for t in loaded])
    ax.set_ylim(0, 1.25 * top)
    ax.set_ylabel("root stress σ1 [MPa]")
    i = summary["inputs"]
    ax.set_title(f"root stress per loaded tooth, each in the fillet it bends in tension\nT "
                 f"{i['torque_Nm']:g} N·m, β {i['position_deg']:.3g}°", fontsize=10)
    ax.legend(fontsize=8, loc="upper right")
    ax.grid(axis="y", alpha=0.3)
    margins(fig, left=0.8, right=0.2, bottom=0.75, top=0.6)
    return save_png(fig, path, 100)

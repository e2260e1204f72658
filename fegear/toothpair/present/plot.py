"""Pictures of a tooth-pair solve (matplotlib): von Mises on the loaded teeth and at the contact
peak, the pressure along each loaded flank and the root stress per tooth (the mesh cycle's:
:mod:`.analyses.cycle.plot`)."""

from __future__ import annotations

import gc

import numpy as np

from ...figures import margins, png_bytes, pyplot
from ...figures.labels import Callout, place_callouts, place_legend
from ...quantities import ROOT1, ROOT2
from ..case import PairSolution
from .marks import VerdictCaption, peak_zoom, pressure_curve, root_hot_spots
from .pictured import frame_of, in_box
from .tables import factor_cell


def prepare_pictures() -> None:
    """matplotlib imported and its fonts loaded, by drawing a word: what a process that will
    draw a pair's pictures does before it is handed them (:func:`~fegear.running.spare_core`'s
    ``prepare``)."""
    plt = pyplot()
    fig = plt.figure(figsize=(1, 1))
    fig.text(0.5, 0.5, "σ1 µm", fontsize=10, weight="bold")
    png_bytes(fig, 10)
    # what is here now stays: the drawing's collections then walk only what the drawing made
    # (a tenth of its time goes to them otherwise)
    gc.freeze()


def von_mises_bytes(sol: PairSolution, summary: dict, bodies, peaks=(), spots=None) -> bytes:
    """:func:`von_mises_figure` as PNG bytes (drawn in another process:
    :func:`~.pictured.for_pictures`)."""
    return png_bytes(von_mises_figure(sol, summary, bodies, peaks, spots), 100)


def von_mises_figure(sol: PairSolution, summary: dict, bodies, peaks=(), spots=None):
    """Von Mises on the loaded teeth and at the contact peak (matplotlib), under the verdict:
    the safety factors of ``summary`` against their allowables.

    Left, the loaded teeth of both gears, the colours clipped at twice the larger root stress
    so that the bending shows beside the contact; the gears and the loaded teeth labelled,
    each gear's root hot spot marked with its root stress and S_F, the maximum marked; the
    labels placed clear of the marks, of each other and of the stressed zones. Right, the
    contact peak with the submodels that resolve it (``peaks``; the ring model) over the
    bodies, on the full range, its maximum marked, and the peak pressure's S_H. A length
    scale in each. ``bodies`` and ``peaks``: :class:`~.case.BodyField` s; ``spots``: the
    root hot spots where they were found before (:func:`~.pictured.for_pictures`)."""
    plt = pyplot()
    p, case = sol.case.params, sol.case
    flanks = sol.detail.flank_pressures()
    spots = root_hot_spots(sol, bodies) if spots is None else spots
    clip = 2.0 * max(sol.root_stress)
    fine = list(peaks)
    frame = frame_of(sol, bodies, peaks, spots)
    box, peak_at, peak, contact = frame.box, frame.peak_at, frame.peak, frame.contact
    zone = sol.detail.contact_zone()
    zoom = peak_zoom(fine, zone.half_width, p.m)
    zbox = (peak_at[0] - zoom, peak_at[0] + zoom, peak_at[1] - zoom, peak_at[1] + zoom)

    fig, (ax, az) = plt.subplots(1, 2, figsize=(16, 8.0), gridspec_kw={"width_ratios": [1.7, 1]})
    im = _draw(ax, bodies, box, (0.0, clip))
    ax.set_title(f"von Mises, T {case.torque:g} N·m, β {np.degrees(case.beta):.3g}°: the loaded "
                 f"teeth\ncolours clipped at {clip:.0f} MPa (twice the largest root stress); "
                 f"the maximum, {peak:.0f} MPa, is at the contact (right)", fontsize=10, y=TITLE_Y)
    mid = np.array([(box[0] + box[1]) / 2, (box[2] + box[3]) / 2])
    out = (mid - [0.0, p.e]) / np.linalg.norm(mid - [0.0, p.e])   # gear 1 towards gear 2
    for sp in spots:
        ax.plot(*sp.point, "o", ms=11, mfc="none", mec="white", mew=2)
    ax.plot(*peak_at, "x", ms=10, mew=2.5, color="white")
    hot = np.vstack([b.points[(b.data["von_mises"] > 0.4 * clip)] for b in bodies])
    _scale_bar(ax, box, "mm", avoid=np.vstack([hot, *contact]))
    fig.colorbar(im, ax=ax, orientation="horizontal", fraction=0.05, pad=0.03,
                 label="von Mises [MPa], clipped", extend="max")

    im = _draw(az, list(bodies) + fine, zbox, (0.0, peak))
    az.plot(*peak_at, "x", ms=12, mew=2.5, color="white")
    what = "submodels resolve the peak" if fine else "the mesh resolves the contact"
    az.set_title(f"the contact peak ({zone.label}), ±{_round(zoom * 1e3)} µm: {what}\n"
                 f"full range, max {peak:.0f} MPa", fontsize=10, y=TITLE_Y)
    _scale_bar(az, zbox, "µm")
    fig.colorbar(im, ax=az, orientation="horizontal", fraction=0.05, pad=0.03,
                 label="von Mises [MPa]")
    verdict = VerdictCaption.of(summary)
    fig.suptitle(verdict.text, fontsize=10.5, weight="bold", color=verdict.colour)
    margins(fig, left=0.25, right=0.25, bottom=0.55, top=1.1, wspace=0.4)

    # the labels last, once the axes are placed: they are placed in the picture's pixels
    place_callouts(ax, [*_gear_names(sol, bodies, box, out),
                        *_tooth_callouts(sol, flanks, -out), *_spot_callouts(spots, summary, out)],
                   data=hot)
    place_callouts(az, [Callout(f"von Mises max {peak:.0f} MPa", tuple(peak_at), (1.0, -1.0),
                                {"fontsize": 10, "bbox": LABEL_BOX, "arrowprops": WHITE_ARROW})])
    return fig


#: where the axes' titles stand, given: matplotlib otherwise measures every axis's ticks at
#: each drawing to lift a title over labels at the top, which these pictures never have
TITLE_Y = 1.0
#: the box of a label on a field, and of a gear's name (white on a dark veil: it reads on
#: the dark, calm material it is written over and on the background where it must cross it)
LABEL_BOX = {"boxstyle": "round,pad=0.2", "fc": "white", "alpha": 0.85}
NAME_BOX = {"boxstyle": "round,pad=0.25", "fc": "#14143c", "alpha": 0.45, "ec": "none"}
#: the leader of a label on a field
WHITE_ARROW = {"arrowstyle": "->", "color": "white", "lw": 1}


def _gear_names(sol, bodies, box, out) -> list[Callout]:
    """Each gear's name, written over its own material near 0.3 of the picture's height from
    its middle towards that gear (``out``: from gear 1 towards gear 2)."""
    p = sol.case.params
    mid = np.array([(box[0] + box[1]) / 2, (box[2] + box[3]) / 2])
    names = []
    for b in bodies:
        if b.name not in ("gear1", "gear2"):
            continue
        side, text = ((-1.0, f"gear 1 (external, z1 = {p.z1})") if b.name == "gear1" else
                      (1.0, f"gear 2 (internal, z2 = {p.z2})"))
        spot = mid + side * 0.3 * (box[3] - box[2]) * out
        own = b.points[((b.points > [box[0], box[2]]) & (b.points < [box[1], box[3]]))
                       .all(axis=1)]
        at = own[np.argmin(np.hypot(*(own - spot).T))] if len(own) else spot
        names.append(Callout(text, tuple(at), style={"fontsize": 11, "color": "white",
                                                     "weight": "bold", "bbox": NAME_BOX},
                             on=own))
    return names


def _round(v: float) -> str:
    """A length for a title: three significant digits, no exponent."""
    return f"{v:.3g}" if v < 100 else f"{v:.0f}"


def _tooth_callouts(sol, flanks, towards) -> list[Callout]:
    """A label of each loaded tooth (its number and load) at its flank's highest pressure,
    rather ``towards`` gear 1."""
    loads = {t.tooth: t.load_N for t in sol.teeth if t.load_N > 0}
    return [Callout(f"tooth {f.tooth}\n{loads[f.tooth]:.0f} N",
                    tuple(f.points[int(np.argmax(f.pressure))]), tuple(towards),
                    {"fontsize": 8.5, "bbox": LABEL_BOX,
                     "arrowprops": {"arrowstyle": "-", "color": "white", "lw": 0.8}})
            for f in flanks if f.tooth in loads]


def _spot_callouts(spots, summary: dict, out) -> list[Callout]:
    """A label of each root hot spot: its σ1 and its S_F, rather into its own gear."""
    s = summary
    return [Callout(f"root σ1 {sp.value:.0f} MPa, gear {sp.gear}"
                    + (f"\nS_F {f:.2f}" if (f := s[f"safety_bending_gear{sp.gear}"]) else ""),
                    tuple(sp.point), tuple(-out if sp.gear == 1 else out),
                    {"fontsize": 8.5, "bbox": LABEL_BOX, "arrowprops": WHITE_ARROW})
            for sp in spots]


def _draw(ax, bodies, box, clim):
    """Von Mises over the corner triangles of ``bodies`` that fall in ``box``."""
    from matplotlib.tri import Triangulation

    im = None
    for b in bodies:
        keep = in_box(b, box)
        if not keep.any():
            continue
        used, local = np.unique(b.cells[keep, :3], return_inverse=True)
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


def _scale_bar(ax, box, unit: str, avoid=None) -> None:
    """A length scale, a round length about a fifth of the width, in the corner where it
    covers the fewest of the points ``avoid`` ((n, 2); the lower left among equals)."""
    width, height = box[1] - box[0], box[3] - box[2]
    scale = 1e3 if unit == "µm" else 1.0
    raw = 0.2 * width * scale
    nice = max(v for v in (1, 2, 5, 10, 20, 50, 100, 200, 500, 1000) if v <= max(raw, 1))
    length = nice / scale
    corners = [(box[0] + 0.05 * width, box[2] + 0.06 * height),
               (box[1] - 0.05 * width - length, box[2] + 0.06 * height),
               (box[0] + 0.05 * width, box[3] - 0.12 * height),
               (box[1] - 0.05 * width - length, box[3] - 0.12 * height)]
    if avoid is not None and len(avoid):
        def covered(c):
            x, y = avoid.T
            return np.count_nonzero((x > c[0] - 0.02 * width) & (x < c[0] + length + 0.02 * width)
                                    & (y > c[1] - 0.03 * height) & (y < c[1] + 0.09 * height))
        x0, y0 = min(corners, key=covered)
    else:
        x0, y0 = corners[0]
    ax.plot([x0, x0 + length], [y0, y0], color="black", lw=4, solid_capstyle="butt")
    words = f"{nice / 1000:g} mm" if unit == "µm" and nice >= 1000 else f"{nice:g} {unit}"
    ax.text(x0 + length / 2, y0 + 0.02 * (box[3] - box[2]), words, ha="center",
            va="bottom", fontsize=10, bbox={"boxstyle": "round,pad=0.15", "fc": "white",
                                            "alpha": 0.8, "ec": "none"})


def chart_pngs(sol: PairSolution, summary: dict) -> dict[str, bytes]:
    """The pictures of a pair drawn from its results alone, without its fields, as PNG bytes
    by file name: flank_pressure.png (:func:`flank_pressure_figure`; none where the model
    keeps no grid pressures) and root_stress.png (:func:`root_stress_figure`). Bytes, not
    files: the output stage may have them drawn in another process while it forms the fields,
    and writes every file itself."""
    drawn = {}
    fig = flank_pressure_figure(sol, summary)
    if fig is not None:
        drawn["flank_pressure.png"] = png_bytes(fig, 100)
    drawn["root_stress.png"] = png_bytes(root_stress_figure(sol, summary), 100)
    return drawn


def flank_pressure_figure(sol: PairSolution, summary: dict):
    """The contact pressure along each loaded tooth's flank, the tip round shaded, with Hertz
    (p0, b at the tooth's contact point, centred on its flank load) and the half-plane
    reference's flank pressure (p ref) beside it; one legend for all panels above them, each
    panel's values in its title. None if the model keeps no grid pressures."""
    flanks = sol.detail.flank_pressures()
    if not flanks:
        return None
    plt = pyplot()
    teeth = {t.tooth: t for t in sol.teeth}
    n = len(flanks)
    cols = min(n, 3)
    rows = -(-n // cols)
    fig = plt.figure(figsize=(5.2 * cols, 3.9 * rows + 0.5))
    grid = fig.add_gridspec(rows, cols)
    # only the panels drawn: an axes made and hidden costs as much as one drawn
    axes = [fig.add_subplot(grid[k // cols, k % cols]) for k in range(n)]
    spikes = [(a, _flank_panel(a, f, teeth[f.tooth])) for a, f in zip(axes, flanks)]
    i = summary["inputs"]
    fig.suptitle(f"contact pressure along the loaded flanks: T {i['torque_Nm']:g} N·m, β "
                 f"{i['position_deg']:.3g}°, quality {i['quality']}", fontsize=10)
    # one label for each direction, not one on every panel: the panels share both quantities
    fig.supxlabel("distance along gear 1's profile from its tip corner [µm]", fontsize=10)
    fig.supylabel("contact pressure [MPa]", fontsize=10)
    margins(fig, left=0.95, right=0.2, bottom=0.65, top=1.3, wspace=0.55, hspace=0.75)
    shown = {}
    for a in axes:
        for h, label in zip(*a.get_legend_handles_labels()):
            shown.setdefault(label, h)
    fig.legend(shown.values(), shown.keys(), loc="upper center", ncol=len(shown), fontsize=8.5,
               bbox_to_anchor=(0.5, 1.0 - 0.45 / fig.get_size_inches()[1]), frameon=False)
    for a, callout in spikes:
        if callout is not None:
            place_callouts(a, [callout])
    return fig


def _flank_panel(a, f, t) -> Callout | None:
    """The pressure along one loaded flank ``f`` (a :class:`~.case.FlankPressure`) of tooth
    ``t`` (its :class:`~.case.ToothResult`) on the axes ``a``, with Hertz and the half-plane
    reference; the label of an edge peak that runs off the top, placed once the figure is
    laid out (None where there is none)."""
    curve = pressure_curve(f, t)
    a.plot(curve.s_um, f.pressure, color="C0", lw=1.6, label="FE")
    if curve.round_um is not None:
        a.axvspan(*curve.round_um, color="C3", alpha=0.12, label="gear 1's tip round")
    a.axvline(0.0, color="k", lw=0.6, ls=":", label="tip corner")
    values = []
    if curve.hertz is not None:
        a.plot(curve.s_um, curve.hertz, "--", color="C1", lw=1.3,
               label="Hertz (p0, b at the contact point)")
        values.append(f"Hertz p0 {t.hertz_p0_MPa:.0f}")
    if t.halfplane_flank_MPa:
        a.axhline(t.halfplane_flank_MPa, color="C2", ls=":", lw=1.3,
                  label="p ref (flank): half-planes, the exact gap")
        values.append(f"p ref {t.halfplane_flank_MPa:.0f}")
    a.set_xlim(*curve.window_um)
    a.set_ylim(0, curve.top)
    spike = None
    if curve.top < f.pressure.max():       # the edge spike runs off the top: say so
        k = int(np.argmax(f.pressure))
        spike = Callout(f"edge peak {f.pressure[k]:.0f} MPa\n(off the scale)",
                        (curve.s_um[k], curve.top), (1.0, -0.5),
                        {"fontsize": 8, "bbox": PLAIN_BOX,
                         "arrowprops": {"arrowstyle": "->", "lw": 0.8}})
    where = "on its tip round" if t.peak_on_round else "on the flank"
    if t.edge_contact:
        values.insert(0, f"flank {t.flank_p_MPa:.0f}")
    a.set_title(f"tooth {t.tooth}: {t.load_N:.0f} N, peak {t.p_max_MPa:.0f} MPa {where}"
                + (f"\n{', '.join(values)} MPa" if values else ""), fontsize=9, y=TITLE_Y)
    a.locator_params(axis="y", nbins=6)
    a.grid(alpha=0.3)
    return spike


#: the box of a label on a chart
PLAIN_BOX = {"boxstyle": "round,pad=0.2", "fc": "white", "ec": "none", "alpha": 0.85}


def root_stress_figure(sol: PairSolution, summary: dict):
    """Root σ1 of each loaded tooth, gear 1 and gear 2 side by side, the allowable bending
    stress as a line and each bar's safety factor on it; the legend where it covers none of
    them."""
    plt = pyplot()
    loaded = [t for t in sol.teeth if t.load_N > 0]
    allow = summary["inputs"].get("allowable_bending_MPa")
    x = np.arange(len(loaded))
    # 0.8 in a bar: its value and S_F over it stay apart from the next bar's
    fig, ax = plt.subplots(figsize=(max(6.0, 1.6 * len(loaded) + 2.5), 4.6))
    for k, q in enumerate((ROOT1, ROOT2)):
        v = np.array([getattr(t, q.attribute) for t in loaded])
        bars = ax.bar(x + (k - 0.5) * 0.38, v, 0.36, label=q.label)
        for b, value in zip(bars, v):
            text = f"{value:.0f}" + (f"\nS_F {factor_cell(allow / value)}"
                                     if allow and value > 0 else "")
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
                 f"{i['torque_Nm']:g} N·m, β {i['position_deg']:.3g}°", fontsize=10, y=TITLE_Y)
    ax.grid(axis="y", alpha=0.3)
    margins(fig, left=0.8, right=0.2, bottom=0.75, top=0.6)
    place_legend(ax, fontsize=8)
    return fig

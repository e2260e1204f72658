"""The mesh cycle's picture (matplotlib): each headline stress, the load shares and the
transmission error over the positions, with the verdict of the safety factors drawn on the
stress panels."""

from __future__ import annotations

from pathlib import Path

from ....figures import margins, pyplot, save_png
from ....figures.labels import place_legend
from ....quantities import FACTORS, QUANTITIES

#: the verdict drawn on a cycle's stress panels: the safety factors of each panel
CYCLE_VERDICT = {1: (FACTORS["safety_bending_gear1"], FACTORS["safety_bending_gear2"]),
                 2: (FACTORS["safety_contact"],)}


def cycle_png(path: Path, rows: list[dict], title: str, stresses: dict[str, str],
              allowables=None) -> Path:
    """:func:`cycle_figure` written to ``path``."""
    return save_png(cycle_figure(rows, title, stresses, allowables), path, 110)


def cycle_figure(rows: list[dict], title: str, stresses: dict[str, str], allowables=None):
    """Load share per tooth, the root stresses, the contact stresses (``stresses``: row key →
    label) and gear 1's rotation against position, on linear axes, from the rows of
    :func:`fegear.toothpair.summary.cycle_rows`. With ``allowables`` the stress panels carry
    the verdict: the allowable as a line (or, where it is over twice the largest stress, in
    the legend) and the smallest S_F and S_H marked at their β. Each legend where it covers
    no curve."""
    plt = pyplot()

    beta = [r["position_deg"] for r in rows]
    fig, ax = plt.subplots(4, 1, figsize=(8, 12), sharex=True)
    for k in (k for k in rows[0] if k.startswith("share_")):
        v = [r[k] for r in rows]
        if any(x > 0 for x in v):
            ax[0].plot(beta, v, marker="o", ms=3, label=f"tooth {k[6:]}")
    ax[0].set_ylabel("load share")
    # the root stresses on their own axis: beside the contact pressures they would be flat
    bending = [k for k in stresses if QUANTITIES[k].allowable == "bending"]
    for panel, keys in ((1, bending), (2, [k for k in stresses if k not in bending])):
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
    for a in ax:
        a.grid(alpha=0.3)
    fig.suptitle(title, fontsize=10)
    # room for the title's lines (0.2 in each at 10 pt) over the first panel
    margins(fig, left=0.85, right=0.2, bottom=0.6, top=0.35 + 0.2 * (title.count("\n") + 1),
            hspace=0.15)
    for a, ncol in zip(ax, (3, 1, 1, 1)):
        place_legend(a, fontsize=8, ncol=ncol)
    return fig


def _verdict(ax, rows: list[dict], limit: float, name: str, factors) -> None:
    """The allowable ``limit`` (MPa) on a cycle's stress panel and each of ``factors``
    (:class:`~fegear.quantities.Factor`) marked where it is smallest, its value in the
    legend."""
    top = max(r[f.stress.key] for f in factors for r in rows)
    if limit <= 2.0 * top:
        ax.axhline(limit, color="C3", ls="--", lw=1.2, label=f"allowable {name} {limit:g} MPa")
    else:
        ax.plot([], [], " ", label=f"allowable {name} {limit:g} MPa (off the scale)")
    for f in factors:
        have = [r for r in rows if r.get(f.key) is not None]
        if not have:
            continue
        worst = min(have, key=lambda r: r[f.key])
        ax.plot(worst["position_deg"], worst[f.stress.key], "v", mfc="none", mec="C3", mew=1.5,
                ms=9, label=f"smallest {f.label} {worst[f.key]:.2f}, at β "
                            f"{worst['position_deg']:.3g}°")
    ax.legend(fontsize=8)

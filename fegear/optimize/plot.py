"""Search plots: the objective against each design variable (feasible designs filled,
infeasible ones open and grey, pruned ones at the bound they were pruned at, the best marked)
and the search's history (each trial and the best so far); with two objectives, their
front."""

from __future__ import annotations

from pathlib import Path

from ..figures import pyplot, save_png
from ..figures.labels import place_legend
from .design import OBJECTIVES

#: the objectives' axis labels
LABELS = {"safety": "smallest S: S_F1, S_F2, S_H flank", "te": "TE peak to peak [µrad]",
          "stiffness": "mean mesh stiffness [N·m/rad]"}


def search_pngs(table, variables: list[str], objectives: list[str], out: Path,
                title: str, baseline: float | None = None,
                relieved: float | None = None) -> dict[str, Path]:
    """``variables.png`` and ``history.png`` (and ``front.png`` with two objectives) from the
    trials ``table`` (pandas, :func:`~.search.load_trials`); ``baseline``/``relieved``: the
    objective of the baseline and the relieved baseline, drawn as lines."""
    plt = pyplot()
    done = table[table["state"] == "COMPLETE"]
    ok = done[done["feasible"].astype(str) == "True"]
    bad = done[done["feasible"].astype(str) != "True"]
    pruned = table[table["state"] == "PRUNED"]
    o = objectives[0]
    col = f"objective_{o}"
    files = {}
    best = (ok.loc[ok[col].idxmax()] if OBJECTIVES[o] == "maximize" else ok.loc[ok[col].idxmin()]
            ) if len(ok) else None
    n, rows = len(variables), len(objectives)
    fig, axes = plt.subplots(rows, n, figsize=(3.4 * n + 0.6, 3.2 * rows + 0.7), squeeze=False,
                             sharey="row", layout="constrained")
    for row, objective in enumerate(objectives):
        c = f"objective_{objective}"
        for ax, v in zip(axes[row], variables):
            if OBJECTIVES[objective] == "maximize":   # at 0: the worst a design can be
                ax.scatter(bad[v], [0.0] * len(bad), s=14, facecolors="none",
                           edgecolors="0.6", label="infeasible (at 0)")
            ax.scatter(ok[v], ok[c], s=16, color="C0", label="feasible")
            _pruned(ax, pruned, v)
            if best is not None:
                ax.scatter([best[v]], [best[c]], s=90, marker="*", color="C3", zorder=3,
                           label=f"best (trial {int(best['trial'])})")
            if objective == "safety":
                _baselines(ax, baseline, relieved)
            ax.set_xlabel(v)
            ax.grid(alpha=0.3)
        axes[row][0].set_ylabel(LABELS[objective])
    # one legend for every panel, under them: inside a panel it covers its points
    fig.legend(*axes[0][-1].get_legend_handles_labels(), loc="outside lower center",
               ncol=5, fontsize=8, frameon=False)
    fig.suptitle(title, fontsize=9)
    files["variables_png"] = save_png(fig, out / "variables.png", 120)
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(8.4, 3.6))
    ax.scatter(bad["trial"], [0.0] * len(bad), s=12, facecolors="none", edgecolors="0.6",
               label="infeasible (at 0)")
    ax.scatter(ok["trial"], ok[col], s=12, color="C0", label="feasible")
    _pruned(ax, pruned, "trial")
    if len(ok):
        ordered = ok.sort_values("trial")
        run = ordered[col].cummax() if OBJECTIVES[o] == "maximize" else ordered[col].cummin()
        ax.step(ordered["trial"], run, where="post", color="C3", label="best so far")
    _baselines(ax, baseline, relieved)
    ax.set_xlabel("trial")
    ax.set_ylabel(LABELS[o])
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))  # beside the trials
    ax.set_title(title, fontsize=9)
    fig.tight_layout()
    files["history_png"] = save_png(fig, out / "history.png", 120)
    plt.close(fig)

    if len(objectives) > 1:
        a, b = (f"objective_{k}" for k in objectives[:2])
        signs = [1.0 if OBJECTIVES[k] == "maximize" else -1.0 for k in objectives[:2]]
        pts = list(zip(ok[a] * signs[0], ok[b] * signs[1]))
        front = [not any(q[0] >= p[0] and q[1] >= p[1] and q != p for q in pts) for p in pts]
        fig, ax = plt.subplots(figsize=(5.6, 4.2))
        ax.scatter(ok[a], ok[b], s=14, color="0.6", label="feasible")
        on = ok[front]
        on = on.sort_values(a)
        ax.plot(on[a], on[b], "o-", color="C3", ms=5, label="Pareto front")
        ax.set_xlabel(LABELS[objectives[0]])
        ax.set_ylabel(LABELS[objectives[1]])
        ax.grid(alpha=0.3)
        ax.set_title(title, fontsize=9)
        fig.tight_layout()
        place_legend(ax, fallback="headroom", fontsize=7)
        files["front_png"] = save_png(fig, out / "front.png", 120)
        plt.close(fig)
    return files


def _pruned(ax, pruned, x: str) -> None:
    """The pruned trials (:mod:`.bar`) at the bound of their objective they were pruned at,
    against ``x``: their objective is at most that."""
    if len(pruned):
        ax.scatter(pruned[x], pruned["objective_bound"], s=14, marker="v", facecolors="none",
                   edgecolors="C1", label="pruned (at most)")


def _baselines(ax, baseline: float | None, relieved: float | None) -> None:
    """The baselines' smallest safety factors (every factor, a loaded round's S_H included:
    solved again at `standard`) as horizontal lines."""
    for value, label, style in ((baseline, "baseline (standard)", "--"),
                                (relieved, "relieved baseline (standard)", ":")):
        if value is not None:
            ax.axhline(value, color="0.3", ls=style, lw=1, label=f"{label}: {value:.2f}")

"""Benchmark plot: run time against error for each ladder, with CalculiX beside it."""

from __future__ import annotations

from pathlib import Path

from ..figures import pyplot, save_png


def ladder_png(path: Path, ladders, targets) -> Path:
    """Run time against error, log-log: one line per ladder (:class:`fegear.verify.bench.Ladder`)
    through its levels, CalculiX on the same meshes as crosses, each target as a box."""
    plt = pyplot()

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
    return save_png(fig, path, 120)

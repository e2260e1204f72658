"""Benchmark plot: run time against error for each ladder, with CalculiX beside it."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from ..figures import pyplot, save_png


@dataclass(frozen=True)
class Series:
    """One line of the plot: its name, (time s, error %, label) per level, CalculiX's (time,
    error) points beside it (``peer_note``: what its error is measured on), and its target
    box (error %, time s) if it has one."""

    name: str
    points: list
    peer: list = field(default_factory=list)
    target: tuple[float, float] | None = None
    peer_note: str = ""


def ladder_png(path: Path, series: list[Series]) -> Path:
    """Run time against error, log-log: one line per series through its levels, CalculiX on
    the same meshes as crosses, each target as a dotted box."""
    plt = pyplot()

    fig, ax = plt.subplots(figsize=(8, 5.5))
    every = [(p[0], max(p[1], 1e-4)) for s in series for p in s.points + s.peer]
    lo_t = min(x for x, _ in every) / 2.0   # the target boxes start below the data
    lo_e = min(y for _, y in every) / 2.0
    for k, s in enumerate(series):
        colour = f"C{k}"
        t = [p[0] for p in s.points]
        e = [max(p[1], 1e-4) for p in s.points]
        ax.plot(t, e, "o-", color=colour, label=f"fegear: {s.name}")
        for i, (x, y, label) in enumerate(zip(t, e, [p[2] for p in s.points])):
            ax.annotate(label, (x, y), textcoords="offset points", fontsize=7,
                        xytext=(4, 4) if i % 2 == 0 else (4, -11))
        if s.peer:
            ax.plot(*zip(*[(x, max(y, 1e-4)) for x, y in s.peer]), "x--", color=colour,
                    label=f"CalculiX: {s.name}{s.peer_note}")
        if s.target:
            err, sec = s.target
            ax.add_patch(plt.Rectangle((lo_t, lo_e), sec - lo_t, err - lo_e, fill=False,
                                       ls=":", color=colour))
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("run time [s] (fegear: all stages after import; CalculiX: its wall time)")
    ax.set_ylabel("error against the reference [%]")
    ax.set_title("run time against error (dotted boxes: targets)", fontsize=10)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    fig.tight_layout()
    return save_png(fig, path, 120)

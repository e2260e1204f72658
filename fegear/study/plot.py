"""Study plots: the headline stresses and the safety factors against each varied input.

:func:`~.results.study_plot` gathers what one picture shows from the study table into a
:class:`StudyPlot` (named data, tested on its own); :func:`study_png` draws it.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from ..figures import pyplot, save_png
from ..quantities import EDGE_LOAD, FACTORS

#: the panels, a row per concern: bending, contact, the rest and the key
PANELS = (("root_stress_gear1_MPa", "root_stress_gear2_MPa", "bending"),
          ("contact_pressure_MPa", "flank_contact_pressure_MPa", "contact"),
          ("von_mises_max_MPa", "edge", "key"))
#: the safety factors each safety panel draws: key → (marker, line style)
SAFETY_PANELS = {"bending": {"safety_bending_gear1": ("o", "-"),
                             "safety_bending_gear2": ("s", ":")},
                 "contact": {"safety_contact": ("o", "-")}}


@dataclass(frozen=True)
class Line:
    """The cases at one level of the other varied inputs, in the order of the plotted input.

    ``stress``: each headline stress (MPa), the case's, or with ``positions`` the largest
    over its cycle; ``error``: its error bar (MPa, the case's discretisation-error estimate);
    ``safety``: S_F gear 1, S_F gear 2 and S_H, the case's or the smallest over its cycle
    (None where nothing loads it); ``edge_N``: the load on gear 1's tip rounds (N), the
    case's or the largest over its cycle; ``on_round``: whether a tip round carries load
    (over a cycle: at the position of its largest contact pressure); ``start``: the headline
    stresses at the first position β0 of each case's cycle (None without ``positions``)."""

    label: str
    x: tuple[float, ...]
    stress: dict[str, tuple[float, ...]]
    error: dict[str, tuple[float, ...]]
    safety: dict[str, tuple[float | None, ...]]
    edge_N: tuple[float, ...]
    on_round: tuple[bool, ...]
    start: dict[str, tuple[float, ...]] | None


@dataclass(frozen=True)
class StudyPlot:
    """One picture: the study's name, the plotted input ``x`` and its axis label, the lines,
    and what all of them share: the torque (N·m; None where the cases differ in it), the
    allowables (σ_FP, σ_HP in MPa; None where the cases differ in them, and then no safety
    factor is drawn) and the cycles' numbers of positions (empty: one position each)."""

    study: str
    x: str
    x_label: str
    lines: tuple[Line, ...]
    torque: float | None
    allowables: tuple[float, float] | None
    positions: tuple[int, ...]

    @property
    def title(self) -> str:
        """What holds for every point: the torque, the allowables, the cycle."""
        said = [f"T = {self.torque:g} N·m" if self.torque is not None
                else "" if self.x == "torque" else "T: see the key"]
        if self.allowables is not None:
            said.append("σ_FP {:g} MPa, σ_HP {:g} MPa".format(*self.allowables))
        if self.positions:
            said.append(f"worst over a cycle of {'/'.join(map(str, self.positions))} "
                        "positions (dashed: at its first position β0)")
        head = f"{self.study}: headline stresses and safety factors against {self.x}"
        return "\n".join([head, "; ".join(s for s in said if s)]).strip()


def study_png(path: Path, plot: StudyPlot, stresses: dict[str, str]) -> Path:
    """The picture of ``plot``: a row of panels for bending (root σ1 of each gear, S_F), one
    for contact (peak and flank pressure, S_H), and one with the largest von Mises stress,
    the load on gear 1's tip rounds and the key. ``stresses``: headline key → label. A tip
    round that carries load gets an open red ring on the contact-pressure and tip-load
    panels; the safety panels draw S = 1."""
    plt = pyplot()
    from matplotlib.ticker import MaxNLocator

    fig, axes = plt.subplots(3, 3, figsize=(14, 10.5), sharex=True)
    # shared; round steps: the default crowded shift 0.016 … 0.024 with 9 labels
    axes[0, 0].xaxis.set_major_locator(MaxNLocator(6, steps=[1, 2, 5, 10]))
    for row, keys in zip(axes, PANELS):
        for ax, k in zip(row, keys):
            if k in SAFETY_PANELS:
                _safety_panel(ax, plot, SAFETY_PANELS[k])
            elif k == "edge":
                _edge_panel(ax, plot)
            elif k in stresses:
                _stress_panel(ax, plot, k, stresses[k])
    _key(axes[2, 2], plot)
    axes[1, 2].xaxis.set_tick_params(labelbottom=True)  # the key takes the panel below it
    for ax in (*axes[2, :2], axes[1, 2]):
        ax.set_xlabel(plot.x_label)
    fig.suptitle(plot.title, fontsize=10)
    fig.tight_layout()
    return save_png(fig, path, 100)


def _key(ax, plot: StudyPlot) -> None:
    """The panel that explains the others: the lines (the other inputs' levels) and the
    marks."""
    from matplotlib.lines import Line2D

    ax.axis("off")
    grey = {"color": "0.3", "ms": 4}
    lines = [Line2D([], [], color=f"C{n}", marker="o", ms=4, label=line.label)
             for n, line in enumerate(plot.lines)]
    marks = []
    if plot.positions:
        marks += [Line2D([], [], marker="o", **grey, label="largest over the cycle"),
                  Line2D([], [], ls="--", lw=1, color="0.3",
                         label="at the cycle's first position β0")]
    if any(e for line in plot.lines for errs in line.error.values() for e in errs):
        marks.append(Line2D([], [], marker="|", ls="none", color="0.3", ms=10,
                            label="error bar: the case's discretisation-error estimate"))
    marks.append(Line2D([], [], color="red", marker="o", ms=10, mfc="none", ls="none",
                        label="a tip round of gear 1 carries load"))
    if plot.allowables is not None:
        marks += [Line2D([], [], marker=m, ls=ls, **grey, label=FACTORS[k].label)
                  for k, (m, ls) in SAFETY_PANELS["bending"].items()]
        marks.append(Line2D([], [], color="C3", ls="--", lw=1.2,
                            label="S = 1: the stress at its allowable"))
    if len(plot.lines) > 1 or plot.lines[0].label != "all":
        ax.add_artist(ax.legend(handles=lines, loc="upper left", fontsize=8,
                                title="other inputs", title_fontsize=8, frameon=False))
    ax.legend(handles=marks, loc="lower left", fontsize=8, frameon=False)


def _stress_panel(ax, plot: StudyPlot, k: str, label: str) -> None:
    for n, line in enumerate(plot.lines):
        ax.errorbar(line.x, line.stress[k], yerr=line.error[k], color=f"C{n}", marker="o",
                    ms=4, capsize=3)
        if line.start is not None:
            ax.plot(line.x, line.start[k], color=f"C{n}", ls="--", lw=1, alpha=0.8)
        if k == "contact_pressure_MPa":
            _rings(ax, line.x, line.stress[k], line.on_round)
    ax.set_ylabel(f"{label} [MPa]" + ("\n(largest over the cycle)" if plot.positions else ""))
    ax.grid(alpha=0.3)


def _edge_panel(ax, plot: StudyPlot) -> None:
    for n, line in enumerate(plot.lines):
        ax.plot(line.x, line.edge_N, color=f"C{n}", marker="o", ms=4)
        _rings(ax, line.x, line.edge_N, [e > 0 for e in line.edge_N])
    ax.set_ylabel(EDGE_LOAD.axis + ("\n(largest over the cycle)" if plot.positions else ""))
    ax.set_ylim(bottom=0.0)
    ax.grid(alpha=0.3)


def _rings(ax, xs, ys, where) -> None:
    ax.plot([a for a, e in zip(xs, where) if e], [b for b, e in zip(ys, where) if e], "o",
            ms=11, mfc="none", color="red")


def _safety_panel(ax, plot: StudyPlot, factors: dict[str, tuple[str, str]]) -> None:
    """The factors (key → marker, line style; the key explains them) of every line, and
    S = 1. Nothing but a note where the cases differ in their allowables."""
    which = " / ".join(FACTORS[k].label for k in factors)
    ax.set_ylabel(f"{which} [-]" + ("\n(smallest over the cycle)" if plot.positions else ""))
    ax.grid(alpha=0.3)
    if plot.allowables is None:
        ax.text(0.5, 0.5, "the cases differ in their allowables:\nsee results.md",
                transform=ax.transAxes, ha="center", va="center", fontsize=9)
        return
    for n, line in enumerate(plot.lines):
        for k, (marker, ls) in factors.items():
            pts = [(a, s) for a, s in zip(line.x, line.safety[k]) if s is not None]
            ax.plot([a for a, _ in pts], [s for _, s in pts], color=f"C{n}", marker=marker,
                    ms=4, ls=ls)
    ax.axhline(1.0, color="C3", ls="--", lw=1.2)
    ax.set_ylim(bottom=0.0)

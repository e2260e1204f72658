"""What a revolution gives a designer (``fegear solve --revolution``): the table it prints
(:func:`revolution_table`) and its files (:func:`write_revolution_outputs`): a row per
position, each tooth's largest stresses, the loaded rotation's harmonics, their pictures and a
ParaView frame a pitch."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from ....files import write_csv
from ....quantities import FACTORS, PEAK, ROOT1, ROOT2
from ...case import HEADLINE
from ...present.tables import aligned_table
from ...present.writers import write_cycle_series
from .plot import revolution_png, revolution_teeth_png
from .solve import amplitudes, gear1_turn_deg, loaded_rotation, median_tooth

if TYPE_CHECKING:   # what the plug-in hands its writer
    from ..base import Writing


def revolution_table(rev: dict) -> str:
    """The text ``fegear solve --revolution`` prints: the worst of each headline with its tooth
    and position, the smallest safety factors, the most loaded teeth of each gear against the
    median tooth, and the loaded rotation with its largest harmonics."""
    worst = rev["worst"]
    lines = aligned_table(["worst over the revolution", "    MPa", "tooth", "β [deg]"], [
        [HEADLINE[k], f"{worst[k]['max']:.1f}",
         "-" if worst[k]["tooth"] is None else f"{worst[k]['gear']}:{worst[k]['tooth']}",
         f"{worst[k]['at_position_deg']:.2f}"] for k in HEADLINE], labels=1)
    lines += ["", "smallest safety factors: " + ", ".join(
        f"{f.label} {worst[k]['min']:.2f} at β {worst[k]['at_position_deg']:.2f}°"
        for k, f in FACTORS.items() if k in worst)]
    for q in (ROOT1, ROOT2, PEAK):
        per = rev["per_tooth"][q.key]
        if not per:
            continue
        cut = rev["per_tooth"]["cut"][f"gear{q.gear}"]
        median = median_tooth(per, cut)
        top = sorted(per.items(), key=lambda kv: -kv[1])[:4]
        lines.append(f"{q.label}: median tooth {median:.1f} MPa; most loaded " + ", ".join(
            f"tooth {t}{'*' if t in cut else ''} {v:.1f} ({100 * (v / median - 1):+.0f} %)"
            for t, v in top)
            + (f" (*: seen in part, teeth {', '.join(map(str, cut))}: the revolution's ends "
               "cut their pass)" if cut else ""))
    te = rev["rotation_urad"]
    top = sorted(rev["spectrum"], key=lambda h: -h["amplitude_urad"])[:5]
    lines.append(f"loaded rotation (transmission error): {te['min']:.1f} ... {te['max']:.1f} µrad "
                 f"({te['peak_to_peak']:.1f} peak to peak); largest harmonics (order per turn "
                 "of gear 1: amplitude): " + ", ".join(
                     f"{h['order']}: {h['amplitude_urad']:.2f} µrad" for h in top))
    return "\n".join(lines)


def write_revolution_outputs(revolution: dict, writing: Writing) -> dict[str, Path]:
    """A revolution's files (its summary entry ``revolution``, the solved job's positions and
    rows in ``writing``): revolution.csv (a row per position, gear 1's turn first),
    revolution_teeth.csv (each tooth's largest stresses), revolution_spectrum.csv (the
    loaded rotation's harmonics), revolution.png and revolution_teeth.png (``pictures``)
    and revolution.pvd (``fields``): a frame a pitch, at the pitch's position of the largest
    gear-1 root stress (every position's fields would be z1 times a cycle's series)."""
    sols, rows, out, title = (writing.solved.solutions, writing.solved.rows, writing.out,
                              writing.title)
    turn = gear1_turn_deg(sols)
    harmonics = amplitudes(loaded_rotation(sols))
    z1 = revolution["pitches"]
    cols = ["gear1_turn_deg", *rows[0]]
    files = {"revolution_csv": write_csv(out / "revolution.csv", cols, (
        [t, *(r[c] for c in cols[1:])] for t, r in zip(turn, rows)))}
    per = revolution["per_tooth"]
    teeth = [(1, t) for t in per["root_stress_gear1_MPa"]] + \
        [(2, t) for t in per["root_stress_gear2_MPa"]]
    files["revolution_teeth_csv"] = write_csv(
        out / "revolution_teeth.csv", ("gear", "tooth", "root_stress_MPa",
                                       "contact_pressure_MPa", "whole_pass"),
        ((g, t, per[f"root_stress_gear{g}_MPa"][t],
          per["contact_pressure_MPa"].get(t, "") if g == 1 else "",
          t not in per["cut"][f"gear{g}"]) for g, t in teeth))
    files["revolution_spectrum_csv"] = write_csv(
        out / "revolution_spectrum.csv", ("order", "mesh_order", "amplitude_urad"),
        ((h, h / z1, a) for h, a in enumerate(harmonics) if h > 0))
    if writing.pictures:
        files["revolution_png"] = revolution_png(out / "revolution.png", revolution, rows,
                                                 turn, harmonics, title)
        files["revolution_teeth_png"] = revolution_teeth_png(
            out / "revolution_teeth.png", per, revolution["worst"],
            writing.solved.job.allowables, title)
    if writing.fields:
        files["revolution_pvd"] = write_cycle_series(_pitch_peaks(sols, rows, z1), out,
                                                     "revolution")["pvd"]
    return files


def _pitch_peaks(sols, rows: list[dict], pitches: int) -> list:
    """Of each pitch's positions (``sols`` in order, as many a pitch), the one of the largest
    gear-1 root stress."""
    per = len(sols) // pitches
    return [sols[k * per + max(range(per), key=lambda i: rows[k * per + i][
        "root_stress_gear1_MPa"])] for k in range(pitches)]

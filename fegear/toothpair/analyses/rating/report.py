"""What a life rating gives a designer (``fegear solve --spectrum``, docs/rating.md): the
levels with their solved torques and largest stresses, each mode's limiting tooth, Miner's
sum, life and safety factor at the required life, and the verdict; as the terminal shows it,
as rating.csv's rows (:func:`write_rating_outputs`) and as the report page's sections."""

from __future__ import annotations

from pathlib import Path

from ....quantities import LEVEL_STRESSES
from ...present.html_parts import escape, safety_cell, table
from ...present.writers import write_rows

#: a level's stresses as the table heads them: each gear's root stress and the flank pressure
#: (gear 1's teeth's: the flanks in contact carry the same)
LEVEL_KEYS = {f"{key}_MPa": LEVEL_STRESSES[key][0].short for key in ("root1", "root2", "flank1")}


def rating_table(r: dict) -> str:
    """The rating as tables: the levels, the modes, the material and factors, the verdict."""
    lines = ["| level | torque N·m | solved N·m | cycles | "
             + " | ".join(f"{v} MPa" for v in LEVEL_KEYS.values()) + " |",
             "|---:|---:|---:|---:|" + "---:|" * len(LEVEL_KEYS)]
    for k, level in enumerate(r["levels"], 1):
        lines.append(f"| {k} | {level['torque_Nm']:g} | {level['solved_torque_Nm']:.4g} | "
                     f"{level['cycles']:.3g} | "
                     + " | ".join(f"{level[key]:.1f}" for key in LEVEL_KEYS) + " |")
    lines += ["", "| mode | limit MPa | S-N k | tooth | damage by level | Miner | life | S at "
              "life |", "|---|---:|---:|---:|---|---:|---:|---:|"]
    for mode, m in r["modes"].items():
        tooth = "all" if m["tooth"] is None else str(m["tooth"])
        damage = " / ".join(damage_text(d) for d in m["damage"])
        lines.append(f"| {mode} | {m['limit_MPa']:.0f} | {m['exponent']:.1f} | {tooth} | "
                     f"{damage} | {damage_text(m['miner'])} | {life_text(m)} | "
                     f"{safety_text(m['safety'])} |")
    mat = r["material"]
    lines += ["", f"material {mat['name']} ({mat['treatment']}): sigma_Hlim "
              f"{mat['sigma_Hlim_MPa']:g} MPa, sigma_FE {mat['sigma_FE_MPa']:g} MPa "
              f"({mat['source']}); KA {r['KA']:g}, KV {r['KV']:g}; flank pressure without the "
              "tip round's (docs/rating.md)", f"verdict: {r['verdict']}"]
    return "\n".join(lines)


def rating_rows(r: dict) -> list[dict]:
    """rating.csv's rows: a row a level and mode, its stress, cycles and damage."""
    return [{"mode": mode, "gear": m["gear"], "tooth": "all" if m["tooth"] is None
             else m["tooth"], "level": k + 1, "torque_Nm": r["levels"][k]["torque_Nm"],
             "solved_torque_Nm": r["levels"][k]["solved_torque_Nm"],
             "stress_MPa": m["stress_MPa"][k], "tooth_cycles": m["cycles"][k],
             "damage": m["damage"][k], "limit_MPa": m["limit_MPa"], "exponent": m["exponent"],
             "miner": m["miner"], "safety_at_life": m["safety"]}
            for mode, m in r["modes"].items() for k in range(len(r["levels"]))]


def write_rating_outputs(rating: dict, out: Path) -> dict[str, Path]:
    """rating.csv: a row a level and mode of a life rating (docs/rating.md): the limiting
    tooth, the level's stress, the tooth's load cycles, the damage, the line's limit and
    exponent, Miner's sum and the safety factor at the required life."""
    return {"rating_csv": write_rows(out / "rating.csv", rating_rows(rating))}


def life_html(r: dict) -> str:
    """Each mode's Miner's sum, life and safety factor at the required life, and the
    material's lines (and that the levels were solved across the face, where they were)."""
    rows = []
    for mode, m in r["modes"].items():
        rows.append([mode, "all" if m["tooth"] is None else str(m["tooth"]),
                     damage_text(m["miner"]), life_text(m), safety_cell(m["safety"])])
    mat = r["material"]
    note = (f"<p>{escape(mat['name'])} ({escape(mat['treatment'])}): σ_Hlim "
            f"{mat['sigma_Hlim_MPa']:g} MPa, σ_FE {mat['sigma_FE_MPa']:g} MPa; "
            f"{escape(mat['source'])}. KA {r['KA']:g}, KV {r['KV']:g}."
            + (" Each level solved across the face: each tooth's stresses at its worst "
               "section." if r.get("across_face") else "") + "</p>")
    return table(["mode", "tooth", "Miner's sum", "life", "S at the required life"],
                 rows) + note


def spectrum_html(r: dict) -> str:
    """Each level's torque, solved torque, cycles and each mode's stress and damage."""
    rows = []
    modes = list(r["modes"].items())
    for k, level in enumerate(r["levels"]):
        rows.append([str(k + 1), f"{level['torque_Nm']:g}", f"{level['solved_torque_Nm']:.4g}",
                     f"{level['cycles']:.3g}",
                     *[f"{m['stress_MPa'][k]:.1f} / {damage_text(m['damage'][k])}"
                       for _, m in modes]])
    head = ["level", "torque N·m", "solved N·m", "cycles",
            *[f"{name}: MPa / damage" for name, _ in modes]]
    return table(head, rows)


def safety_text(x) -> str:
    """A safety factor at the required life as the tables show it: ∞ for "inf" (a mode no
    level loads)."""
    return "∞" if x == "inf" else f"{x:.2f}"


def damage_text(d) -> str:
    """A damage or Miner's sum as the tables show it: ∞ for "inf" (a level that breaks the
    tooth at once), 0 for none."""
    return "∞" if d == "inf" else "0" if d == 0 else f"{d:.3g}"


def life_text(m: dict) -> str:
    """A mode's life (``m``: its ``life_h`` and ``life_repeats``) as the tables show it: in
    hours, or without a speed in repeats of the spectrum; "unlimited" below the endurance
    limit."""
    if m["life_h"] is not None:
        return "unlimited" if m["life_h"] == "inf" else f"{m['life_h']:.3g} h"
    return "unlimited" if m["life_repeats"] == "inf" else f"{m['life_repeats']:.3g} spectra"

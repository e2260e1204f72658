"""What a life rating gives a designer (``fegear solve --spectrum``, docs/rating.md): the
levels with their solved torques and largest stresses, each mode's limiting tooth, Miner's
sum, life and safety factor at the required life, and the verdict; as the terminal shows it
and as rating.csv's rows."""

from __future__ import annotations

from ..quantities import LEVEL_STRESSES

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

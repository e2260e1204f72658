"""A pair rated for a life: each tooth's stress at each level of a spectrum against its
material's S-N lines (docs/rating.md).

Four ways a pair wears out are rated: each gear's root breaking (bending: its root stress
against σ_FE on the Y_NT line) and each gear's flank pitting (its flank pressure against σ_Hlim
on the Z_NT line). The flank pressure is the flanks' own, the tip round's left out: an edge
contact is a fault of the profile that the static S_H and the relief already name, not a
pitting load ISO 6336's lines were measured for. A gear-1 tooth meshes once a revolution of
gear 1 against gear 2, a gear-2 tooth z1/z2 times.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

from ..quantities import LEVEL_STRESSES
from .life import BENDING, CONTACT
from .materials import GearMaterial
from .miner import damage, safety_at_life

#: how a tooth wears out under a stress held against each allowable
WEAR = {"bending": "bending", "contact": "pitting"}
#: the modes rated: name → (the stress key of a level's teeth, gear, "bending" or "contact"):
#: each of :data:`fegear.quantities.LEVEL_STRESSES`
MODES = {f"{WEAR[q.allowable]} gear {gear}": (key, gear, q.allowable)
         for key, (q, gear) in LEVEL_STRESSES.items()}


def rate(levels: Sequence[Mapping[str, Mapping]], cycles: Sequence[float],
         z: tuple[int, int], material: GearMaterial, hours: float | None = None) -> dict:
    """Each mode's rating: the levels' stresses by tooth (``levels[i][key][tooth]``, MPa; a
    tooth None: every tooth alike), each level met ``cycles[i]`` revolutions of gear 1
    against gear 2 over the required life (``hours`` long where known). Per mode: the
    limiting tooth (the largest damage), its stress and damage per level, its Miner sum, the
    life (hours where the spectrum's are known, else as repeats of the spectrum) and the
    safety factor at the required life; then the verdict."""
    out = {}
    for mode, (key, gear, kind) in MODES.items():
        curve = (BENDING if kind == "bending" else CONTACT)[material.treatment]
        limit = material.sigma_FE if kind == "bending" else material.sigma_Hlim
        per = z[0] / z[1] if gear == 2 else 1.0   # a tooth's meshes a revolution
        n = [c * per for c in cycles]
        teeth = sorted({t for level in levels for t in level[key]}, key=_order)
        rated = []
        for tooth in teeth:
            stresses = [level[key].get(tooth, 0.0) for level in levels]
            rated.append((damage(stresses, n, limit, curve), tooth, stresses))
        d, tooth, stresses = max(rated, key=lambda r: (r[0], _order(r[1])))
        repeats = math.inf if d == 0 else 1.0 / d
        out[mode] = {
            "gear": gear, "tooth": tooth, "limit_MPa": limit, "exponent": curve.exponent,
            "stress_MPa": stresses, "cycles": n,
            "damage": [damage([s], [c], limit, curve) for s, c in zip(stresses, n)],
            "miner": d, "life_repeats": repeats,
            "life_h": None if hours is None else hours * repeats,
            "safety": safety_at_life(stresses, n, limit, curve)}
    return {"modes": out, "hours": hours, "verdict": verdict(out, hours)}


def verdict(modes: Mapping[str, dict], hours: float | None) -> str:
    """One line: PASS or FAIL at the required life, and the limiting mode with its tooth."""
    name, worst = min(modes.items(), key=lambda kv: kv[1]["safety"])
    tooth = "every tooth alike" if worst["tooth"] is None else f"tooth {worst['tooth']}"
    life = ("" if hours is None or worst["life_h"] is None else
            f"; life {_hours(worst['life_h'])} of {_hours(hours)} required")
    word = "PASS" if worst["miner"] <= 1.0 else "FAIL"
    broken = ("; a level beyond the static strength breaks it at once"
              if math.isinf(worst["miner"]) else "")
    return (f"{word}: {name} ({tooth}) limits: safety factor {worst['safety']:.2f} at the "
            f"required life, Miner's sum {worst['miner']:.3g}{life}{broken}")


def _hours(h: float) -> str:
    return "unlimited" if math.isinf(h) else f"{h:.3g} h"


def _order(tooth) -> tuple:
    return (tooth is not None, -1 if tooth is None else tooth)

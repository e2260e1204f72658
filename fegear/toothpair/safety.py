"""Safety factors of a solved pair: S = allowable / stress, per tooth, per position and for
the pair (docs/model.md, "Safety factors").

S_F (bending), per gear, divides the allowable root stress σ_FP by the root stress: the
largest σ1 in the fillets a tooth bends in tension. S_H (contact) divides the allowable contact
pressure σ_HP by the tooth's peak contact pressure wherever it sits, on the flank or on gear 1's
tip round: an edge that presses harder than the flank sets S_H, it is not hidden behind the
flank (on the baseline at 200 N·m the round reads 1880 MPa beside a 624 MPa flank: S_H 0.40,
S_H flank 1.19). S_H flank, from the flank pressure alone, stands beside it: what a tip relief
that keeps the load off the rounds would leave. A pair's factors divide by its headline
stresses (the largest over the teeth), so they are the smallest over its teeth.

The factors are read off a summary's stresses (:func:`with_safety`), so a study computes them
from its stored results at the allowables of its file without solving again.
"""

from __future__ import annotations

from collections.abc import Mapping

from ..fe import Allowables
from ..quantities import FACTORS

#: the allowables when none are given: 42CrMo's (σ_FP 558, σ_HP 745 MPa)
DEFAULT_ALLOWABLES = Allowables()

#: the pair's safety factors: key → (the allowable, the summary's headline stress it divides)
SAFETY = {f.key: (f.stress.allowable, f.stress.key) for f in FACTORS.values()}
#: a tooth's safety factors, from its own stresses in the summary's ``teeth``
TOOTH_SAFETY = {f.key: (f.stress.allowable, f.stress.tooth_key) for f in FACTORS.values()}
#: the summary's inputs that record the allowables (MPa)
ALLOWABLE_KEYS = {"bending": "allowable_bending_MPa", "contact": "allowable_contact_MPa"}


def allowables_of(values: Mapping[str, object]) -> Allowables:
    """The allowables among inputs given by name (``allowable-bending``,
    ``allowable-contact``; missing ones at the defaults), checked."""
    d = DEFAULT_ALLOWABLES
    return Allowables(values.get("allowable-bending", d.bending),
                      values.get("allowable-contact", d.contact))


def safety_factor(allowable: float, stress: float | None) -> float | None:
    """``allowable / stress``; None where the stress is missing or not positive (an unloaded
    contact has no limit)."""
    if stress is None or stress <= 0:
        return None
    return allowable / stress


def safety_factors(stresses: Mapping, allowables: Allowables,
                   table: Mapping[str, tuple[str, str]] = SAFETY) -> dict[str, float | None]:
    """The factors of ``table`` (key → (allowable, stress key)) from ``stresses`` (MPa)."""
    return {key: safety_factor(getattr(allowables, which), stresses.get(stress))
            for key, (which, stress) in table.items()}


def smallest(rows: list[dict]) -> dict[str, dict]:
    """Each pair factor's smallest value over a cycle's rows and the position where it
    occurs (``at_position_deg``); None where no row has a value."""
    out = {}
    for key in SAFETY:
        have = [r for r in rows if r.get(key) is not None]
        worst = min(have, key=lambda r: r[key]) if have else None
        out[key] = {"min": worst[key] if worst else None,
                    "at_position_deg": worst["position_deg"] if worst else None}
    return out


def with_safety(summary: dict, allowables: Allowables) -> dict:
    """A copy of a solve's summary (``fegear solve --json``) with the allowables among its
    inputs and every safety factor computed from its stresses: the pair's, each tooth's, and
    over a cycle each position's and their minima. The stresses are not touched."""
    out = dict(summary)
    out["inputs"] = {**summary.get("inputs", {}),
                     **{k: getattr(allowables, w) for w, k in ALLOWABLE_KEYS.items()}}
    out.update(safety_factors(summary, allowables))
    out["teeth"] = [{**t, **safety_factors(t, allowables, TOOTH_SAFETY)}
                    for t in summary.get("teeth", [])]
    cycle = summary.get("cycle")
    if cycle:
        rows = [{**r, **safety_factors(r, allowables)} for r in cycle.get("rows", [])]
        out["cycle"] = {**cycle, **smallest(rows), "rows": rows}
    return out

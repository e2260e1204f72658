"""A whole revolution of gear 1 (``fegear solve --revolution``): every pitch, so that every
tooth of a real pair meets its mates, its deviations and all.

The positions run over z1 pitches of gear 2 (gear 1 turns once), ``per_pitch`` in each. What a
designer reads of them: the worst of each headline stress with the position and the tooth
where it occurs (gear 1's for its root and for the contact, gear 2's for its root), the largest
of each stress per tooth, and gear 1's loaded rotation from its kinematic position over the
revolution (the loaded transmission error in its usual sense: the deviations' unloaded share
included, where a position's ``transmission_error_urad`` is the rotation beyond first touch)
with its spectrum in orders of gear 1's revolution: the mesh order is z1, a gear-1 runout adds
order 1 and the sidebands z1 ± 1, a gear-2 runout order z1/z2 and z1 ± z1/z2.
"""

from __future__ import annotations

import math

import numpy as np

from ....fe import Allowables
from ....quantities import PEAK, QUANTITIES
from ...case import HEADLINE, PairSolution
from ...safety import DEFAULT_ALLOWABLES, safety_factors

#: the largest harmonics of the spectrum a summary keeps
HARMONICS = 12


def per_tooth(sols: tuple[PairSolution, ...]) -> dict:
    """The largest stress each tooth carried over the positions: gear 1's root and contact
    pressure by gear-1 tooth, gear 2's root by gear-2 tooth (MPa); and under ``cut``, by gear,
    the teeth seen only in part.

    A tooth loaded at the first or the last position met the mesh partly outside the
    positions. Its pass is whole only where the revolution repeats for its gear: gear 1's
    when gear 2 is perfect (after z1 pitches gear 1 stands where it started, against
    identical teeth, so the pass that the end cuts off is the one the start holds). Gear 2
    turns z1/z2 of a turn, so its teeth at the ends are always cut: their largest stress here
    is a lower bound."""
    whole1 = not (sols[0].case.deviations.gear2 or sols[0].case.deviations.runout2.fr)
    ends = [t for s in (sols[0], sols[-1]) for t in s.teeth if t.load_N > 0]
    cut = {1: set() if whole1 else {t.tooth for t in ends},
           2: {t.tooth2 for t in ends if t.tooth2 is not None}}
    root1: dict[int, float] = {}
    contact: dict[int, float] = {}
    root2: dict[int, float] = {}
    for s in sols:
        for t in s.teeth:
            if t.load_N <= 0:
                continue
            root1[t.tooth] = max(root1.get(t.tooth, 0.0), t.root1_MPa)
            contact[t.tooth] = max(contact.get(t.tooth, 0.0), t.p_max_MPa)
            if t.tooth2 is not None:
                root2[t.tooth2] = max(root2.get(t.tooth2, 0.0), t.root2_MPa)
    return {"root_stress_gear1_MPa": dict(sorted(root1.items())),
            "contact_pressure_MPa": dict(sorted(contact.items())),
            "root_stress_gear2_MPa": dict(sorted(root2.items())),
            "cut": {"gear1": sorted(cut[1]), "gear2": sorted(cut[2])}}


def median_tooth(values: dict[int, float], cut: list[int]) -> float:
    """The median of the teeth's largest stresses, the teeth seen only in part left out (all
    of them where every tooth is)."""
    whole = [v for t, v in values.items() if t not in cut] or list(values.values())
    return float(np.median(whole))


def worst(sols: tuple[PairSolution, ...], allowables: Allowables = DEFAULT_ALLOWABLES) -> dict:
    """Each headline stress's largest over the positions, where (β in degrees) and on which
    tooth (gear 2's for its root stress, gear 1's otherwise; the von Mises maximum's: the
    tooth of the largest contact pressure, where it sits); each safety factor's smallest."""
    out = {}
    for key in HEADLINE:
        s = max(sols, key=lambda x: x.headline()[key])
        out[key] = {"max": s.headline()[key], "at_position_deg": math.degrees(s.case.beta),
                    "gear": 2 if QUANTITIES[key].gear == 2 else 1,
                    "tooth": _tooth_of(s, key)}
    for key in safety_factors(sols[0].headline(), allowables):
        values = [safety_factors(s.headline(), allowables)[key] for s in sols]
        k = int(np.argmin(values))
        out[key] = {"min": values[k], "at_position_deg": math.degrees(sols[k].case.beta)}
    return out


def _tooth_of(sol: PairSolution, key: str) -> int | None:
    """The tooth where ``sol`` carries its headline ``key``: gear 2's for its root, gear 1's
    otherwise."""
    loaded = [t for t in sol.teeth if t.load_N > 0]
    if not loaded:
        return None
    q = QUANTITIES[key]
    field = q.attribute or PEAK.attribute     # the von Mises maximum's: where the peak sits
    top = max(loaded, key=lambda t: getattr(t, field))
    return top.tooth2 if q.gear == 2 else top.tooth


def loaded_rotation(sols: tuple[PairSolution, ...]) -> np.ndarray:
    """Gear 1's loaded rotation over the positions (µrad): from its kinematic position under
    the torque, the deviations' unloaded share included."""
    return np.array([1e6 * s.rotation for s in sols])


def amplitudes(te: np.ndarray) -> np.ndarray:
    """The amplitude (µrad) of each harmonic 0, 1, … of ``te`` over one turn of gear 1 (its
    mean left out: harmonic 0 is 0)."""
    return 2.0 * np.abs(np.fft.rfft(te - te.mean())) / len(te)


def spectrum(te: np.ndarray, z1: int) -> list[dict]:
    """The loaded rotation's :data:`HARMONICS` largest harmonics over one turn of gear 1:
    order (harmonics per turn of gear 1; the mesh is z1), the mesh order it is (order / z1)
    and the amplitude (µrad), by order."""
    amplitude = amplitudes(te)
    orders = np.argsort(amplitude[1:])[::-1][:HARMONICS] + 1
    return [{"order": int(h), "mesh_order": float(h / z1),
             "amplitude_urad": float(amplitude[h])} for h in sorted(orders)]


def gear1_turn_deg(sols: tuple[PairSolution, ...]) -> np.ndarray:
    """Gear 1's turn (deg) at each position from the first: z2/z1 of gear 2's rolling angle."""
    p = sols[0].case.params
    beta = np.array([s.case.beta for s in sols])
    return np.degrees(beta - beta[0]) * p.z2 / p.z1


def revolution_summary(sols: tuple[PairSolution, ...],
                       allowables: Allowables = DEFAULT_ALLOWABLES) -> dict:
    """The summary's ``revolution``: positions, pitches, the worst of each headline with its
    position and tooth, the largest stresses per tooth, the loaded rotation's range and
    spectrum."""
    z1 = sols[0].case.params.z1
    te = loaded_rotation(sols)
    return {"positions": len(sols), "pitches": z1, "worst": worst(sols, allowables),
            "per_tooth": per_tooth(sols),
            "rotation_urad": {"min": float(te.min()), "max": float(te.max()),
                                        "mean": float(te.mean()),
                                        "peak_to_peak": float(te.max() - te.min())},
            "spectrum": spectrum(te, z1)}

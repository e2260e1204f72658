"""A tolerance class's samples as rows (:mod:`.solve`): what the chains gave gathered by
sample, and a sample's row (its deviations in brief, its status, its worst over its positions
and the safety factors they give)."""

from __future__ import annotations

import math

import numpy as np

from ....fe import Allowables
from ....tolerance import tooth_positions
from ...case import HEADLINE
from ...face import Face
from ...safety import safety_factors

#: the exact pair's key among what the chains gave by sample (its readings across the face)
EXACT = -1
#: … and the positions a chain did not solve its pairs at, (β, how many) each, where its run
#: ended early (:class:`~.chains.Enough`)
SKIPPED = -2
#: what a sample solved across the face gives beside its headlines: the face's load factor
K_HBETA = "K_Hbeta"


def gathered(chains) -> tuple[dict[int, list], dict[int, list]]:
    """By sample, its (β, headline or why) and what was read of it, over the chains'
    positions (:meth:`~.solve.OnKept.__call__`) in order; across the face, the exact pair's
    (β, headline) under :data:`EXACT`."""
    found: dict[int, list] = {}
    readings: dict[int, list] = {}
    for done in chains:
        for _, got, took in done:
            for k, each in got.items():
                found.setdefault(k, []).extend(each)
            for k, each in took.items():
                readings.setdefault(k, []).extend(each)
    return found, readings


#: why a pair that turns has the status "stopped": its run ended early (:class:`~.chains.Enough`)
STOPPED = ("the run ended before this pair was solved everywhere: enough pairs had shown "
           "what it asked")
#: … and why one has the status "left out": its run did not need it solved
LEFT_OUT = "not solved: its run knew its answer already (from a run it was solved in)"


def sample_row(k: int, brief: dict, jammed: str | None, got: list,
               allowables: Allowables, unfinished: tuple[str, str] | None = None) -> dict:
    """Sample k's row: its deviations in ``brief`` (:func:`brief_of`), its status and why, and
    where it turns its worst over its positions (``got``: (β, headline or why) pairs);
    ``unfinished``: the status and why of a pair that turns but was not solved everywhere
    ("stopped": :data:`STOPPED`, "left out": :data:`LEFT_OUT`), with the worst of those it
    was solved at, if any."""
    if jammed is not None:
        return {"sample": k, **brief, "status": "jammed", "why": jammed}
    failed = [why for _, why in got if isinstance(why, str)]
    if failed:
        return {"sample": k, **brief, "status": "failed", "why": failed[0]}
    if unfinished is not None:
        return {"sample": k, **brief, "status": unfinished[0], "why": unfinished[1],
                **(worst_of(got, allowables) if got else {})}
    return {"sample": k, **brief, "status": "solved", "why": "", **worst_of(got, allowables)}


def worst_of(got: list, allowables: Allowables) -> dict:
    """A sample's largest headline stresses over its positions ((β, headline) pairs; across
    the face each its worst section's, and K_Hβ), each with the position (degrees), and the
    safety factors they give."""
    out = {}
    for key in (*HEADLINE, K_HBETA):
        if key not in got[0][1]:
            continue
        beta, head = max(got, key=lambda g: g[1][key])
        out[key] = head[key]
        out[f"{key.removesuffix('_MPa')}_at_deg"] = math.degrees(beta)
    if K_HBETA in out:   # samples.csv says where across the face its stresses are
        out["stresses_at"] = "worst section"
    return {**out, **safety_factors(out, allowables)}


def brief_of(deviations, z: tuple[int, int], face: Face | None = None) -> dict:
    """A sample's deviations in a few numbers (µm), as a measuring machine reads them: each
    gear's cumulative pitch (the range of its teeth's positions, runout included) and largest
    single pitch, its largest profile slope and form and its runout, and the centre
    distance's; ``z``: the gears' numbers of teeth. Across the ``face`` (its own), each gear's
    largest helix slope and form too, and its misalignment."""
    out = {}
    for g, zg in zip((1, 2), z):
        teeth = deviations.teeth(g)
        position = tooth_positions(deviations, g, zg)
        out[f"gear{g}_cumulative_pitch_um"] = float(np.ptp(position))
        out[f"gear{g}_single_pitch_um"] = float(np.abs(position - np.roll(position, 1)).max())
        out[f"gear{g}_slope_um"] = max((abs(d.slope) for d in teeth.values()), default=0.0)
        out[f"gear{g}_form_um"] = max((abs(d.form) for d in teeth.values()), default=0.0)
        out[f"gear{g}_runout_um"] = getattr(deviations, f"runout{g}").fr
    out["centre_distance_um"] = deviations.centre_distance
    if face is not None:
        for g, helix in ((1, face.helix1), (2, face.helix2)):
            out[f"gear{g}_helix_slope_um"] = max((abs(s) for _, s, _ in helix), default=0.0)
            out[f"gear{g}_helix_form_um"] = max((abs(f) for _, _, f in helix), default=0.0)
        out["misalignment_um"] = face.misalignment
    return out

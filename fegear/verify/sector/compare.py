"""A design solved by both models: the product's ring model and the sector model, its full-FE
peer, side by side (``fegear bench --sector``)."""

from __future__ import annotations

from ...geometry import Gear1Profile, gear1_profile
from ...toothpair import HEADLINE, PairSolution, SolveCase, solve_pair
from .case import SectorCase


def cross_check(case: SolveCase, profile: Gear1Profile | None = None, **sector: object
                ) -> tuple[PairSolution, PairSolution]:
    """``case`` (one position) solved by the ring model and by the sector model (its own
    inputs ``sector``: ``extra_teeth``, ``penalty_factor``)."""
    from .solve import (
        solve_pair as sector_pair,  # lazy: heavy: scikit-fem, off `fegear bench`'s check
    )

    profile = profile if profile is not None else gear1_profile(case.params)
    return solve_pair(case), sector_pair(SectorCase.of(case, **sector), profile)


def cross_table(ring: PairSolution, sector: PairSolution) -> str:
    """Markdown: each headline stress and each loaded tooth's share and flank pressure by
    both models, with the sector model's difference (%)."""
    def row(label, a, b):
        diff = 100.0 * (b - a) / a if a else float("nan")
        return f"| {label} | {a:.1f} | {b:.1f} | {diff:+.2f} |"

    lines = ["| quantity | ring | sector | sector − ring [%] |", "|---|---:|---:|---:|"]
    a, b = ring.headline(), sector.headline()
    lines += [row(f"{label} [MPa]", a[k], b[k]) for k, label in HEADLINE.items()]
    ta = {t.tooth: t for t in ring.teeth}
    tb = {t.tooth: t for t in sector.teeth}
    for tooth in sorted(k for k in ta if k in tb and (ta[k].load_N > 0 or tb[k].load_N > 0)):
        lines.append(row(f"tooth {tooth} load share [%]", 100 * ta[tooth].load_share,
                         100 * tb[tooth].load_share))
        lines.append(row(f"tooth {tooth} flank pressure [MPa]", ta[tooth].flank_p_MPa,
                         tb[tooth].flank_p_MPa))
    lines.append(row("transmission error [µrad]", 1e6 * (ring.rotation - ring.first_touch),
                     1e6 * (sector.rotation - sector.first_touch)))
    return "\n".join(lines)

"""What the pictures of a tooth-pair solve mark, from its results: each gear's root hot spot,
the largest value of a field, a flank's pressure curve ready to draw, the solve's verdict
(its safety factors against their allowables) and the stretches of the gears the von Mises
picture shows. No drawing here: :mod:`.plot` draws them."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...geometry import gear1_profile
from ...quantities import FACTORS
from ..case import PairSolution
from ..edge import flank_centre


@dataclass(frozen=True)
class HotSpot:
    """The largest root stress of one gear in the drawn fields: gear (1, 2), where (fixed
    frame, mm) and σ1 there (MPa)."""

    gear: int
    point: np.ndarray
    value: float


def root_hot_spots(sol: PairSolution, bodies) -> tuple[HotSpot, ...]:
    """Each gear's largest σ1 in its fillets: the lower 30 % of its tooth height, where the
    solve reads its root stresses (docs/model.md, "Results")."""
    p = sol.case.params
    g1 = gear1_profile(p)     # the solve's own, kept: building it again costs 0.04 s
    root1 = float(g1.radius(np.array([g1.phi_space]))[0])
    tip1 = float(g1.radius(np.array([g1.tooth_center]))[0])
    root2, tip2 = p.r0 + 2 * p.e1, p.r0 - 2 * p.e1
    zones = {"gear1": (np.array([0.0, p.e]), lambda r: r <= root1 + 0.3 * (tip1 - root1)),
             "gear2": (np.zeros(2), lambda r: r >= root2 - 0.3 * (root2 - tip2))}
    out = []
    for b in bodies:
        if b.name not in zones:
            continue
        centre, inside = zones[b.name]
        mask = inside(np.hypot(*(b.points - centre).T))
        s1 = np.where(mask, b.data["s1"], -np.inf)
        i = int(np.argmax(s1))
        out.append(HotSpot(int(b.name[-1]), b.points[i], float(s1[i])))
    return tuple(out)


def field_max(bodies, name: str) -> tuple[np.ndarray, float]:
    """Where the largest value of a field lies over ``bodies`` (fixed frame) and its value."""
    best = max(bodies, key=lambda b: b.data[name].max())
    i = int(np.argmax(best.data[name]))
    return best.points[i], float(best.data[name][i])


@dataclass(frozen=True)
class PressureCurve:
    """A flank's pressure made ready to draw: the distance from the tip corner (µm, > 0 down
    the flank, < 0 on the round), the Hertz ellipse at the same points (MPa; None without a
    Hertz pair), the tip round's span (µm; None if the grid has no round), the window to show
    (µm) and the top of the pressure axis (MPa): the flank's scale when an edge spike would
    flatten the flank into the axis, the whole curve's otherwise."""

    s_um: np.ndarray
    hertz: np.ndarray | None
    round_um: tuple[float, float] | None
    window_um: tuple[float, float]
    top: float


#: an edge spike higher than this many times the flank's own scale is drawn off the axis
SPIKE_CLIP = 1.6


def pressure_curve(f, tooth) -> PressureCurve:
    """:class:`PressureCurve` of one :class:`~.case.FlankPressure` and its tooth result: the
    window spans the loaded stretch and a margin either side, the tip corner kept in view;
    Hertz is centred on the flank's load (the round's left out)."""
    s = f.from_corner * 1e3
    centre = flank_centre(s, f.pressure, f.on_round)
    hertz = None
    if tooth.hertz_p0_MPa and tooth.hertz_b_mm:
        b = tooth.hertz_b_mm * 1e3
        x = np.clip((s - centre) / b, -1.0, 1.0)
        hertz = tooth.hertz_p0_MPa * np.sqrt(1.0 - x * x)
    rnd = (float(s[f.on_round].min()), float(s[f.on_round].max())) if f.on_round.any() else None
    on = s[f.pressure > 0]
    # a margin of three half-widths, at most a third of the loaded stretch (nearly conformal
    # flanks have half-widths of a good part of a millimetre)
    margin = max(min(3 * tooth.half_width_mm * 1e3, np.ptp(on) / 3), 1e-3 * np.ptp(s))
    lo = max(min(float(on.min()) - margin, 0.0 if rnd is None else rnd[0]), float(s.min()))
    window = (lo, min(float(on.max()) + margin, float(s.max())))
    # the flank's scale: its reported pressure (the spike's tail next to the round left out)
    flank_p = tooth.flank_p_MPa if tooth.edge_contact else float(f.pressure.max())
    scale = max(flank_p, tooth.hertz_p0_MPa or 0.0, tooth.halfplane_flank_MPa or 0.0)
    peak = float(f.pressure.max())
    top = 1.1 * max(peak, scale) if peak <= SPIKE_CLIP * scale else SPIKE_CLIP * scale
    return PressureCurve(s, hertz, rnd, window, top)


@dataclass(frozen=True)
class VerdictCaption:
    """A solve's verdict in two lines: each safety factor beside its allowable, then the
    smallest and whether it is at least 1 (``colour``: green if so, red if not)."""

    text: str
    colour: str

    @classmethod
    def of(cls, summary: dict) -> VerdictCaption:
        s, i = summary, summary["inputs"]
        peak, flank = FACTORS["safety_contact"], FACTORS["safety_contact_flank"]
        bending = {FACTORS[k].label: s[k] for k in ("safety_bending_gear1",
                                                     "safety_bending_gear2")}
        contact = {peak.label: s[peak.key]}
        where = "a tip round's" if s["contact_peak_on_tip_round"] else "the flank's"
        line = (", ".join(f"{k} {v:.2f}" for k, v in bending.items() if v)
                + f" (σ_FP {i['allowable_bending_MPa']:g} MPa)")
        if s[peak.key]:
            line += (f";  {peak.label} {s[peak.key]:.2f} at {where} "
                     f"{s[peak.stress.key]:.0f} MPa")
            if s["contact_peak_on_tip_round"] and s[flank.key]:
                line += (f", {flank.label} {s[flank.key]:.2f} at "
                         f"{s[flank.stress.key]:.0f} MPa")
            line += f" (σ_HP {i['allowable_contact_MPa']:g} MPa)"
        have = {k: v for k, v in {**bending, **contact}.items() if v}
        if not have:
            return cls(line, "black")
        name = min(have, key=have.get)
        if have[name] >= 1.0:
            return cls(f"{line}\nevery safety factor at least 1: the pair carries the load "
                       "at this position", "#1e6b2f")
        return cls(f"{line}\n{name} {have[name]:.2f} below 1: the stress exceeds the "
                   "allowable", "#b0201a")


def labelled_box(points: np.ndarray, m: float) -> tuple[float, float, float, float]:
    """A box around the marked ``points``, at least 4:3, with room about them for their
    labels: 1.2 m (``m``: the module, mm), or on a long arc of loaded teeth a tenth of its
    extent, each side."""
    pad = max(1.2 * m, 0.1 * np.ptp(points, axis=0).max())
    lo, hi = points.min(axis=0) - pad, points.max(axis=0) + pad
    w, h = hi - lo
    if h < 0.75 * w:
        mid = 0.5 * (lo[1] + hi[1])
        lo[1], hi[1] = mid - 0.375 * w, mid + 0.375 * w
    return float(lo[0]), float(hi[0]), float(lo[1]), float(hi[1])


def peak_zoom(fine, half_width: float, m: float) -> float:
    """Half the side (mm) of the contact peak's picture: within the submodels ``fine`` where
    they resolve it, else some contact half-widths (``half_width``, mm) or a share of the
    module ``m`` (mm)."""
    if fine:
        near = max(np.ptp(b.points, axis=0).max() for b in fine)
        return min(0.6 * near, max(12.0 * half_width, 0.02 * m))
    return max(8.0 * half_width, 0.05 * m)

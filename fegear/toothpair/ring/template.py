"""One tooth pitch of each gear, meshed once per geometry: the template sectors of the ring model.

Every tooth of a gear has the same shape, so gear k's sector n is its template turned by n
pitches. Gear 1's template runs from the middle of tooth 0's tip (polar angle
``tooth_center``) one pitch counter-clockwise: tooth 0's leading flank (the one a positive
torque loads), the tooth space and its root, tooth 1's trailing flank. Gear 2's runs from a
tooth tip (ξ = 0) to the next. Both are cut radially down to gear 1's bore (held: its elastic
part vanishes there, the rigid rotation carries the torque) and out to gear 2's rim (held);
the two cuts of a template carry matching nodes (:class:`~fegear.fe.Periodic`).

The contact is not resolved by these meshes: its near field is the half-plane's
(:mod:`fegear.contact.halfplane`), so the flanks need only be fine enough to carry a load a few
elements deep, and the sizes follow the module and the tip round, not the load. Refined: the
root zones (the lower ``ROOT_BAND`` of the tooth height, for the root stress), both flanks,
gear 1's tip rounds and the tangent points where a round meets the flank.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...fe import BodyGeometry, Periodic, Refinement, Segment
from ...geometry import Cycloid, PairParameters, RoundedProfile
from ..segments import (
    ROOT_BAND,
    Layout,
    PolarCurve,
    gear2_outline,
    gear2_polar,
    profile_segments,
    root_half_angle,
)

#: how precisely gmsh places the nodes along the templates' curves (its
#: Mesh.LcIntegrationPrecision; :data:`fegear.fe.mesh.CURVE_PRECISION` is gmsh's own 1e-9): gear
#: 1's template meshed in 0.25 s at 1e-9, 0.06 s at 1e-7, another mesh as good as the first.
#: Five such meshes (1e-9 … 1e-5) of six designs moved the pressures and the von Mises stress by
#: up to 0.6 % at every level, the root stresses by up to 0.2 % (a seventh design, 0.7 and
#: 0.3 %): the error estimate's floor (:data:`~fegear.toothpair.estimate.MESH_SCATTER_PCT`).
#: At 1e-7 the baseline's `coarse` template is the one gmsh's default gives
CURVE_PRECISION = 1e-7


@dataclass(frozen=True)
class TemplateSizes:
    """Element sizes of the templates (mm): root zones, flanks, gear 1's rounds and their
    tangent points, and the rest of the body; the growth away from them (mm per mm); and the
    share of its curvature radius an element of gear 2 takes where the flank size does not
    follow its bend."""

    root: float
    flank: float
    round: float
    junction: float
    body: float
    growth: float = 0.3
    bend: float = 0.125   # gear 2 where it bends tighter than its flank size: this × its ρ


@dataclass(frozen=True)
class Template:
    """A gear's template sector: its geometry, the boundary names along its tooth profile, the
    polar angle where it starts (rad, the gear's own frame), its pitch (rad), the name of its
    held boundary and of its periodic cut, and the radii of its root zone (mm)."""

    geometry: BodyGeometry
    profile: tuple[str, ...]
    start: float
    pitch: float
    held: str
    cut: str
    root_band: tuple[float, float]


def gear1_template(p: PairParameters, shape: RoundedProfile, sizes: TemplateSizes,
                   rim: float) -> Template:
    """Gear 1's template: its profile from the middle of tooth 0's tip one pitch on, two radial
    cuts and the bore ``rim`` below the root."""
    pitch = shape.pitch
    a, b = shape.tooth_center, shape.tooth_center + pitch
    rho = shape.radius(np.linspace(0, pitch, 400) + shape.phi_space)
    r_min, r_max = float(rho.min()), float(rho.max())
    bore = r_min - rim
    space = shape.phi_space + pitch  # the tooth space between tooth 0 and tooth 1
    root_half = root_half_angle(shape.radius, space, pitch, r_min, r_max)
    # every round on the sector, also one the cut halves (a pointed tooth's tip round)
    rounds = [(c - h, c + h) for c, h, _ in shape.fillet_angles(range(-1, 3))
              if c + h > a and c - h < b]
    span = 2.0 * sizes.round / r_max  # the tangent points: finer over ± two round elements
    # a round shorter than the two zones is one zone (else a sliver piece between them)
    marks = [mark for lo, hi in rounds for mark in (
        [(lo - span, lo + span, "g1_junction"), (hi - span, hi + span, "g1_junction")]
        if hi - lo > 3 * span else [(lo - span, hi + span, "g1_junction")])]
    marks += [(lo - 4 * span, hi + 4 * span, "g1_round") for lo, hi in rounds]
    marks += [(x, x, None) for lo, hi in rounds for x in (lo, hi)]  # cut at the curvature jump

    def project(x):
        return shape.point(np.arctan2(x[:, 1], x[:, 0]))

    segs, names = profile_segments("g1", PolarCurve(shape.point, project), a, b, Layout(
        roots=(("g1_root", space, root_half),), marks=tuple(marks),
        sizes={"g1_root": sizes.root, "g1_flank": sizes.flank, "g1_round": sizes.round,
               "g1_junction": sizes.junction}))
    pa, pb = shape.point(np.array([a]))[0], shape.point(np.array([b]))[0]
    t = np.linspace(b, a, 40)
    bore_pts = bore * np.column_stack([np.cos(t), np.sin(t)])

    def bore_project(x):
        return bore * x / np.linalg.norm(x, axis=1)[:, None]

    geo = BodyGeometry("gear1", (
        *segs,
        Segment("g1_cut_b", np.array([pb, bore_pts[0]])),
        Segment("g1_bore", bore_pts, bore_project),
        Segment("g1_cut_a", np.array([bore_pts[-1], pa])),
    ), size=sizes.body, refinements=(
        Refinement(("g1_root",), sizes.root, sizes.growth),
        Refinement(("g1_flank",), sizes.flank, sizes.growth),
        *([Refinement(("g1_round",), sizes.round, sizes.growth),
           Refinement(("g1_junction",), sizes.junction, sizes.growth)] if rounds else [])),
        periodic=(Periodic("g1_cut_b", "g1_cut_a", pitch),), curve_precision=CURVE_PRECISION)
    band = (r_min, r_min + ROOT_BAND * (r_max - r_min))
    return Template(geo, names, a, pitch, "g1_bore", "g1_cut_b", band)


def gear2_template(p: PairParameters, curve: Cycloid, sizes: TemplateSizes,
                   rim: float) -> Template:
    """Gear 2's template: its profile from a tooth tip (ξ = 0) to the next, two radial cuts and
    the fixed rim ``rim`` beyond the root."""
    pitch = 2 * math.pi / p.z2
    a, b = 0.0, pitch
    r_min, r_max = p.r0 - 2 * p.e1, p.r0 + 2 * p.e1
    outer = r_max + rim

    g2_profile = gear2_polar(curve)
    # the template's geometry and sizes are inverted without a table (Cycloid.xi_at_angle)
    root_half = root_half_angle(lambda t: curve.radius_at_angle(t, tabled=False), 0.5 * pitch,
                                pitch, r_min, r_max, inverted=True)
    marks, bent = bends(curve, a, b, sizes)
    segs, names = profile_segments("g2", g2_profile, a, b, Layout(
        roots=(("g2_root", 0.5 * pitch, root_half),), marks=tuple(marks),
        sizes={"g2_root": sizes.root, "g2_flank": sizes.flank, "g2_bend": bent}))
    geo = BodyGeometry("gear2", gear2_outline(g2_profile.point, segs, a, b, outer, 40),
                       size=sizes.body, refinements=(
        Refinement(("g2_root",), sizes.root, sizes.growth),
        Refinement(("g2_flank",), sizes.flank, sizes.growth),
        *([Refinement(("g2_bend",), bent, sizes.growth)] if marks else [])),
        periodic=(Periodic("g2_cut_b", "g2_cut_a", pitch),), curve_precision=CURVE_PRECISION)
    band = (r_max - ROOT_BAND * (r_max - r_min), r_max)
    return Template(geo, names, a, pitch, "g2_rim", "g2_cut_b", band)


def bends(curve: Cycloid, a: float, b: float, sizes: TemplateSizes,
          samples: int = 4001) -> tuple[list, float]:
    """The polar-angle stretches of gear 2's profile over [a, b] whose curvature radius ρ is
    below the flank size over ``sizes.bend`` (its quadratic edges would bow off the exact curve
    by ~h³/ρ²: a pointed tooth tip at larger h1 and small f1), widened by a flank element
    each side, as refinement marks ``g2_bend``; and their element size, ``sizes.bend`` times
    the least ρ (the flank size where there is none)."""
    theta = np.linspace(a, b, samples)
    rho = np.abs(curve.curvature_radius(curve.xi_at_angle(theta, tabled=False)))
    tight = rho * sizes.bend < sizes.flank
    if not tight.any():
        return [], sizes.flank
    r = curve.radius_at_angle(theta, tabled=False)
    pad = sizes.flank / float(r.min())
    edges = np.flatnonzero(np.diff(np.concatenate([[0], tight.astype(int), [0]])))
    marks = [(max(a, theta[i] - pad), min(b, theta[j - 1] + pad), "g2_bend")
             for i, j in zip(edges[::2], edges[1::2])]
    return marks, sizes.bend * float(rho[tight].min())

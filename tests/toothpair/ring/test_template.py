"""The template sectors mesh into valid elements across the design space: the admissible pairs
whose templates the random-pair property test (tests/toothpair/test_properties.py) found
refused, meshed at `coarse` (about a second each)."""

import numpy as np
import pytest
from shapes import POINTED, SMALL_GEAR

from fegear.errors import FegearError
from fegear.fe import mesh_bodies
from fegear.geometry import Gear1Profile, PairParameters, RoundedProfile
from fegear.toothpair import SolveCase
from fegear.toothpair.ring import build_templates

SMALL_SHIFTED = dict(m=0.5341851169029675, z2=52, z1=50, h1=0.29203301120379815,
                     f1=0.29203301120379815, shift=0.0035418302359403564,
                     rotation=1.6420731396915087e-166)
TIGHT = dict(z2=66, z1=65, h1=0.31303910669746804, f1=0.2515399623644864)
#: h1 0.95 and f1 0 at z2 = 111: gear 2's tooth tip bends at a 0.47 mm radius under 0.19 mm
#: flank elements, whose quadratic edges left the exact tip by a fifth of an element
SHARP_GEAR2 = dict(POINTED, z2=111, z1=108)

REFUSED = {
    # m ≈ 0.5: gear 2's flanks turn at a 0.26-0.29 mm radius and run up to 3.8 times faster
    # than r dθ; their 8-point polylines strayed 6 µm from the curve, and snapping the nodes
    # back along the polar angle moved them 16-19 µm in 25 µm elements (Jacobian ratio -0.33)
    "m 0.53, z 50/52: gear 2 inverted": SMALL_SHIFTED,
    "m 0.5, z 50/52: gear 2 inverted": dict(SMALL_SHIFTED, m=0.5),
    "m 0.5, z 65/66: gear 2 inverted": dict(TIGHT, m=0.5),
    # gear 1's round zone ended 0.6 µm before its root zone began: a 0.6 µm boundary piece
    # under 57 µm elements (shape quality 0.010)
    "m 3.67, z 65/66: gear 1 sliver": dict(TIGHT, m=3.6733480641517477,
                                           shift=0.02582530840530918,
                                           rotation=0.003758945773820904),
    # a pointed gear-1 tooth: its tip round straddles the template's cut, which left it out of
    # the round's refinement (a 0.14 element at the corner)
    "m 4.95, z 8/10, h1 0.99, f1 0: gear 1's cut through its tip round":
        dict(m=4.948717708822167, z2=10, z1=8, h1=0.9917657907891634, f1=0.0,
             shift=0.03958974167057734, rotation=0.004948717708822168,
             tip_clearance=0.03958974167057734),
    # gear 1's root radius (4.6 mm) below the default 3 m rim (5.7 mm): a negative bore, on
    # which gmsh failed or hung
    "m 1.91, z 8/9, h1 0.91: a rim deeper than the root": SMALL_GEAR,
}


@pytest.mark.parametrize("inputs", REFUSED.values(), ids=REFUSED.keys())
def test_templates_mesh_without_inverted_or_badly_shaped_elements(inputs):
    p = PairParameters(**inputs)
    case = SolveCase(p, torque=10.0, quality="coarse")
    templates = build_templates(case, RoundedProfile(Gear1Profile(p), case.edge_radius))
    meshes = mesh_bodies([t.geometry for t in templates])
    for template, body in zip(templates, meshes):
        assert body.quality.min_jacobian_ratio > 0.0
        assert body.quality.min_shape >= template.geometry.min_quality


def test_a_rim_deeper_than_gear_1s_root_stops_at_a_share_of_it():
    """The default 3 m rim of gear 1 is cut to RIM1_SHARE of its root radius where that is
    less (its bore stays positive); a rim given deeper is refused by name, with its range."""
    from fegear.errors import ParameterError
    from fegear.toothpair.case import RIM1_SHARE

    small = SolveCase(PairParameters(**SMALL_GEAR), torque=0.5, quality="coarse")
    root = small.root_radius1
    assert root < 3 * small.params.m
    assert small.rims == pytest.approx((RIM1_SHARE * root, 3 * small.params.m))
    baseline = SolveCase(PairParameters(), quality="coarse")
    assert baseline.rims == (3 * baseline.params.m, 3 * baseline.params.m)
    with pytest.raises(ParameterError) as err:
        SolveCase(PairParameters(**SMALL_GEAR), torque=0.5, rim1=0.7 * root)
    assert err.value.name == "rim1"
    assert f"{RIM1_SHARE * root:.4g}" in err.value.admissible


def test_gear_2_is_refined_where_it_bends_tighter_than_its_flank_elements():
    """A sharp gear-2 tip gets elements a share of its curvature radius: points on the exact
    curve there lie in the mesh (the contact submodel's cut is held at such points)."""
    from fegear.fe import Probe
    from fegear.geometry import gear2_curve
    from fegear.toothpair.ring.template import bends

    p = PairParameters(**SHARP_GEAR2)
    case = SolveCase(p, torque=10.0, quality="coarse")
    t1, t2 = build_templates(case, RoundedProfile(Gear1Profile(p), case.edge_radius))
    sizes = [r.size for r in t2.geometry.refinements]
    curve = gear2_curve(p)
    marks, size = bends(curve, 0.0, t2.pitch, _sizes(case))
    assert marks and marks[0][0] == 0.0                 # at the tooth tip, ξ = 0
    tip = abs(curve.curvature_radius(np.array([0.0]))[0])     # 0.47 mm
    assert size == pytest.approx(_sizes(case).bend * tip, rel=1e-2) and size in sizes
    assert size < 0.5 * min(sizes[:2])
    (mesh,) = mesh_bodies([t2.geometry])
    theta = np.linspace(marks[0][0], marks[0][1], 200)
    r = curve.radius_at_angle(theta)
    on_curve = np.column_stack([r * np.cos(theta), r * np.sin(theta)])
    Probe(mesh.mesh).locate(on_curve)
    # a point a tenth of a millimetre off the body is no boundary approximation: refused
    with pytest.raises(FegearError, match="outside the mesh"):
        Probe(mesh.mesh).locate(on_curve[100:101] * (1.0 - 0.1 / r[100]))
    # a smooth gear 2 has none
    assert bends(gear2_curve(PairParameters()), 0.0, 2 * np.pi / 45,
                 _sizes(SolveCase(PairParameters(), quality="coarse")))[0] == []


def _sizes(case):
    from fegear.toothpair.ring.model import LEVELS
    from fegear.toothpair.ring.template import TemplateSizes

    level, m = LEVELS[case.quality], case.params.m
    return TemplateSizes(root=level.root * m, flank=level.flank * m, round=0.0, junction=0.0,
                         body=level.body * m)

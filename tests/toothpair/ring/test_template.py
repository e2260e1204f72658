"""The template sectors mesh into valid elements across the design space: the admissible pairs
whose templates the random-pair property test (tests/toothpair/test_properties.py) found
refused, meshed at `coarse` (about a second each)."""

import pytest

from fegear.fe import mesh_bodies
from fegear.geometry import Gear1Profile, PairParameters, RoundedProfile
from fegear.toothpair import SolveCase
from fegear.toothpair.ring import build_templates

SMALL_SHIFTED = dict(m=0.5341851169029675, z2=52, z1=50, h1=0.29203301120379815,
                     f1=0.29203301120379815, shift=0.0035418302359403564,
                     rotation=1.6420731396915087e-166)
TIGHT = dict(z2=66, z1=65, h1=0.31303910669746804, f1=0.2515399623644864)

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

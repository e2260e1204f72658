"""The clearances and extreme admissible shapes both tooth-pair models must converge on, and
which loaded teeth sit on the far side."""

import pytest

from fegear.geometry import Gear1Profile, ToothContact

BASELINE_MODS = dict(shift=0.016, rotation=0.002)

#: z 8/9 with h1 0.91: gear 1's root radius (4.6 mm) below the default 3 m rim (5.7 mm), and
#: its first touch on a tip round that stands µm behind the sharp profile's (the random-pair
#: property test's draws)
SMALL_GEAR = dict(m=1.9077814968607891, z2=9, z1=8, h1=0.9133963644840435,
                  f1=0.01741198407749094, shift=0.015262251974886313,
                  rotation=0.0019077814968607892, tip_clearance=0.01741198407749094)
#: h1 0.95 and f1 0 at m 3.8, z1 8 and 108: pointed teeth; at z2 = 111 gear 2's tooth tip bends
#: at a 0.47 mm radius under 0.19 mm flank elements
POINTED = dict(m=3.7947903015118905, h1=0.9492161670931352, f1=0.0,
               shift=0.030358322412095125, rotation=0.0037947903015118907,
               tip_clearance=0.030358322412095125)

#: id: (pair inputs, torque N·m, whether only far-side teeth may carry it)
EXTREME_SHAPES = {
    "zero tip clearance, light: only far-side teeth touch": (dict(BASELINE_MODS, tip_clearance=0.0),
                                                        1.0, True),
    "zero tip clearance, baseline torque": (dict(BASELINE_MODS, tip_clearance=0.0), 200.0, False),
    "unmodified: zero clearance": (dict(), 50.0, False),
    "shift 0.1 µm": (dict(shift=1e-4), 200.0, False),
    "h1 0.6 (limit 0.6047)": (dict(h1=0.6), 50.0, False),
    # near its looping limit gear 2 runs almost radially (ds = 18.9 r dθ; 2.1 on the
    # baseline): sampled evenly in polar angle, its spline overshot by up to 57 µm and
    # snapping inverted 171 gear-2 elements (sector model)
    "f1 0.39 (limit 0.3902)": (dict(h1=0.3, f1=0.39), 50.0, False),
    "h1 0.05": (dict(h1=0.05), 50.0, False),
    "f1 0": (dict(BASELINE_MODS, f1=0.0), 50.0, False),
}


def extreme_shapes(slow: set[str], extra=()) -> list:
    """``EXTREME_SHAPES`` as pytest parameters (params, torque, far_side_only), those named in
    ``slow`` marked slow, then ``extra`` parameters."""
    assert slow <= set(EXTREME_SHAPES), slow - set(EXTREME_SHAPES)
    return [pytest.param(*case, id=name, marks=pytest.mark.slow if name in slow else ())
            for name, case in EXTREME_SHAPES.items()] + list(extra)


def far_side(sol) -> list[bool]:
    """For each loaded tooth of ``sol``: is it on the far side (more than 90° from the pitch
    point at the solved position)?"""
    p = sol.case.params
    where = {c.tooth: c.position_deg
             for c in ToothContact(p, Gear1Profile(p)).state(sol.case.beta).teeth}
    return [abs(where[t.tooth]) > 90 for t in sol.teeth if t.load_N > 0]

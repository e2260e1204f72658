"""The drive level's inputs, one schema each (``fegear drive``'s options and the checks of the
objects they build): seed 000's three-ring reducer (:class:`~.bearings.RingDrive`), the
torsional model (:class:`~.dynamics.TorsionalPair`) and a planetary train's ratio. No numpy
here: ``fegear drive --help`` reads them. Seed 003's reducer has its own
(:data:`~.reducer_inputs.REDUCER_INPUTS`).
"""

from __future__ import annotations

from ..checks import Input

#: seed 000's three-ring reducer; the defaults are the paper's worked example
BEARING_INPUTS = (
    Input("z1", int, 78, "external (output) gear teeth", low=1, high=9999,
          limits="an integer 1 <= z1 < z2"),
    Input("z2", int, 81, "internal ring teeth", low=2, high=10000,
          limits="an integer z1 < z2 <= 10000"),
    Input("m", float, 4.5, "module", "mm", low=0.0, low_open=True),
    Input("torque", float, 1117.0, "output torque", "N·m", low=0.0, low_open=True),
    Input("rings", int, 3, "planet rings", low=1, high=100),
    Input("speed", float, 1500.0, "crank speed", "r/min", low=0.0),
    Input("pressure-angle", float, 20.0, "standard pressure angle", "deg", low=0.0, high=90.0,
          low_open=True, high_open=True),
    Input("working-angle", float, 35.286, "working pressure angle α'", "deg", low=0.0,
          high=90.0, low_open=True, high_open=True),
    Input("base-radius", float, 171.26, "base radius r_b of the ring", "mm", low=0.0,
          low_open=True),
    Input("ring-weight", float, 420.6, "ring weight G_2", "N", low=0.0, low_open=True),
    Input("inertia-force", float, 8050.2, "ring inertia force P_i2 (0: from eq. 2)", "N",
          low=0.0),
    Input("load-factor", float, 1.2, "F_n = factor · T / (rings r_b)", low=0.0,
          low_open=True),
    Input("half-span", float, 338.0, "half distance l of bearings A, B", "mm", low=0.0,
          low_open=True),
    Input("eccentric-spacing", float, 40.0, "axial spacing B of the eccentrics", "mm",
          low=0.0, low_open=True, aliases=("spacing",)),
    Input("support-span", float, 180.0, "span L' of a crank shaft's supports", "mm", low=0.0,
          low_open=True),
    Input("bearing-weight", float, 20.0, "eccentric-bearing weight G_H", "N", low=0.0),
)

#: the torsional two-inertia model (its mesh stiffness and ratio come from a solve's file)
DYNAMICS_INPUTS = (
    Input("J1", float, None, "gear-1 inertia", "kg·m²", low=0.0, low_open=True,
          rule="a steel disk of its pitch radius"),
    Input("J2", float, None, "gear-2 inertia", "kg·m²", low=0.0, low_open=True,
          rule="a steel ring, pitch radius + 3 m"),
    Input("zeta", float, 0.05, "mesh damping ratio", low=0.0, high=1.0, high_open=True),
    Input("torque", float, None, "gear-1 torque", "N·m", low=0.0, high=1e5, low_open=True,
          rule="the stiffness file's"),
)

#: a planetary train's transformed ratio and efficiency (``fegear drive ratio``)
RATIO_INPUTS = (
    Input("i-ab-h", float, None, "2kh: the carrier-fixed ratio i_ab^H with its sign",
          limits="a finite i-ab-h other than 0 and 1", rule="none (--teeth gives the train)"),
    Input("eta-h", float, None, "efficiency of the carrier-fixed mechanism (product of its "
          "meshes)", low=0.0, high=1.0, low_open=True, rule="none (no efficiency)"),
)

"""The Hertz validation case's inputs (``fegear hertz``'s options beside the material's), in a
module of their own: ``fegear --help`` reads them without numpy (:mod:`.disk_case` checks
them)."""

from __future__ import annotations

from ..checks import Input

#: the contact penalty's default factor, :class:`~fegear.verify.penalty.ContactSettings`' (tested)
PENALTY_FACTOR = 300.0
#: elements across the Hertz half-width b in the contact windows, per quality level
DISK_QUALITY = {"coarse": 4, "standard": 8, "fine": 16}
#: the case's inputs beside the material's (``fegear hertz``)
DISK_INPUTS = (
    Input("r1", float, 10.0, "disk 1 radius", "mm", low=0.0, high=1e4, low_open=True),
    Input("r2", float, 10.0, "disk 2 radius; negative: a bore holding disk 1", "mm",
          low=-1e4, high=1e4, limits="0 < r2 <= 10000 mm, or a bore: -10000 <= r2 < -r1 mm"),
    Input("load", float, 1000.0, "normal load", "N", low=0.0, low_open=True,
          limits="0 < load, with the Hertz half-width b below r/2"),
    Input("quality", str, "standard", "elements across the Hertz half-width b: coarse / "
          "standard / fine = 4 / 8 / 16, or a number",
          limits="coarse / standard / fine, or 1 <= quality <= 200"),
    Input("penalty-factor", float, PENALTY_FACTOR, "penalty κ = factor·E*/h",
          low=0.0, high=1e6, low_open=True),
)

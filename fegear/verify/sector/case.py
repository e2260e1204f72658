"""The sector model's case: the product's :class:`~fegear.toothpair.SolveCase` and the two
inputs only this model has."""

from __future__ import annotations

from dataclasses import dataclass, fields

from ...checks import require_range
from ...toothpair import SolveCase
from .deviated import explicit_only

EXTRA_TEETH = (1, 10)        # admissible unloaded teeth meshed on each side
PENALTY_LIMIT = 1e6          # the largest penalty factor


@dataclass(frozen=True)
class SectorCase(SolveCase):
    """A tooth-pair case for the sector model: unloaded teeth meshed beyond the paired ones on
    each side (``extra_teeth``) and the contact penalty κ = ``penalty_factor`` · E*/h, h the
    local facet length."""

    extra_teeth: int = 2
    penalty_factor: float = 1000.0

    def __post_init__(self) -> None:
        super().__post_init__()
        require_range("extra-teeth", self.extra_teeth, *EXTRA_TEETH)
        require_range("penalty-factor", self.penalty_factor, 0.0, PENALTY_LIMIT, lo_open=True)
        explicit_only(self.deviations)

    @classmethod
    def of(cls, case: SolveCase, **sector: object) -> SectorCase:
        """``case`` (a product case) for the sector model, with its own inputs ``sector``."""
        return cls(**{f.name: getattr(case, f.name) for f in fields(SolveCase)}, **sector)

"""What a property test's draws came to: each admissible draw either converged (and passed the
test's checks) or was refused with a named fegear error, whose reason is kept. A test fails when
more than its stated share of admissible draws is refused, so that a regression that makes every
draw raise a named error cannot pass as "refused by name"."""

from __future__ import annotations

import math
from collections import Counter

LISTED = 10   # refused draws shown whole in the summary


class Draws:
    """The outcomes of one property test's admissible draws."""

    def __init__(self, max_refused_share: float) -> None:
        self.max_refused_share = max_refused_share
        self.converged = 0
        self.refused: list[tuple[str, str, str]] = []  # (draw, error type, message)

    def ok(self) -> None:
        self.converged += 1

    def refuse(self, draw: object, error: Exception) -> None:
        self.refused.append((repr(draw), type(error).__name__, str(error)))

    @property
    def total(self) -> int:
        return self.converged + len(self.refused)

    def reasons(self) -> str:
        """The refusals grouped by error type and the start of the message, most common first."""
        counts = Counter(f"{kind}: {message[:90]}" for _, kind, message in self.refused)
        return "\n".join(f"  {n} × {reason}" for reason, n in counts.most_common())

    def summary(self) -> str:
        listed = "".join(f"\n  {draw}: {kind}: {message}" for draw, kind, message in
                         self.refused[:LISTED])
        return (f"{self.total} admissible draws: {self.converged} converged, "
                f"{len(self.refused)} refused by name (at most "
                f"{self.max_refused_share:.0%} allowed)\n{self.reasons()}{listed}")

    def check(self) -> None:
        print(self.summary())  # shown with -rA or -s, and on failure
        assert self.total > 0, "no admissible draw"
        assert len(self.refused) <= self.max_refused_share * self.total, self.summary()


def finite(value, path="summary"):
    """Every number in a JSON-like tree is finite (None allowed); returns the offending path."""
    if isinstance(value, dict):
        return next((p for k, v in value.items() if (p := finite(v, f"{path}.{k}"))), None)
    if isinstance(value, (list, tuple)):
        return next((p for i, v in enumerate(value) if (p := finite(v, f"{path}[{i}]"))), None)
    if isinstance(value, float) and not math.isfinite(value):
        return path
    return None

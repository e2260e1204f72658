"""Exceptions raised by fegear.

Every user-facing failure is a :class:`FegearError`; the CLI prints its message as one line and
exits with code 2. Library code never prints or exits.
"""

from __future__ import annotations


class FegearError(Exception):
    """Base class of every error fegear raises on purpose."""


class ParameterError(FegearError, ValueError):
    """An input parameter is outside its admissible range.

    The message always names the parameter, the offending value and the admissible range
    (evaluated at the other parameters' values where the range depends on them).
    """

    def __init__(self, name: str, value: object, admissible: str, reason: str = "") -> None:
        self.name = name.replace("_", "-")   # as the input is typed: tip-clearance
        self.value = value.item() if hasattr(value, "item") else value   # not np.float64(…)
        self.admissible = admissible
        self.reason = reason
        super().__init__(self.describe(self.name))

    def __reduce__(self):
        # raised in a pool worker, it is pickled to the parent: by its fields, not its message
        return type(self), (self.name, self.value, self.admissible, self.reason)

    def describe(self, name: str) -> str:
        """The message with the input called ``name`` (``--tip-clearance`` on the command
        line, ``tip-clearance`` in a study file)."""
        why = f" ({self.reason})" if self.reason else ""
        return f"{name} = {self.value!r} is not admissible{why}; admissible: {self.admissible}"


class ContactError(FegearError):
    """A contact problem has no admissible solution, or the iterations did not find it."""


class GeometryError(FegearError):
    """A geometric construction failed for an admissible-looking input (a bug or an edge case)."""

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
        self.name = name
        self.value = value
        self.admissible = admissible
        self.reason = reason
        why = f" ({reason})" if reason else ""
        super().__init__(f"{name} = {value!r} is not admissible{why}; admissible: {admissible}")


class GeometryError(FegearError):
    """A geometric construction failed for an admissible-looking input (a bug or an edge case)."""

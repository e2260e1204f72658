"""Public faces that import on demand.

Every stage's ``__init__`` names what it exports and the module each name lives in; a name is
imported when first asked for. ``fegear --help`` and a one-line user error therefore never pay
for scipy, scikit-fem, gmsh or matplotlib, and importing one light module of a stage (the input
schema, say) does not drag in the rest of it.
"""

from __future__ import annotations

import importlib
import sys
from collections.abc import Callable, Mapping


def lazy(package: str, table: Mapping[str, tuple[str, ...]]
         ) -> tuple[Callable[[str], object], Callable[[], list[str]], list[str]]:
    """``__getattr__``, ``__dir__`` and ``__all__`` for ``package``, whose public names are
    those of ``table`` (module → names), each imported from its module on first use."""
    owner = {name: module for module, names in table.items() for name in names}

    def __getattr__(name: str) -> object:
        module = owner.get(name)
        if module is None:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        value = getattr(importlib.import_module(f"{package}.{module}"), name)
        setattr(sys.modules[package], name, value)  # later lookups skip __getattr__
        return value

    def __dir__() -> list[str]:
        return sorted(set(owner) | set(vars(sys.modules[package])))

    return __getattr__, __dir__, sorted(owner)

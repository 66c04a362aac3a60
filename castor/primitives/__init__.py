"""The primitives of the language, one module each (LANGUAGE.md §4.1).

Each module of this package that defines ``PRIMITIVE`` (a ``base.PrimitiveKind``)
declares one primitive: its name, arguments, checks, unit box, mesh and ray
spans. ``PRIMITIVES`` (name → PrimitiveKind) is gathered from the modules found
here, so adding a primitive is adding its file: the parser, the evaluator,
the facetizer (castor.mesh.primitives), the ray tracer (castor.pictures.spans)
and the editor files read this table and keep none of their own.
"""

from __future__ import annotations

import importlib
import os

from castor.primitives.base import FLAT, Argument, Mesh, PrimitiveKind


def _module_names() -> list[str]:
    """The modules of this package (its NAME.py files: pkgutil's listing, without
    importing pkgutil at start-up)."""
    names = set()
    for directory in __path__:
        for entry in os.listdir(directory):
            name, dot, suffix = entry.partition(".")
            if suffix == "py" and name.isidentifier() and not name.startswith("_"):
                names.add(name)
    return sorted(names)


def _gathered() -> dict[str, PrimitiveKind]:
    found = []
    for name in _module_names():
        declared = getattr(importlib.import_module(f"{__name__}.{name}"), "PRIMITIVE", None)
        if isinstance(declared, PrimitiveKind):
            found.append(declared)
    return {p.name: p for p in sorted(found, key=lambda p: p.place)}


PRIMITIVES: dict[str, PrimitiveKind] = _gathered()

__all__ = ["FLAT", "PRIMITIVES", "Argument", "Mesh", "PrimitiveKind"]

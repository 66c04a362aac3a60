"""Unit-size primitives as triangle meshes with face numbers (LANGUAGE.md §4.1).

Each primitive's mesh is declared with the primitive (``castor.primitives``);
this is the facetizer's way in: ``build`` and ``estimate_triangles`` by kind.
"""

from __future__ import annotations

from castor.primitives import PRIMITIVES, Mesh
from castor.primitives.facets import circle_segments, sphere_segments, signed_volume

__all__ = ["Mesh", "build", "circle_segments", "estimate_triangles", "signed_volume",
           "sphere_segments"]


def estimate_triangles(kind: str, shape: tuple, tolerance: float) -> int:
    """Triangles a primitive will have, computed before building it."""
    return PRIMITIVES[kind].triangles(shape, tolerance)


def build(kind: str, shape: tuple, tolerance: float) -> Mesh:
    """The mesh of primitive ``kind`` with its non-colour arguments ``shape``,
    already checked (castor.primitives) by the evaluator."""
    return PRIMITIVES[kind].mesh(shape, tolerance)

"""Unit-size primitives as triangle meshes with face numbers (LANGUAGE.md §4.1).

Each primitive's mesh is declared with the primitive (``castor.primitives``);
this is the facetizer's way in: ``facet_counts`` (which the primitive chooses
from the leaf's transformation and tolerance), then ``build`` and
``estimate_triangles`` by kind and counts.
"""

from __future__ import annotations

from castor.primitives import PRIMITIVES, Mesh
from castor.primitives.facets import (circle_segments, linear_part, product, signed_volume,
                                      sphere_segments)

__all__ = ["Mesh", "build", "circle_segments", "estimate_triangles", "facet_counts",
           "signed_volume", "sphere_segments"]


def facet_counts(leaf) -> tuple[int, ...]:
    """The facet counts of an evaluated primitive (castor.csg.tree.Primitive):
    the primitive reads them off the linear map from its unit space to the
    units its tolerance is in, its matrix after the shape of the stretch above
    its shared subtree (``leaf.metric``). Empty for a primitive without curved
    faces."""
    declared = PRIMITIVES[leaf.kind]
    if declared.facets is None:
        return ()
    linear = linear_part(leaf.matrix)
    if leaf.metric is not None:
        linear = product(leaf.metric, linear)
    return declared.facets(leaf.shape, linear, leaf.tolerance)


def _counts(kind: str, shape: tuple, facets) -> tuple:
    """Facet counts as given, or those of the unit primitive for a tolerance
    (a number: how tests and tools ask for a mesh of its own)."""
    if isinstance(facets, tuple):
        return facets
    return PRIMITIVES[kind].facet_counts(shape, _UNSTRETCHED, float(facets))


_UNSTRETCHED = (1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0)


def estimate_triangles(kind: str, shape: tuple, facets) -> int:
    """Triangles a primitive will have, computed before building it."""
    return PRIMITIVES[kind].triangles(shape, _counts(kind, shape, facets))


def build(kind: str, shape: tuple, facets) -> Mesh:
    """The mesh of primitive ``kind`` with its non-colour arguments ``shape``,
    already checked (castor.primitives) by the evaluator, and its facet counts
    (or a tolerance, for the primitive unstretched)."""
    return PRIMITIVES[kind].mesh(shape, _counts(kind, shape, facets))

"""Smooth solids in the facetizer (``@s``, LANGUAGE.md §7.1).

The operand is facetized as any solid is and its merged convex polygons
become the control mesh (castor.mesh.subdivide); the refined triangles go
back to the engine as one solid whose triangles keep, each, the origin (path
and colour) of the control polygon they come from, so that booleans above
cut them and colour their cuts like any other solid's.
"""

from __future__ import annotations

import numpy as np

from castor.csg import tree
from castor.diagnostics import GeometryError, LimitError
from castor.mesh import engine, memory, polygons, subdivide
from castor.mesh.frame import FrameObject, compact


def control_mesh(solid: engine.Solid) -> FrameObject:
    """A solid's polygons as §7 writes them: closed, convex, merged."""
    merger = polygons.Merger()
    pieces = []
    for batch in engine.batches(solid.parts):
        tri = engine.triangles(batch, solid.origins)
        pieces.append((tri.vertices, merger.merge(tri.vertices, tri.triangles, tri.origin_ids,
                                                  tri.face_ids)))
    return compact(pieces, solid.origins)


def triangle_budget(max_polygons: int) -> int:
    """The most triangles a smoothing may make: --max-polygons, and what the
    memory available holds."""
    budget = max_polygons
    available = memory.available_bytes()
    if available is not None:
        per_triangle = memory.BYTES_PER_TRIANGLE + subdivide.BYTES_PER_TRIANGLE
        budget = min(budget, max(0, available - memory.BASE_BYTES) // per_triangle)
    return int(budget)


def face_numbers(vertices, triangles, control) -> np.ndarray:
    """A face number for each triangle, as the engine's faces are numbered: one
    flat face, one number. A control face that stayed flat (between creases)
    keeps its number for all its triangles, merged into polygons again; the
    triangles of a curved one have a number each (the passes that look for
    sheets take a face number for one plane)."""
    p = vertices[triangles]
    normal = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    normal /= np.maximum(np.linalg.norm(normal, axis=1), 1e-300)[:, None]
    count = int(control.max()) + 1
    first = np.full(count, len(triangles))
    np.minimum.at(first, control, np.arange(len(triangles)))
    reference = first[control]
    size = max(1.0, float(np.abs(vertices).max()))
    offset = np.einsum("ij,ij->i", normal[reference], p[reference, 0])
    apart = np.abs(np.einsum("ij,itj->it", normal[reference], p) - offset[:, None]).max(axis=1)
    flat = (np.abs(normal - normal[reference]).max(axis=1) < 1e-9) & (apart < 1e-9 * size)
    face_flat = np.ones(count, bool)
    face_flat[control[~flat]] = False
    return np.where(face_flat[control], control, count + np.arange(len(triangles)))


def smoothed(operand: engine.Solid, node: tree.Smooth, max_polygons: int) -> engine.Solid:
    """The smooth solid of ``node`` whose operand, facetized, is ``operand``
    (in the node's own space); the operand itself when every edge is a crease."""
    if operand.empty:
        return operand
    control = control_mesh(operand)
    try:
        result = subdivide.smooth(control.vertices, control.offsets, control.indices,
                                  node.angle, node.tolerance, triangle_budget(max_polygons))
    except subdivide.SubdivisionLimit as exc:
        raise LimitError(f"'@s({node.angle:g})': {exc} (--max-polygons {max_polygons:,} and "
                         "the memory available); raise the tolerance or smooth a smaller "
                         "object", node.location) from None
    if result is None:
        return operand
    try:
        return engine.refined(result.vertices, result.triangles,
                              control.origin_of[result.faces],
                              face_numbers(result.vertices, result.triangles, result.faces),
                              tuple(control.origins))
    except engine.EngineError as exc:
        raise GeometryError(f"'@s({node.angle:g})' gives no valid solid ({exc})",
                            node.location) from None

"""Smooth solids in the facetizer (``@s``, LANGUAGE.md §7.1).

The operand is facetized as any solid is and its merged convex polygons
become the control mesh (castor.mesh.subdivide); the refined triangles go
back to the engine as one solid whose triangles keep, each, the origin (path
and colour) of the control polygon they come from, so that booleans above
cut them and colour their cuts like any other solid's.

The facets of one smooth patch (control polygons joined by edges that are no
creases) are facets of one curved surface for the crease rule
(castor.mesh.creases): each origin of a smooth solid carries ``surfaces``
that name the patch of every curved facet, so neither drawings nor pictures
draw lines between them; a control face left flat between creases keeps one
face number and is a flat face.
"""

from __future__ import annotations

import numpy as np

from castor.csg import tree
from castor.diagnostics import GeometryError, LimitError
from castor.mesh import adapter, memory, merge, provenance, subdivide
from castor.mesh.frame import FaceSurfaces, FrameObject, Origin, compact
from castor.mesh.regularize import regular_triangles
from castor.mesh.solid import Solid


def control_mesh(solid: Solid) -> FrameObject:
    """A solid's polygons as §7 writes them: closed, convex, merged."""
    pieces = []
    for batch in provenance.batches(solid.parts):
        tri = regular_triangles(provenance.triangles(batch, solid.origins), batch)
        pieces.append((tri.vertices, merge.merge(tri.vertices, tri.triangles, tri.origin_ids,
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


def smoothed(operand: Solid, node: tree.Smooth, max_polygons: int) -> Solid:
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
    faces = face_numbers(result.vertices, result.triangles, result.faces)
    patch = subdivide.patches(control.vertices, control.offsets, control.indices, node.angle)
    try:
        return refined(result.vertices, result.triangles, control.origin_of[result.faces], faces,
                       _surfaces(faces, result.faces, patch, control.polygon_count),
                       tuple(control.origins))
    except adapter.EngineError as exc:
        raise GeometryError(f"'@s({node.angle:g})' gives no valid solid ({exc})",
                            node.location) from None


def _surfaces(faces: np.ndarray, control: np.ndarray, patch: np.ndarray,
              count: int) -> FaceSurfaces:
    """For each face number of the refined triangles (``face_numbers``), the
    smooth patch its facet lies on, or -1 for a control face left flat."""
    of_face = np.full(int(faces.max()) + 1 if len(faces) else 0, -1, np.int64)
    curved = faces >= count
    of_face[faces[curved]] = patch[control[curved]]
    return FaceSurfaces(of_face)


def refined(vertices: np.ndarray, triangles: np.ndarray, entries: np.ndarray,
            faces: np.ndarray, surfaces: FaceSurfaces, table: tuple) -> Solid:
    """A solid from a closed triangle mesh castor made itself (a smooth
    solid's refined facets), each triangle with its entry in ``table`` (the
    Origin of its control polygon) and its face number: one engine ID per
    entry, so that the triangles of each keep their origin through any
    boolean. Each entry keeps its path, colour and kind, with ``surfaces``."""
    order = np.lexsort((faces, entries))
    entries, faces, triangles = entries[order], faces[order], triangles[order]
    starts = np.flatnonzero(np.r_[True, entries[1:] != entries[:-1]])
    used = entries[starts]
    manifold, ids = adapter.from_runs(vertices, triangles, faces, starts)
    origins = provenance.Origins(
        ids, np.repeat(np.eye(4)[None, :3], len(ids), axis=0),
        tuple(_smoothed_origin(table[int(e)], surfaces) for e in used))
    return Solid((manifold,), origins)


def _smoothed_origin(origin: Origin, surfaces: FaceSurfaces) -> Origin:
    return Origin(origin.steps, origin.colour, origin.kind, surfaces)

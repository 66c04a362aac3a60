"""Unit-size primitives as triangle meshes with face numbers (LANGUAGE.md §4.1).

Each builder returns ``Mesh(vertices, triangles, faces)``: vertices in double
precision, triangles counter-clockwise seen from outside, and for each triangle
the number of the flat face it belongs to (the two triangles of a side quad of a
cylinder share one), which the engine carries through the booleans so that
flat faces are rebuilt as polygons afterwards.

Facet counts come from the tolerance, in the primitive's own units (the
facetizer divides the scene tolerance by the largest scale factor above it).
A chord of a circle of radius r spanning the angle 2π/n lies at most
r·(1 − cos(π/n)) inside the circle, so a circle gets
n = max(8, ⌈π / acos(1 − t/r)⌉) segments. A sphere's facets are quads spanning
δ in latitude and at most δ in longitude; their farthest point from the sphere
is under the angle δ/√2, so δ = √2·acos(1 − t/r).
"""

from __future__ import annotations

import math
from typing import Callable, NamedTuple

import numpy as np

from castor.language.outline import polygon, profile, signed_area

MIN_SEGMENTS = 8


class Mesh(NamedTuple):
    vertices: np.ndarray  # (V, 3) float64
    triangles: np.ndarray  # (T, 3) int64
    faces: np.ndarray  # (T,) int64


# More segments than this for one circle is refused (by the polygon limit).
_HUGE = 10**9


def _half_angle(ratio: float) -> float:
    """acos(1 - ratio), accurate for tiny ratios too (where 1 - ratio rounds to 1)."""
    if ratio > 1e-8:
        return math.acos(1.0 - ratio)
    return math.sqrt(2.0 * ratio)


def circle_segments(radius: float, tolerance: float) -> int:
    """Segments for a full circle of ``radius`` within ``tolerance``."""
    if radius <= 0 or tolerance >= radius:
        return MIN_SEGMENTS
    angle = _half_angle(tolerance / radius)
    if angle <= math.pi / _HUGE:
        return _HUGE
    return max(MIN_SEGMENTS, math.ceil(math.pi / angle - 1e-9))


def sphere_segments(tolerance: float) -> tuple[int, int]:
    """(around, rings) for the unit sphere."""
    if tolerance >= 1.0:
        step = math.pi / 4
    else:
        step = math.sqrt(2.0) * _half_angle(tolerance)
    if step <= 2 * math.pi / _HUGE:
        return _HUGE, _HUGE
    around = max(MIN_SEGMENTS, math.ceil(2 * math.pi / step - 1e-9))
    rings = max(MIN_SEGMENTS // 2, math.ceil(math.pi / step - 1e-9))
    return around, rings


def torus_segments(k: float, tolerance: float) -> tuple[int, int]:
    return circle_segments(1.0 + k, tolerance / 2), circle_segments(k, tolerance / 2)


def estimate_triangles(kind: str, shape: tuple, tolerance: float) -> int:
    """Triangles a primitive will have, computed before building it."""
    return BUILDERS[kind].triangles(shape, tolerance)


def _ring(n: int, radius: float, z: float) -> np.ndarray:
    angles = 2 * np.pi * np.arange(n) / n
    ring = np.empty((n, 3))
    ring[:, 0] = radius * np.cos(angles)
    ring[:, 1] = radius * np.sin(angles)
    ring[:, 2] = z
    ring[0, 1] = 0.0
    return ring


def _fan(indices: np.ndarray, reverse: bool) -> np.ndarray:
    """Triangles of a convex polygon given counter-clockwise (seen from outside unless reverse)."""
    n = len(indices)
    tris = np.column_stack([np.full(n - 2, indices[0]), indices[1:-1], indices[2:]])
    return tris[:, ::-1] if reverse else tris


def _mesh(vertices, triangle_blocks, face_blocks) -> Mesh:
    return Mesh(np.ascontiguousarray(vertices, dtype=np.float64),
                np.ascontiguousarray(np.concatenate(triangle_blocks), dtype=np.int64),
                np.ascontiguousarray(np.concatenate(face_blocks), dtype=np.int64))


def cube() -> Mesh:
    vertices = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0],
                         [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], dtype=np.float64)
    quads = np.array([[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4],
                      [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]])
    return _quads(vertices, quads, 0)


def _quads(vertices: np.ndarray, quads: np.ndarray, first_face: int) -> Mesh:
    tris = np.concatenate([quads[:, [0, 1, 2]], quads[:, [0, 2, 3]]])
    faces = np.tile(np.arange(first_face, first_face + len(quads)), 2)
    return Mesh(vertices, tris, faces)


def prism(n: int) -> Mesh:
    """Cylinder or prism: a regular n-gon swept from z = 0 to z = 1."""
    vertices = np.concatenate([_ring(n, 1.0, 0.0), _ring(n, 1.0, 1.0)])
    j = np.arange(n)
    k = (j + 1) % n
    sides = np.column_stack([j, k, n + k, n + j])
    side = _quads(vertices, sides, 2)
    return _mesh(vertices,
                 [_fan(j, reverse=True), _fan(n + j, reverse=False), side.triangles],
                 [np.zeros(n - 2, np.int64), np.ones(n - 2, np.int64), side.faces])


def pyramid(n: int) -> Mesh:
    """Cone or pyramid: a regular n-gon base in z = 0, apex (0, 0, 1)."""
    vertices = np.concatenate([_ring(n, 1.0, 0.0), [[0.0, 0.0, 1.0]]])
    j = np.arange(n)
    sides = np.column_stack([j, (j + 1) % n, np.full(n, n)])
    return _mesh(vertices, [_fan(j, reverse=True), sides],
                 [np.zeros(n - 2, np.int64), np.arange(1, n + 1)])


def sphere(around: int, rings: int) -> Mesh:
    polar = np.pi * np.arange(1, rings) / rings
    blocks = [np.array([[0.0, 0.0, 1.0]])]
    for angle in polar:
        z = math.cos(angle)
        ring = _ring(around, math.sin(angle), z)
        blocks.append(ring)
    blocks.append(np.array([[0.0, 0.0, -1.0]]))
    vertices = np.concatenate(blocks)
    if rings % 2 == 0:  # the equator lies exactly in z = 0
        vertices[1 + (rings // 2 - 1) * around: 1 + (rings // 2) * around, 2] = 0.0
    south = len(vertices) - 1
    j = np.arange(around)
    k = (j + 1) % around
    top = np.column_stack([np.zeros(around, np.int64), 1 + j, 1 + k])
    bottom_ring = 1 + (rings - 2) * around
    bottom = np.column_stack([np.full(around, south), bottom_ring + k, bottom_ring + j])
    upper = 1 + np.arange(rings - 2)[:, None] * around  # first index of each upper ring
    quads = np.stack([upper + j, upper + around + j, upper + around + k, upper + k], axis=-1)
    quads = quads.reshape(-1, 4)
    side = _quads(vertices, quads, 2 * around)
    return _mesh(vertices, [top, bottom, side.triangles],
                 [np.arange(around), around + np.arange(around), side.faces])


def torus(k: float, around: int, tube: int) -> Mesh:
    """Torus: centre circle of radius 1 in z = 0, tube radius k."""
    theta = 2 * np.pi * np.arange(around) / around
    phi = 2 * np.pi * np.arange(tube) / tube
    radius = 1.0 + k * np.cos(phi)
    vertices = np.empty((around, tube, 3))
    vertices[..., 0] = np.cos(theta)[:, None] * radius[None, :]
    vertices[..., 1] = np.sin(theta)[:, None] * radius[None, :]
    vertices[..., 2] = (k * np.sin(phi))[None, :]
    vertices[0, :, 1] = 0.0
    i = np.arange(around)[:, None]
    j = np.arange(tube)[None, :]
    i1, j1 = (i + 1) % around, (j + 1) % tube
    quads = np.stack([i * tube + j, i1 * tube + j, i1 * tube + j1, i * tube + j1], axis=-1)
    return _quads(vertices.reshape(-1, 3), quads.reshape(-1, 4), 0)


def extrusion(values: tuple) -> Mesh:
    """The simple polygon (x1, y1, ...) in z = 0 swept to z = 1."""
    from castor.mesh.adapter import triangulate

    points = polygon(values, "polygon", None, "")
    if signed_area(points) < 0:
        points = points[::-1].copy()
    n = len(points)
    cap = triangulate(points)
    vertices = np.concatenate([np.column_stack([points, np.zeros(n)]),
                               np.column_stack([points, np.ones(n)])])
    j = np.arange(n)
    k = (j + 1) % n
    side = _quads(vertices, np.column_stack([j, k, n + k, n + j]), 2)
    return _mesh(vertices, [cap[:, ::-1], cap + n, side.triangles],
                 [np.zeros(len(cap), np.int64), np.ones(len(cap), np.int64), side.faces])


def revolution(values: tuple, segments: int) -> Mesh:
    """The simple profile (r1, z1, ...) turned a full circle about the z axis."""
    outline = profile(values, None, "")
    if signed_area(outline) < 0:
        outline = outline[::-1].copy()
    n = segments
    m = len(outline)
    on_axis = outline[:, 0] == 0
    # vertex numbers: one per profile point on the axis, n per point off it
    first = np.zeros(m, np.int64)
    count = np.where(on_axis, 1, n)
    first[1:] = np.cumsum(count)[:-1]
    angles = 2 * np.pi * np.arange(n) / n
    cos, sin = np.cos(angles), np.sin(angles)
    sin[0] = 0.0
    blocks = []
    for (r, z), axis in zip(outline, on_axis):
        if axis:
            blocks.append([[0.0, 0.0, z]])
        else:
            blocks.append(np.column_stack([r * cos, r * sin, np.full(n, z)]))
    vertices = np.concatenate([np.asarray(b, dtype=np.float64) for b in blocks])
    j = np.arange(n)
    k = (j + 1) % n
    tris, faces = [], []
    face = 0
    for a in range(m):
        b = (a + 1) % m
        if on_axis[a] and on_axis[b]:
            continue
        va = first[a] + (0 if on_axis[a] else j)
        vb = first[b] + (0 if on_axis[b] else j)
        va1 = first[a] + (0 if on_axis[a] else k)
        vb1 = first[b] + (0 if on_axis[b] else k)
        # profile counter-clockwise in (r, z): a quad (a_j, b_j, b_j+1, a_j+1) faces out
        # after turning the orientation round (checked below by the volume's sign)
        if on_axis[a]:
            block = np.column_stack([va1 * np.ones(n, np.int64), vb, vb1])
        elif on_axis[b]:
            block = np.column_stack([va, vb * np.ones(n, np.int64), va1])
        else:
            block = np.concatenate([np.column_stack([va, vb, vb1]), np.column_stack([va, vb1, va1])])
        tris.append(block)
        per = n if (on_axis[a] or on_axis[b]) else 2 * n
        faces.append(face + (np.arange(per) % n))
        face += n
    mesh = _mesh(vertices, tris, faces)
    if signed_volume(mesh.vertices, mesh.triangles) < 0:
        mesh = Mesh(mesh.vertices, mesh.triangles[:, ::-1].copy(), mesh.faces)
    return mesh


def signed_volume(vertices: np.ndarray, triangles: np.ndarray) -> float:
    a, b, c = (vertices[triangles[:, i]] for i in range(3))
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)


class Builder(NamedTuple):
    """How a primitive of castor.language.vocabulary.PRIMITIVES becomes triangles:
    ``mesh(shape, tolerance)`` builds it, ``triangles(shape, tolerance)`` says
    how many it will have without building it."""

    mesh: Callable[[tuple, float], Mesh]
    triangles: Callable[[tuple, float], int]


def _revolution_segments(shape: tuple, tolerance: float) -> int:
    return circle_segments(max(shape[0::2]) if shape else 0.0, tolerance)


BUILDERS: dict[str, Builder] = {
    "cu": Builder(lambda shape, t: cube(), lambda shape, t: 12),
    "sp": Builder(lambda shape, t: sphere(*sphere_segments(t)),
                  lambda shape, t: 2 * math.prod(sphere_segments(t))),
    "cy": Builder(lambda shape, t: prism(circle_segments(1.0, t)),
                  lambda shape, t: 4 * circle_segments(1.0, t)),
    "co": Builder(lambda shape, t: pyramid(circle_segments(1.0, t)),
                  lambda shape, t: 4 * circle_segments(1.0, t)),
    "to": Builder(lambda shape, t: torus(shape[0], *torus_segments(shape[0], t)),
                  lambda shape, t: 2 * math.prod(torus_segments(shape[0], t))),
    "pr": Builder(lambda shape, t: prism(int(shape[0])), lambda shape, t: 4 * int(shape[0])),
    "py": Builder(lambda shape, t: pyramid(int(shape[0])), lambda shape, t: 4 * int(shape[0])),
    "ex": Builder(lambda shape, t: extrusion(shape), lambda shape, t: 4 * (len(shape) // 2)),
    "rv": Builder(lambda shape, t: revolution(shape, _revolution_segments(shape, t)),
                  lambda shape, t: 2 * (len(shape) // 2) * _revolution_segments(shape, t)),
}


def build(kind: str, shape: tuple, tolerance: float) -> Mesh:
    """The mesh of primitive ``kind`` with its non-colour arguments ``shape``,
    already checked (castor.language.vocabulary) by the evaluator."""
    return BUILDERS[kind].mesh(shape, tolerance)

"""What the primitives' meshes share: facet counts from the tolerance, and the
rings, fans and quads they are made of (LANGUAGE.md §4.1, §7).

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

import numpy as np

from castor.primitives.base import FLAT, Mesh

MIN_SEGMENTS = 8

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


def ring(n: int, radius: float, z: float) -> np.ndarray:
    angles = 2 * np.pi * np.arange(n) / n
    points = np.empty((n, 3))
    points[:, 0] = radius * np.cos(angles)
    points[:, 1] = radius * np.sin(angles)
    points[:, 2] = z
    points[0, 1] = 0.0
    return points


def fan(indices: np.ndarray, reverse: bool) -> np.ndarray:
    """Triangles of a convex polygon given counter-clockwise (seen from outside unless reverse)."""
    n = len(indices)
    tris = np.column_stack([np.full(n - 2, indices[0]), indices[1:-1], indices[2:]])
    return tris[:, ::-1] if reverse else tris


def joined(vertices, triangle_blocks, face_blocks, surfaces) -> Mesh:
    return Mesh(np.ascontiguousarray(vertices, dtype=np.float64),
                np.ascontiguousarray(np.concatenate(triangle_blocks), dtype=np.int64),
                np.ascontiguousarray(np.concatenate(face_blocks), dtype=np.int64),
                np.asarray(surfaces, dtype=np.int64))


def quads(vertices: np.ndarray, corners: np.ndarray, first_face: int,
          surface: int = FLAT) -> Mesh:
    """Quads (Q, 4) as two triangles each, numbered as faces from ``first_face``,
    all facets of ``surface``."""
    tris = np.concatenate([corners[:, [0, 1, 2]], corners[:, [0, 2, 3]]])
    faces = np.tile(np.arange(first_face, first_face + len(corners)), 2)
    return Mesh(vertices, tris, faces, np.full(first_face + len(corners), surface, np.int64))


def column(n: int, surface: int = FLAT) -> Mesh:
    """Cylinder or prism: a regular n-gon swept from z = 0 to z = 1; its caps
    are flat, its sides facets of ``surface``."""
    vertices = np.concatenate([ring(n, 1.0, 0.0), ring(n, 1.0, 1.0)])
    j = np.arange(n)
    k = (j + 1) % n
    sides = np.column_stack([j, k, n + k, n + j])
    side = quads(vertices, sides, 2)
    return joined(vertices,
                  [fan(j, reverse=True), fan(n + j, reverse=False), side.triangles],
                  [np.zeros(n - 2, np.int64), np.ones(n - 2, np.int64), side.faces],
                  [FLAT, FLAT] + [surface] * n)


def spire(n: int, surface: int = FLAT) -> Mesh:
    """Cone or pyramid: a regular n-gon base in z = 0, apex (0, 0, 1); its base
    is flat, its sides facets of ``surface``."""
    vertices = np.concatenate([ring(n, 1.0, 0.0), [[0.0, 0.0, 1.0]]])
    j = np.arange(n)
    sides = np.column_stack([j, (j + 1) % n, np.full(n, n)])
    return joined(vertices, [fan(j, reverse=True), sides],
                  [np.zeros(n - 2, np.int64), np.arange(1, n + 1)], [FLAT] + [surface] * n)


def signed_volume(vertices: np.ndarray, triangles: np.ndarray) -> float:
    a, b, c = (vertices[triangles[:, i]] for i in range(3))
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)

"""What the primitives' meshes share: facet counts from the tolerance and the
stretch of the primitive's transformation, and the rings, fans and quads they
are made of (LANGUAGE.md §4.1, §7).

The error bound holds after the transformation (LANGUAGE.md §7). The
facetizer hands each curved primitive the linear part of the map from its unit
space to the units its tolerance is in (``Linear``), and the primitive reads
what matters for each of its circles: a circle in the xy plane is stretched by
at most the largest singular value of that map restricted to the xy plane
(``plane_stretch``), whatever it does along z, so a tall thin column gets the
segments its radius needs. A chord of a circle of radius r spanning the angle
2π/n lies at most r·(1 − cos(π/n)) inside the circle, and an affine map moves
that gap by at most the stretch of the circle's plane, so a circle gets
n = max(8, ⌈π / acos(1 − t/r)⌉) segments with r its radius times that stretch.

A tolerance over a stretch is rounded down to a power of 2^(1/4)
(``quantize``), so that near-equal scales share one facetization.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from castor.primitives.base import FLAT, Mesh

if TYPE_CHECKING:  # numpy is imported where it is used: see rays.py
    import numpy as np

MIN_SEGMENTS = 8

# More segments than this for one circle is refused (by the polygon limit).
_HUGE = 10**9


def _half_angle(ratio: float) -> float:
    """acos(1 - ratio), accurate for tiny ratios too (where 1 - ratio rounds to 1)."""
    if ratio > 1e-8:
        return math.acos(1.0 - ratio)
    return math.sqrt(2.0 * ratio)


Linear = tuple[float, ...]  # a 3x3 matrix, row by row


def quantize(tolerance: float) -> float:
    """Round a tolerance down to a power of 2^(1/4), so that near-equal scales
    share one shared subtree and one facetization."""
    if tolerance <= 0 or not math.isfinite(tolerance):
        return tolerance
    # the slack makes it idempotent: a quantized tolerance quantizes to itself
    return 2.0 ** (math.floor(math.log2(tolerance) * 4 + 1e-9) / 4)


def linear_part(matrix: tuple) -> Linear:
    """The 3x3 linear part of a 3x4 affine matrix given row by row."""
    return (matrix[0], matrix[1], matrix[2], matrix[4], matrix[5], matrix[6],
            matrix[8], matrix[9], matrix[10])


def product(a: Linear, b: Linear) -> Linear:
    """The 3x3 product a·b."""
    return tuple(a[3 * i] * b[j] + a[3 * i + 1] * b[3 + j] + a[3 * i + 2] * b[6 + j]
                 for i in range(3) for j in range(3))


def plane_stretch(linear: Linear, i: int = 0, j: int = 1) -> float:
    """The largest factor by which ``linear`` stretches a vector of the plane of
    axes i and j (0 x, 1 y, 2 z): the largest singular value of its columns i, j.
    A circle of radius r in that plane becomes an ellipse whose largest radius
    is r times this."""
    p = linear[i] ** 2 + linear[3 + i] ** 2 + linear[6 + i] ** 2
    q = linear[j] ** 2 + linear[3 + j] ** 2 + linear[6 + j] ** 2
    if p + q < 1e-280:  # squares near underflow (@h(1e-300)): measured scaled up
        big = max(abs(linear[k]) for k in (i, 3 + i, 6 + i, j, 3 + j, 6 + j))
        return big * plane_stretch(tuple(v / big for v in linear), i, j) if big else 0.0
    r = linear[i] * linear[j] + linear[3 + i] * linear[3 + j] + linear[6 + i] * linear[6 + j]
    half = (p - q) / 2
    return math.sqrt((p + q) / 2 + math.sqrt(half * half + r * r))


def largest_stretch(linear: Linear) -> float:
    """The largest factor by which ``linear`` stretches any vector: its largest
    singular value."""
    import numpy as np

    return float(np.linalg.norm(np.array(linear, dtype=np.float64).reshape(3, 3), 2))


def stretch_above(linear: Linear) -> tuple[float, Linear | None]:
    """How a shared subtree placed by ``linear`` is stretched, as its facet
    counts see it: the largest factor s, and the shape of the stretch, the
    symmetric P/s of the polar decomposition linear = R·P (R a rotation or a
    mirror), whose largest singular value is 1; None when it is a rotation
    times a uniform scale (every direction stretched alike). A rotation R after
    the stretch changes no length, so two uses that differ by one share a
    subtree; the shape is rounded to 12 decimals for the same reason."""
    gram = [linear[i] * linear[j] + linear[3 + i] * linear[3 + j] + linear[6 + i] * linear[6 + j]
            for i, j in ((0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2))]
    square = gram[0]
    if (abs(gram[1] - square) <= 1e-12 * square and abs(gram[2] - square) <= 1e-12 * square
            and max(abs(g) for g in gram[3:]) <= 1e-12 * square):
        return math.sqrt(square), None  # a rotation, a mirror, a uniform scale (the commonest)
    import numpy as np  # here: the commonest placements above need none

    a = np.array(linear, dtype=np.float64).reshape(3, 3)
    _, values, turn = np.linalg.svd(a)
    largest = float(values[0])
    if values[2] >= largest * (1 - 1e-9):
        return largest, None
    shape = turn.T @ np.diag(values / largest) @ turn
    return largest, tuple(round(float(x), 12) + 0.0 for x in shape.ravel())


def circle_segments(radius: float, tolerance: float) -> int:
    """Segments for a full circle of ``radius`` within ``tolerance``."""
    if radius <= 0 or tolerance >= radius:
        return MIN_SEGMENTS
    angle = _half_angle(tolerance / radius)
    if angle <= math.pi / _HUGE:
        return _HUGE
    return max(MIN_SEGMENTS, math.ceil(math.pi / angle - 1e-9))


def _sphere_step(tolerance: float) -> float:
    """The angle δ = √2·acos(1 − t) a unit sphere's quads may span in each direction."""
    return math.pi / 4 if tolerance >= 1.0 else math.sqrt(2.0) * _half_angle(tolerance)


def sphere_segments(tolerance: float, flat: float | None = None,
                    ratio: float = 1.0) -> tuple[int, int]:
    """(around, rings) for the unit sphere stretched by at most 1 in any
    direction, within ``tolerance``; when its xy plane is stretched less, by
    ``ratio`` < 1 of the largest, ``flat`` is the tolerance over that stretch.

    A point of the sphere at (φ, θ) and the point of its quad at the same
    parameters differ by e = (1 − m)·p + m(1 − k)·sin φ·h, where p is the point,
    h the horizontal unit vector towards it, 1 − m ≤ 1 − cos(Δφ/2) the gap of
    a meridian's chord and 1 − k ≤ 1 − cos(Δθ/2) that of a latitude circle's. A
    map that stretches by at most 1, and by at most f in the xy plane, moves e
    by at most (1 − cos(Δφ/2)) + cos(Δφ/2)·(1 − cos(Δθ/2))·f. The rings come
    from the largest stretch, as for a ball (δ apart); the segments around
    from the xy plane's, as for a ball of that size, and more if the sum needs
    them. Unstretched (f = 1) that sum is sin²(δ/2) ≤ 1 − cos(δ/√2) = t: the
    counts of a ball."""
    step = _sphere_step(tolerance)
    if step <= 2 * math.pi / _HUGE:
        return _HUGE, _HUGE
    rings = max(MIN_SEGMENTS // 2, math.ceil(math.pi / step - 1e-9))
    if flat is None or flat <= tolerance:
        return max(MIN_SEGMENTS, math.ceil(2 * math.pi / step - 1e-9)), rings
    around_step = _sphere_step(flat)
    if around_step <= 2 * math.pi / _HUGE:
        return _HUGE, rings
    around = max(MIN_SEGMENTS, math.ceil(2 * math.pi / around_step - 1e-9))
    # the sum: what the meridians leave of the tolerance goes to the latitude circles
    half = math.pi / (2 * rings)
    left = (tolerance - (1 - math.cos(half))) / (math.cos(half) * min(1.0, ratio))
    if left <= 0:
        return _HUGE, rings
    return max(around, circle_segments(1.0, left)), rings


def ring(n: int, radius: float, z: float) -> np.ndarray:
    import numpy as np

    angles = 2 * np.pi * np.arange(n) / n
    points = np.empty((n, 3))
    points[:, 0] = radius * np.cos(angles)
    points[:, 1] = radius * np.sin(angles)
    points[:, 2] = z
    points[0, 1] = 0.0
    return points


def fan(indices: np.ndarray, reverse: bool) -> np.ndarray:
    """Triangles of a convex polygon given counter-clockwise (seen from outside unless reverse)."""
    import numpy as np

    n = len(indices)
    tris = np.column_stack([np.full(n - 2, indices[0]), indices[1:-1], indices[2:]])
    return tris[:, ::-1] if reverse else tris


def joined(vertices, triangle_blocks, face_blocks, surfaces) -> Mesh:
    import numpy as np

    return Mesh(np.ascontiguousarray(vertices, dtype=np.float64),
                np.ascontiguousarray(np.concatenate(triangle_blocks), dtype=np.int64),
                np.ascontiguousarray(np.concatenate(face_blocks), dtype=np.int64),
                np.asarray(surfaces, dtype=np.int64))


def quads(vertices: np.ndarray, corners: np.ndarray, first_face: int,
          surface: int = FLAT) -> Mesh:
    """Quads (Q, 4) as two triangles each, numbered as faces from ``first_face``,
    all facets of ``surface``."""
    import numpy as np

    tris = np.concatenate([corners[:, [0, 1, 2]], corners[:, [0, 2, 3]]])
    faces = np.tile(np.arange(first_face, first_face + len(corners)), 2)
    return Mesh(vertices, tris, faces, np.full(first_face + len(corners), surface, np.int64))


def column(n: int, surface: int = FLAT) -> Mesh:
    """Cylinder or prism: a regular n-gon swept from z = 0 to z = 1; its caps
    are flat, its sides facets of ``surface``."""
    import numpy as np

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
    import numpy as np

    vertices = np.concatenate([ring(n, 1.0, 0.0), [[0.0, 0.0, 1.0]]])
    j = np.arange(n)
    sides = np.column_stack([j, (j + 1) % n, np.full(n, n)])
    return joined(vertices, [fan(j, reverse=True), sides],
                  [np.zeros(n - 2, np.int64), np.arange(1, n + 1)], [FLAT] + [surface] * n)


def signed_volume(vertices: np.ndarray, triangles: np.ndarray) -> float:
    import numpy as np

    a, b, c = (vertices[triangles[:, i]] for i in range(3))
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)

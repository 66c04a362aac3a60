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
from typing import NamedTuple

import numpy as np

from castor.diagnostics import GeometryError, Location

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
    if kind == "sp":
        around, rings = sphere_segments(tolerance)
        return 2 * around * rings
    if kind in ("cy", "co"):
        return 4 * circle_segments(1.0, tolerance)
    if kind == "to":
        a, b = torus_segments(shape[0], tolerance)
        return 2 * a * b
    if kind in ("pr", "py"):
        return 4 * int(shape[0])
    if kind == "ex":
        return 4 * (len(shape) // 2)
    if kind == "rv":
        radius = max(shape[0::2]) if shape else 0.0
        return 2 * (len(shape) // 2) * circle_segments(radius, tolerance)
    return 12


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


def _check_simple(points: np.ndarray, what: str, location: Location, path: object) -> None:
    """Refuse repeated vertices, self-intersection and zero area."""
    n = len(points)
    nxt = np.roll(points, -1, axis=0)
    if np.any(np.all(points == nxt, axis=1)):
        raise GeometryError(f"the {what} of {path} repeats a vertex", location)
    a, b = points, nxt
    d = b - a
    for i in range(n):
        p, r = a[i], d[i]
        # edges that do not share a vertex with edge i
        others = np.array([j for j in range(n) if j != i and j != (i + 1) % n and (j + 1) % n != i])
        if len(others) == 0:
            continue
        q, s = a[others], d[others]
        denom = r[0] * s[:, 1] - r[1] * s[:, 0]
        qp = q - p
        t_num = qp[:, 0] * s[:, 1] - qp[:, 1] * s[:, 0]
        u_num = qp[:, 0] * r[1] - qp[:, 1] * r[0]
        with np.errstate(divide="ignore", invalid="ignore"):
            t = t_num / denom
            u = u_num / denom
        crossing = (denom != 0) & (t >= 0) & (t <= 1) & (u >= 0) & (u <= 1)
        # parallel edges on one line that overlap
        collinear = (denom == 0) & (t_num == 0)
        if np.any(collinear):
            rr = float(r @ r)
            t0 = (qp[collinear] @ r) / rr
            t1 = ((qp[collinear] + s[collinear]) @ r) / rr
            overlap = (np.maximum(t0, t1) >= 0) & (np.minimum(t0, t1) <= 1)
            crossing[np.flatnonzero(collinear)[overlap]] = True
        if np.any(crossing):
            raise GeometryError(f"the {what} of {path} intersects itself (edge {i + 1} crosses "
                                f"edge {int(others[np.argmax(crossing)]) + 1})", location)
        # adjacent edges folding back onto each other
        r_next = d[(i + 1) % n]
        if r[0] * r_next[1] - r[1] * r_next[0] == 0 and float(r @ r_next) < 0:
            raise GeometryError(f"the {what} of {path} folds back on itself at vertex "
                                f"{(i + 1) % n + 1}", location)
    if _signed_area(points) == 0:
        raise GeometryError(f"the {what} of {path} has zero area", location)


def _signed_area(points: np.ndarray) -> float:
    x, y = points[:, 0], points[:, 1]
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


def _polygon(values: tuple, what: str, location: Location, path: object) -> np.ndarray:
    points = np.array(values, dtype=np.float64).reshape(-1, 2)
    if len(points) > 3 and np.all(points[0] == points[-1]):
        points = points[:-1]  # a closing vertex repeating the first is allowed
    if len(points) < 3:
        raise GeometryError(f"the {what} of {path} needs at least 3 vertices", location)
    _check_simple(points, what, location, path)
    return points


def extrusion(values: tuple, location: Location, path: object) -> Mesh:
    """The simple polygon (x1, y1, ...) in z = 0 swept to z = 1."""
    from manifold3d import triangulate

    points = _polygon(values, "polygon", location, path)
    if _signed_area(points) < 0:
        points = points[::-1].copy()
    n = len(points)
    cap = np.asarray(triangulate([points]), dtype=np.int64)
    vertices = np.concatenate([np.column_stack([points, np.zeros(n)]),
                               np.column_stack([points, np.ones(n)])])
    j = np.arange(n)
    k = (j + 1) % n
    side = _quads(vertices, np.column_stack([j, k, n + k, n + j]), 2)
    return _mesh(vertices, [cap[:, ::-1], cap + n, side.triangles],
                 [np.zeros(len(cap), np.int64), np.ones(len(cap), np.int64), side.faces])


def revolution(values: tuple, segments: int, location: Location, path: object) -> Mesh:
    """The simple profile (r1, z1, ...) turned a full circle about the z axis."""
    profile = _profile(values, location, path)
    if _signed_area(profile) < 0:
        profile = profile[::-1].copy()
    n = segments
    m = len(profile)
    on_axis = profile[:, 0] == 0
    # vertex numbers: one per profile point on the axis, n per point off it
    first = np.zeros(m, np.int64)
    count = np.where(on_axis, 1, n)
    first[1:] = np.cumsum(count)[:-1]
    angles = 2 * np.pi * np.arange(n) / n
    cos, sin = np.cos(angles), np.sin(angles)
    sin[0] = 0.0
    blocks = []
    for (r, z), axis in zip(profile, on_axis):
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


def validate(kind: str, shape: tuple, location: Location, path: object) -> None:
    """Refuse arguments that give no valid solid, without building anything."""
    if kind == "to":
        k = shape[0]
        if not 0 < k < 1:
            raise GeometryError(f"the tube radius K of {path} must lie strictly between 0 and 1, "
                                f"not {k:g}", location)
    elif kind in ("pr", "py"):
        n = shape[0]
        if n != int(n) or n < 3:
            raise GeometryError(f"the number of sides N of {path} must be a whole number >= 3, "
                                f"not {n:g}", location)
        if n > 10_000_000:
            raise GeometryError(f"the number of sides N of {path} is too large ({n:g})", location)
    elif kind == "ex":
        _polygon(shape, "polygon", location, path)
    elif kind == "rv":
        _profile(shape, location, path)


def _profile(values: tuple, location: Location, path: object) -> np.ndarray:
    profile = _polygon(values, "profile", location, path)
    if np.any(profile[:, 0] < 0):
        i = int(np.argmax(profile[:, 0] < 0))
        raise GeometryError(f"the profile of {path} has r < 0 at vertex {i + 1} "
                            f"(r = {profile[i, 0]:g}); a profile lies in the half-plane r >= 0",
                            location)
    return profile


def build(kind: str, shape: tuple, tolerance: float, location: Location, path: object) -> Mesh:
    """The mesh of primitive ``kind`` with its non-colour arguments ``shape``."""
    if kind in ("to", "pr", "py"):
        validate(kind, shape, location, path)
    if kind == "cu":
        return cube()
    if kind == "sp":
        return sphere(*sphere_segments(tolerance))
    if kind == "cy":
        return prism(circle_segments(1.0, tolerance))
    if kind == "co":
        return pyramid(circle_segments(1.0, tolerance))
    if kind == "to":
        return torus(shape[0], *torus_segments(shape[0], tolerance))
    if kind in ("pr", "py"):
        return prism(int(shape[0])) if kind == "pr" else pyramid(int(shape[0]))
    if kind == "ex":
        return extrusion(shape, location, path)
    if kind == "rv":
        radius = max(shape[0::2])
        return revolution(shape, circle_segments(radius, tolerance), location, path)
    raise AssertionError(kind)

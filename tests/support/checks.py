"""A frame closed (every edge matched by one opposite edge), its polygons
convex and planar, and outward."""

from __future__ import annotations

from collections import Counter

import numpy as np

from .stream import Frame, newell


def check_closed(frame: Frame) -> None:
    """Every directed edge is matched by exactly one opposite edge (by exact position)."""
    edges = Counter()
    for p in frame.polygons:
        pts = [tuple(v) for v in p.points.tolist()]
        for i in range(len(pts)):
            edges[(pts[i], pts[(i + 1) % len(pts)])] += 1
    for (a, b), count in edges.items():
        assert count == 1, f"edge {a}->{b} used {count} times"
        assert edges.get((b, a)) == 1, f"edge {a}->{b} has no opposite edge"


def check_convex_planar(frame: Frame, slack: float = 1e-7) -> None:
    """Every polygon has 3 corners or more, an area, lies in its plane (within
    ``slack`` of its size) and turns one way (convex), tested on all the
    polygons' arrays at once; the first polygon that fails says why."""
    if not frame.polygons:
        return
    corners, starts = frame.arrays()
    sizes = np.diff(starts)
    polygon = np.repeat(np.arange(len(sizes)), sizes)
    centre = np.add.reduceat(corners, starts[:-1], axis=0) / sizes[:, None]
    about = corners - centre[polygon]
    following = np.arange(len(corners)) + 1
    following[starts[1:] - 1] = starts[:-1]
    normal = np.zeros((len(sizes), 3))
    np.add.at(normal, polygon, np.cross(about, about[following]))  # Newell's, as ``newell``
    length = np.linalg.norm(normal, axis=1)
    degenerate = length <= 0
    unit = normal / np.where(degenerate, 1.0, length)[:, None]
    size = (np.maximum.reduceat(corners, starts[:-1], axis=0)
            - np.minimum.reduceat(corners, starts[:-1], axis=0)).max(axis=1)
    distance = np.abs(np.einsum("ij,ij->i", about, unit[polygon]))
    not_planar = np.maximum.reduceat(distance, starts[:-1]) > slack * np.maximum(size, 1.0)
    edges = corners[following] - corners
    turns = np.einsum("ij,ij->i", np.cross(edges, edges[following]), unit[polygon])
    scale = np.linalg.norm(edges, axis=1) * np.linalg.norm(edges[following], axis=1)
    concave = np.zeros(len(sizes), bool)
    concave[polygon[turns < -slack * scale]] = True
    for i in np.flatnonzero((sizes < 3) | degenerate | not_planar | concave)[:1].tolist():
        path = frame.polygons[i].path
        assert sizes[i] >= 3
        assert not degenerate[i], f"degenerate polygon {path}"
        assert not not_planar[i], f"non-planar polygon {path}"
        assert not concave[i], f"non-convex polygon {path}"


def check_solid(frame: Frame) -> None:
    check_closed(frame)
    check_convex_planar(frame)
    if frame.polygons:
        assert frame.volume() > 0, "surface is not outward oriented"

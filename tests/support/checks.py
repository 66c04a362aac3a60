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
    for p in frame.polygons:
        pts = p.points
        assert len(pts) >= 3
        normal = newell(pts)
        length = np.linalg.norm(normal)
        assert length > 0, f"degenerate polygon {p.path}"
        normal /= length
        size = np.ptp(pts, axis=0).max()
        distance = (pts - pts.mean(axis=0)) @ normal
        assert np.abs(distance).max() <= slack * max(size, 1.0), f"non-planar polygon {p.path}"
        edges = np.roll(pts, -1, axis=0) - pts
        turns = np.cross(edges, np.roll(edges, -1, axis=0)) @ normal
        scale = np.linalg.norm(edges, axis=1) * np.linalg.norm(np.roll(edges, -1, axis=0), axis=1)
        assert np.all(turns >= -slack * scale), f"non-convex polygon {p.path}"


def check_solid(frame: Frame) -> None:
    check_closed(frame)
    check_convex_planar(frame)
    if frame.polygons:
        assert frame.volume() > 0, "surface is not outward oriented"

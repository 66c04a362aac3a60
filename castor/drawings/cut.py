"""The section: each object's solid cut by a plane, as closed loops.

Each convex polygon that crosses the plane does so along one segment; the
segments, oriented so that the cut region lies to their left as seen by the
viewer, join end to end into the loops that bound the poché. A vertex lying
exactly on the plane counts as beyond it (on the kept side), which keeps
every crossing well defined.
"""

from __future__ import annotations

import numpy as np


def polygon_edges(obj) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Each polygon's edges: start vertex, end vertex, polygon number."""
    following = np.arange(1, len(obj.indices) + 1)
    following[obj.offsets[1:] - 1] = obj.offsets[:-1]
    polygon = np.repeat(np.arange(obj.polygon_count), np.diff(obj.offsets))
    return obj.indices, obj.indices[following], polygon


def cut_segments(obj, view, depth: float) -> np.ndarray:
    """(S, 2, 2): the oriented segments along which the plane cuts the object."""
    seen = obj.vertices @ view.basis().T
    removed = seen[:, 2] > depth  # between the viewer and the plane
    a, b, polygon = polygon_edges(obj)
    entering = removed[a] & ~removed[b]
    leaving = ~removed[a] & removed[b]
    if not entering.any():
        return np.zeros((0, 2, 2))

    def crossing(mask):
        i, j = a[mask], b[mask]
        lo, hi = np.minimum(i, j), np.maximum(i, j)  # one point per edge, bit for bit
        t = (seen[lo, 2] - depth) / (seen[lo, 2] - seen[hi, 2])
        points = seen[lo, :2] + t[:, None] * (seen[hi, :2] - seen[lo, :2])
        order = np.argsort(polygon[mask], kind="stable")
        return points[order]

    segments = np.stack([crossing(entering), crossing(leaving)], axis=1)
    keep = np.any(segments[:, 0] != segments[:, 1], axis=1)
    return segments[keep]


def section_area(segments: np.ndarray) -> float:
    """The cut region's area, from its oriented boundary (Green's theorem)."""
    if not len(segments):
        return 0.0
    p, q = segments[:, 0], segments[:, 1]
    return float(np.sum(p[:, 0] * q[:, 1] - q[:, 0] * p[:, 1]) / 2)


def loops_area(loops) -> float:
    """The area enclosed by loops (counter-clockwise outer, clockwise holes)."""
    total = 0.0
    for loop in loops:
        x, y = loop[:, 0], loop[:, 1]
        total += float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y) / 2)
    return total


def cut_loops(obj, view, depth: float) -> list[np.ndarray]:
    """The closed loops bounding the object's cut regions, in page metres."""
    segments = cut_segments(obj, view, depth)
    if not len(segments):
        return []
    size = float(np.abs(segments).max()) + 1.0
    grid = size * 1e-9
    keys = np.round(segments / grid).astype(np.int64)
    starts: dict[tuple, list[int]] = {}
    for k, (x, y) in enumerate(keys[:, 0].tolist()):
        starts.setdefault((x, y), []).append(k)
    used = np.zeros(len(segments), bool)
    loops = []
    for first in range(len(segments)):
        if used[first]:
            continue
        loop = []
        k = first
        while k is not None and not used[k]:
            used[k] = True
            loop.append(segments[k, 0])
            candidates = starts.get(tuple(keys[k, 1].tolist()), [])
            k = next((c for c in candidates if not used[c]), None)
        if len(loop) >= 3:
            loops.append(np.array(loop))
    return loops

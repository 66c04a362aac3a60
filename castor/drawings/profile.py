"""The profile: which seen edges are an object's outline against what lies
behind it, to be drawn with the heavier of the two seen pens.

Just off the middle of each seen segment, on either side, the nearest face
the viewer sees there is found. Where that face reaches the segment itself
(its plane, extended, passes through the segment's middle at the segment's
depth) the surface goes on across the edge on that side: a crease between two
seen faces, or a line drawn on one. Where on some side there is no face, or
the nearest one lies behind the edge, the edge stands out against what is
behind it (the sky, the ground, a wall farther off, the room seen through a
window with no glass): it is profile.
"""

from __future__ import annotations

import numpy as np


def _nearest_plane(points, tris, planes, depth, candidates):
    """For page points (N, 2): the plane (gx, gy, c) of the nearest face that
    covers each, NaN where none does. ``candidates(points)`` gives the
    (point, triangle) pairs whose boxes meet."""
    found = np.full((len(points), 3), np.nan)
    if not len(tris) or not len(points):
        return found
    point, tri = candidates(points)
    if not len(point):
        return found
    p = points[point]
    t = tris[tri, :, :2]
    inside = np.ones(len(point), bool)
    area = ((t[:, 1, 0] - t[:, 0, 0]) * (t[:, 2, 1] - t[:, 0, 1])
            - (t[:, 1, 1] - t[:, 0, 1]) * (t[:, 2, 0] - t[:, 0, 0]))
    for k in range(3):
        a, b = t[:, k], t[:, (k + 1) % 3]
        side = (b[:, 0] - a[:, 0]) * (p[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (p[:, 0] - a[:, 0])
        inside &= side * np.sign(area) >= 0
    plane = planes[tri]
    z = plane[:, 2] + plane[:, 0] * p[:, 0] + plane[:, 1] * p[:, 1]
    if depth is not None:
        inside &= z <= depth + 1e-9 * max(1.0, abs(depth))
    point, plane, z = point[inside], plane[inside], z[inside]
    order = np.lexsort((-z, point))  # for each point, its nearest face first
    point, plane = point[order], plane[order]
    first = np.ones(len(point), bool)
    first[1:] = point[1:] != point[:-1]
    found[point[first]] = plane[first]
    return found


def profile_mask(segments, zmid, tris, planes, depth, extent, candidates) -> np.ndarray:
    """(L,) bool: which seen segments (L, 2, 2), whose middles lie at depth
    ``zmid``, are profile (see the module's text)."""
    if not len(segments):
        return np.zeros(0, bool)
    a, b = segments[:, 0], segments[:, 1]
    mid = (a + b) / 2
    d = b - a
    length = np.hypot(d[:, 0], d[:, 1])
    normal = np.column_stack([-d[:, 1], d[:, 0]]) / np.maximum(length, 1e-300)[:, None]
    step = np.minimum(extent * 2e-5, length / 4)[:, None]
    sides = np.concatenate([mid + step * normal, mid - step * normal])
    plane = _nearest_plane(sides, tris, planes, depth, candidates)
    mid2 = np.concatenate([mid, mid])
    at_edge = plane[:, 2] + plane[:, 0] * mid2[:, 0] + plane[:, 1] * mid2[:, 1]
    tol = extent * 1e-6
    attached = np.abs(at_edge - np.concatenate([zmid, zmid])) <= tol  # NaN: False
    n = len(segments)
    return ~(attached[:n] & attached[n:])

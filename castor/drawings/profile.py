"""The profile: which seen edges are an object's outline against what lies
behind it, to be drawn with the heavier of the two seen pens.

An object's outline is the boundary of the region it covers on the page.
Just off the middle of each seen segment, on either side, the object's own
faces (those the viewer could see, beyond the section plane if there is one)
are looked for: where on some side none covers the page, the segment is on
the object's outline, seen against the sky, the ground or another object
behind: profile. Where the object goes on on both sides (a window's frame
with the room behind it seen through the opening, a crease between two
faces, a chimney in front of its own roof), the edge is an ordinary seen one.
"""

from __future__ import annotations

import numpy as np


def _covered(points, owner, tris, tri_owner, planes, depth, candidates) -> np.ndarray:
    """(N,) bool: whether a face of the point's own object covers each page point."""
    found = np.zeros(len(points), bool)
    if not len(tris) or not len(points):
        return found
    point, tri = candidates(points)
    keep = tri_owner[tri] == owner[point]
    point, tri = point[keep], tri[keep]
    if not len(point):
        return found
    p = points[point]
    t = tris[tri, :, :2]
    area = ((t[:, 1, 0] - t[:, 0, 0]) * (t[:, 2, 1] - t[:, 0, 1])
            - (t[:, 1, 1] - t[:, 0, 1]) * (t[:, 2, 0] - t[:, 0, 0]))
    inside = np.ones(len(point), bool)
    for k in range(3):
        a, b = t[:, k], t[:, (k + 1) % 3]
        side = (b[:, 0] - a[:, 0]) * (p[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (p[:, 0] - a[:, 0])
        inside &= side * np.sign(area) >= 0
    if depth is not None:  # what is left of a face the plane cuts: beyond the plane
        plane = planes[tri]
        z = plane[:, 2] + plane[:, 0] * p[:, 0] + plane[:, 1] * p[:, 1]
        inside &= z <= depth + 1e-9 * max(1.0, abs(depth))
    found[point[inside]] = True
    return found


def profile_mask(segments, owner, tris, tri_owner, planes, depth, extent, candidates) -> np.ndarray:
    """(L,) bool: which seen segments (L, 2, 2) of objects ``owner`` are
    profile, given the faces ``tris`` (T, 3, 3) of objects ``tri_owner`` and
    their planes (page depth = c + gx x + gy y)."""
    if not len(segments):
        return np.zeros(0, bool)
    a, b = segments[:, 0], segments[:, 1]
    mid = (a + b) / 2
    d = b - a
    length = np.hypot(d[:, 0], d[:, 1])
    normal = np.column_stack([-d[:, 1], d[:, 0]]) / np.maximum(length, 1e-300)[:, None]
    step = np.minimum(extent * 2e-5, length / 4)[:, None]
    sides = np.concatenate([mid + step * normal, mid - step * normal])
    covered = _covered(sides, np.concatenate([owner, owner]), tris, tri_owner, planes, depth,
                       candidates)
    n = len(segments)
    return ~(covered[:n] & covered[n:])

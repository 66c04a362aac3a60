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


def split_at_junctions(segments, owner, extent, pairs):
    """The segments cut where an end of another seen segment of the same
    object lies on them (a T on the page: the edge of a part standing on a
    ledge), so that each piece is outline or not along its whole length."""
    ends = segments.reshape(-1, 2)
    end_owner = np.repeat(owner, 2)
    lo, hi = segments.min(axis=1), segments.max(axis=1)
    tol = extent * 1e-7  # hidden-line removal ends a piece a hair off the edge it meets
    point, seg = pairs(ends, ends, lo - tol, hi + tol)
    keep = end_owner[point] == owner[seg]
    point, seg = point[keep], seg[keep]
    a, b = segments[seg, 0], segments[seg, 1]
    d = b - a
    length2 = np.einsum("ij,ij->i", d, d)
    t = np.einsum("ij,ij->i", ends[point] - a, d) / np.maximum(length2, 1e-300)
    off = np.abs(d[:, 0] * (ends[point, 1] - a[:, 1]) - d[:, 1] * (ends[point, 0] - a[:, 0]))
    on = (off <= tol * np.sqrt(length2)) & (t > 1e-9) & (t < 1 - 1e-9)
    seg, t = seg[on], t[on]
    if not len(seg):
        return segments, owner
    cuts = np.concatenate([seg, np.arange(len(segments)), np.arange(len(segments))])
    ts = np.concatenate([t, np.zeros(len(segments)), np.ones(len(segments))])
    order = np.lexsort((ts, cuts))
    cuts, ts = cuts[order], ts[order]
    same = cuts[1:] == cuts[:-1]
    start, end, which = ts[:-1][same], ts[1:][same], cuts[:-1][same]
    keep = end - start > 1e-9
    start, end, which = start[keep], end[keep], which[keep]
    a, d = segments[which, 0], segments[which, 1] - segments[which, 0]
    pieces = np.stack([a + start[:, None] * d, a + end[:, None] * d], axis=1)
    return pieces, owner[which]


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

"""The generalized winding number of a triangle surface at points."""

from __future__ import annotations

import math

import numpy as np


def winding_numbers(triangles: np.ndarray, points: np.ndarray) -> np.ndarray:
    """The generalized winding number of a triangle surface at each point.

    On a closed surface (every directed edge, by exact positions, used as
    often the other way) it is an integer, the signed number of times a ray
    from the point crosses the surface (Jacobson et al. 2013, §3): that count
    is made here along one ray direction for all points, the triangles found
    through a grid, so that thousands of points against tens of thousands of
    triangles take a moment rather than minutes. An open surface's (fractional)
    number is the sum of the triangles' solid angles (Van Oosterom and
    Strackee), point by triangle."""
    triangles = np.asarray(triangles, dtype=np.float64).reshape(-1, 3, 3)
    points = np.asarray(points, dtype=np.float64).reshape(-1, 3)
    if not len(triangles) or not len(points):
        return np.zeros(len(points))
    ids = _closed_vertex_ids(triangles)
    if ids is None:
        return _solid_angle_winding(triangles, points)
    return _crossing_winding(triangles, ids, points)


def _solid_angle_winding(triangles: np.ndarray, points: np.ndarray) -> np.ndarray:
    """Sum of the triangles' solid angles at each point, over 4 pi."""
    out = np.zeros(len(points))
    for start in range(0, len(points), 64):
        q = points[start:start + 64]
        a = triangles[None, :, 0, :] - q[:, None, :]
        b = triangles[None, :, 1, :] - q[:, None, :]
        c = triangles[None, :, 2, :] - q[:, None, :]
        la, lb, lc = (np.linalg.norm(x, axis=2) for x in (a, b, c))
        det = np.einsum("qtj,qtj->qt", a, np.cross(b, c))
        div = (la * lb * lc + np.einsum("qtj,qtj->qt", a, b) * lc
               + np.einsum("qtj,qtj->qt", b, c) * la + np.einsum("qtj,qtj->qt", c, a) * lb)
        out[start:start + 64] = np.arctan2(det, div).sum(axis=1) / (2 * np.pi)
    return out


def _closed_vertex_ids(triangles: np.ndarray) -> np.ndarray | None:
    """Each corner's vertex number (one per exact position), if the surface is
    closed: every directed edge used as often as its reverse; else None."""
    flat = triangles.reshape(-1, 3)
    _, ids = np.unique(flat, axis=0, return_inverse=True)
    ids = ids.reshape(-1, 3)
    start = ids.ravel()
    end = ids[:, [1, 2, 0]].ravel()
    n = int(ids.max()) + 1
    forward = np.sort(start * n + end)
    backward = np.sort(end * n + start)
    return ids if np.array_equal(forward, backward) else None


# a fixed rotation in no special direction: rays along its third axis run
# along no edge or face a scene's grid and right angles make
_RAY_FRAME = None


def _ray_frame() -> np.ndarray:
    global _RAY_FRAME
    if _RAY_FRAME is None:
        a, b, c = 0.6180339887, 1.2247448714, 0.4142135624
        rx = np.array([[1, 0, 0], [0, math.cos(a), -math.sin(a)], [0, math.sin(a), math.cos(a)]])
        ry = np.array([[math.cos(b), 0, math.sin(b)], [0, 1, 0], [-math.sin(b), 0, math.cos(b)]])
        rz = np.array([[math.cos(c), -math.sin(c), 0], [math.sin(c), math.cos(c), 0], [0, 0, 1]])
        _RAY_FRAME = rz @ ry @ rx
    return _RAY_FRAME


def _crossing_winding(triangles: np.ndarray, ids: np.ndarray, points: np.ndarray,
                      pairs_per_chunk: int = 4_000_000) -> np.ndarray:
    """Signed crossings of a closed surface by a ray from each point (up the
    third axis of ``_ray_frame``). Each edge's side test is computed from its
    two ends in one order (the lower vertex number first) for both triangles
    on it, and a point exactly on an edge's line belongs to one side only: a
    ray through an edge is counted once, never twice or not at all."""
    frame = _ray_frame()
    t = triangles @ frame.T
    q = points @ frame.T
    x, y = t[:, :, 0], t[:, :, 1]
    area = ((x[:, 1] - x[:, 0]) * (y[:, 2] - y[:, 0]) - (x[:, 2] - x[:, 0]) * (y[:, 1] - y[:, 0]))
    turn = np.sign(area)  # +1 where the triangle faces up the ray
    keep = turn != 0
    t, ids, turn = t[keep], ids[keep], turn[keep]
    if not len(t):
        return np.zeros(len(points))
    # each side (corner k to k + 1) from its lower-numbered end
    start, end = ids, ids[:, [1, 2, 0]]
    forward = start < end  # the side runs from its lower end
    low = np.where(forward[:, :, None], t, t[:, [1, 2, 0]])
    high = np.where(forward[:, :, None], t[:, [1, 2, 0]], t)
    lx, ly = low[:, :, 0], low[:, :, 1]
    dx, dy = high[:, :, 0] - lx, high[:, :, 1] - ly
    # the side of each line (from its lower end) the triangle's inside lies on;
    # a point on the line is inside where that side is the left
    inside_sign = np.where(forward, 1.0, -1.0) * turn[:, None]
    normal = np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0])
    # the grid: about as many cells as triangles
    lo = np.minimum(t[:, :, :2].min(axis=1).min(axis=0), q[:, :2].min(axis=0))
    hi = np.maximum(t[:, :, :2].max(axis=1).max(axis=0), q[:, :2].max(axis=0))
    cells = int(min(max(math.sqrt(len(t)), 1), 512))
    step = np.maximum((hi - lo) / cells, 1e-300)

    def cell(v):
        return np.clip(((v - lo) / step).astype(np.int64), 0, cells - 1)

    first = cell(t[:, :, :2].min(axis=1))
    last = cell(t[:, :, :2].max(axis=1))
    span = last - first + 1
    per = span[:, 0] * span[:, 1]
    owner = np.repeat(np.arange(len(t)), per)
    local = np.arange(len(owner)) - np.repeat(np.cumsum(per) - per, per)
    cx = first[owner, 0] + local % span[owner, 0]
    cy = first[owner, 1] + local // span[owner, 0]
    key = cy * cells + cx
    order = np.argsort(key, kind="stable")
    owner, key = owner[order], key[order]
    bounds = np.searchsorted(key, np.arange(cells * cells + 1))
    point_cell = cell(q[:, :2])
    point_key = point_cell[:, 1] * cells + point_cell[:, 0]
    begin, count = bounds[point_key], bounds[point_key + 1] - bounds[point_key]
    out = np.zeros(len(points))
    chunk_start = 0
    while chunk_start < len(points):
        total = np.cumsum(count[chunk_start:])
        chunk_end = chunk_start + max(1, int(np.searchsorted(total, pairs_per_chunk)))
        counts = count[chunk_start:chunk_end]
        which = np.repeat(np.arange(chunk_start, chunk_end), counts)
        offset = np.arange(len(which)) - np.repeat(np.cumsum(counts) - counts, counts)
        tri = owner[np.repeat(begin[chunk_start:chunk_end], counts) + offset]
        px, py, pz = q[which, 0], q[which, 1], q[which, 2]
        inside = np.ones(len(which), bool)
        for k in range(3):
            side = dx[tri, k] * (py - ly[tri, k]) - dy[tri, k] * (px - lx[tri, k])
            wanted = inside_sign[tri, k]
            inside &= (side * wanted > 0) | ((side == 0) & (wanted > 0))
        tri, which, px, py, pz = tri[inside], which[inside], px[inside], py[inside], pz[inside]
        n = normal[tri]
        height = t[tri, 0, 2] - (n[:, 0] * (px - t[tri, 0, 0]) + n[:, 1] * (py - t[tri, 0, 1])) / n[:, 2]
        above = height > pz
        out += np.bincount(which[above], weights=turn[tri[above]], minlength=len(points))
        chunk_start = chunk_end
    return out

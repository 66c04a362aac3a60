"""Where pieces cut apart meet again: seams welded, and T-junctions split.

After a sheet is cut out (castor.mesh.sheets), two shells may meet edge to
edge with vertices a rounding apart, or one side of an edge may hold points
the other has not; both are mended here, so that every edge is paired.
"""

from __future__ import annotations

import math

import numpy as np


def keys_in(values: np.ndarray, table: np.ndarray) -> np.ndarray:
    """np.isin(values, table) for integer keys, by one sort of ``table`` and a
    search: the same answer, several times faster on the half-edge keys of a
    frame (np.isin would allocate a table over the keys' whole range)."""
    if not len(table):
        return np.zeros(values.shape, bool)
    ordered = np.sort(table.ravel())
    at = np.searchsorted(ordered, values)
    at[at == len(ordered)] = 0
    return ordered[at] == values


def welded_seams(vertices: np.ndarray, triangles: np.ndarray, eps: float) -> np.ndarray:
    """Two shells that met through a sheet now meet edge to edge, where each
    kept its own vertices (a rounding apart): the vertices of edges left
    without a partner are welded to those within ``eps``."""
    a = triangles.ravel()
    b = np.roll(triangles, -1, axis=1).ravel()
    n = len(vertices) + 1
    forward, backward = a * n + b, b * n + a
    lonely = ~keys_in(forward, backward)
    if not lonely.any():
        return triangles
    ends = np.unique(np.concatenate([a[lonely], b[lonely]]))
    points = vertices[ends]
    table = np.arange(len(vertices))
    for i in range(len(ends)):
        close = np.flatnonzero(np.abs(points[i + 1:] - points[i]).max(axis=1) <= eps)
        for j in close.tolist():
            u, w = int(ends[i]), int(ends[i + 1 + j])
            table[max(table[u], table[w])] = min(table[u], table[w])
    table = table[table]
    return table[triangles]


def without_t_junctions(vertices, triangles, origin_ids, face_ids, eps):
    """Where a cut put points along one side of an edge and not the other, the
    triangle on the other side is split at them, so that every edge is paired
    again: an edge left without a partner gets the ends of the other lonely
    edges that lie on it, in order, and its triangle becomes a fan from its
    opposite corner (or, with points on more than one side, from its centre)."""
    a = triangles.ravel()
    b = np.roll(triangles, -1, axis=1).ravel()
    n = len(vertices) + 1
    lonely = np.flatnonzero(~keys_in(a * n + b, b * n + a))
    if not len(lonely):
        return vertices, triangles, origin_ids, face_ids
    ends = np.unique(np.concatenate([a[lonely], b[lonely]]))
    points = vertices[ends]
    inserted: dict[int, dict[int, list[int]]] = {}  # triangle -> side -> points on it
    for e in lonely.tolist():
        u, v = int(a[e]), int(b[e])
        pu = vertices[u]
        d = vertices[v] - pu
        length = math.sqrt(float(d @ d))
        if length == 0:
            continue
        t = (points - pu) @ d / (length * length)
        off = np.abs(points - (pu + t[:, None] * d)).max(axis=1)
        on = (off <= 1e3 * eps) & (t * length > eps) & ((1 - t) * length > eps)
        on &= (ends != u) & (ends != v)
        if on.any():
            inside = ends[on][np.argsort(t[on], kind="stable")]
            inserted.setdefault(e // 3, {})[e % 3] = inside.tolist()
    if not inserted:
        return vertices, triangles, origin_ids, face_ids
    new_points: list[np.ndarray] = []
    rows, origin, face = [], [], []
    for i, sides in inserted.items():
        tri = triangles[i].tolist()
        if len(sides) == 1:
            (k, inside), = sides.items()
            chain = [tri[k], *inside, tri[(k + 1) % 3]]
            apex = tri[(k + 2) % 3]
            fan = [[chain[j], chain[j + 1], apex] for j in range(len(chain) - 1)]
        else:
            outline = []
            for k in range(3):
                outline.append(tri[k])
                outline.extend(sides.get(k, []))
            centre = len(vertices) + len(new_points)
            new_points.append(vertices[tri].mean(axis=0))
            fan = [[outline[j], outline[(j + 1) % len(outline)], centre] for j in range(len(outline))]
        rows.extend(fan)
        origin.extend([origin_ids[i]] * len(fan))
        face.extend([face_ids[i]] * len(fan))
    keep = np.ones(len(triangles), bool)
    keep[list(inserted)] = False
    if new_points:
        vertices = np.vstack([vertices, np.array(new_points)])
    return (vertices, np.vstack([triangles[keep], np.array(rows, np.int64)]),
            np.concatenate([origin_ids[keep], np.array(origin, np.int64)]),
            np.concatenate([face_ids[keep], np.array(face, np.int64)]))

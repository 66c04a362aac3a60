"""Merge the engine's triangles back into convex polygons.

Triangles are grouped by origin (the primitive they lie on) and face number
(the flat face of that primitive), so a group is planar by construction. Within
a group, neighbouring polygons are merged across their shared edges while the
result stays convex (Hertel-Mehlhorn). Only interior edges are removed, so
every edge of the output is still shared by exactly two polygons in opposite
directions: no T-junctions. Groups of one triangle and of two triangles forming
a convex quad (the facets of spheres and cylinders) are handled with numpy.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

# sin of the angle by which a corner may turn the wrong way and still count
# as convex (rounding in the engine's intersection points)
_CONVEX_SLACK = 1e-9


class Polygons(NamedTuple):
    offsets: np.ndarray  # (P + 1,) start of each polygon in indices
    indices: np.ndarray  # vertex numbers, counter-clockwise from outside
    origin_ids: np.ndarray  # (P,) origin of each polygon


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Row-wise cross product (numpy's np.cross is several times slower)."""
    out = np.empty(np.broadcast_shapes(a.shape, b.shape))
    out[..., 0] = a[..., 1] * b[..., 2] - a[..., 2] * b[..., 1]
    out[..., 1] = a[..., 2] * b[..., 0] - a[..., 0] * b[..., 2]
    out[..., 2] = a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]
    return out


def _norm(a: np.ndarray) -> np.ndarray:
    return np.sqrt(np.einsum("...j,...j->...", a, a))


def _convex_quads(v: np.ndarray, quads: np.ndarray) -> np.ndarray:
    """Which quads (Q, 4) are convex, judged against their own normal."""
    p = v[quads]
    normal = _cross(p[:, 2] - p[:, 0], p[:, 3] - p[:, 1])
    edges = np.roll(p, -1, axis=1) - p
    following = np.roll(edges, -1, axis=1)
    turn = _cross(edges, following)
    dots = np.einsum("qkj,qj->qk", turn, normal)
    normal_length = _norm(normal)
    scale = _norm(edges) * _norm(following) * normal_length[:, None]
    return np.all(dots >= -_CONVEX_SLACK * scale, axis=1) & (normal_length > 0)


def _pairs_to_quads(tris: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """For pairs of triangles (N, 2, 3), the quad they form and whether they share an edge."""
    t1, t2 = tris[:, 0], tris[:, 1]
    n = len(tris)
    quads = np.zeros((n, 4), np.int64)
    found = np.zeros(n, bool)
    for i in range(3):
        x, y, z = t1[:, i], t1[:, (i + 1) % 3], t1[:, (i + 2) % 3]
        for r in range(3):
            # t2 rotated so that it reads (y, x, w)
            a, b, w = t2[:, r], t2[:, (r + 1) % 3], t2[:, (r + 2) % 3]
            hit = (a == y) & (b == x) & ~found
            quads[hit] = np.column_stack([y, z, x, w])[hit]
            found |= hit
    return quads, found


def _merge_group(v: np.ndarray, tris: np.ndarray) -> list[list[int]]:
    """Hertel-Mehlhorn on one planar group of triangles."""
    p = v[tris]
    normal = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]).sum(axis=0)
    length = np.linalg.norm(normal)
    if length == 0:
        return [list(t) for t in tris.tolist()]
    normal = normal / length
    polys: dict[int, list[int]] = {i: t for i, t in enumerate(tris.tolist())}
    owner: dict[tuple[int, int], int] = {}
    for i, t in polys.items():
        for k in range(3):
            owner[(t[k], t[(k + 1) % 3])] = i
    interior = [(a, b) for (a, b) in owner if a < b and (b, a) in owner]
    if not interior:
        return list(polys.values())
    # longest diagonals first: fewer, better-shaped polygons
    ia = np.array(interior)
    lengths = np.linalg.norm(v[ia[:, 0]] - v[ia[:, 1]], axis=1)
    for e in np.argsort(-lengths, kind="stable").tolist():
        a, b = interior[e]
        pi, qi = owner.get((a, b)), owner.get((b, a))
        if pi is None or qi is None or pi == qi:
            continue
        merged = _join(polys[pi], polys[qi], a, b)
        if merged is None or not _convex(v, merged, normal):
            continue
        for k in range(len(polys[qi])):
            owner.pop((polys[qi][k], polys[qi][(k + 1) % len(polys[qi])]), None)
        for k in range(len(polys[pi])):
            owner.pop((polys[pi][k], polys[pi][(k + 1) % len(polys[pi])]), None)
        del polys[qi]
        polys[pi] = merged
        for k in range(len(merged)):
            owner[(merged[k], merged[(k + 1) % len(merged)])] = pi
    return list(polys.values())


def _join(p: list[int], q: list[int], a: int, b: int) -> list[int] | None:
    """The polygon p ∪ q across their shared edge a→b (in p) / b→a (in q)."""
    i = p.index(a)
    p = p[i + 1:] + p[:i + 1]  # now p = [b, ..., a]
    j = q.index(b)
    q = q[j + 1:] + q[:j + 1]  # now q = [a, ..., b]
    merged = p + q[1:-1]
    # remove spikes u, v, u left where the two shared more than one edge
    changed = True
    while changed and len(merged) >= 3:
        changed = False
        n = len(merged)
        for k in range(n):
            if merged[k - 1] == merged[(k + 1) % n]:
                drop = {k, (k + 1) % n}
                merged = [x for idx, x in enumerate(merged) if idx not in drop]
                changed = True
                break
    if len(merged) < 3 or len(set(merged)) != len(merged):
        return None
    return merged


def _convex(v: np.ndarray, poly: list[int], normal: np.ndarray) -> bool:
    p = v[poly]
    edges = np.roll(p, -1, axis=0) - p
    nxt = np.roll(edges, -1, axis=0)
    turn = np.cross(edges, nxt) @ normal
    scale = np.linalg.norm(edges, axis=1) * np.linalg.norm(nxt, axis=1)
    return bool(np.all(turn >= -_CONVEX_SLACK * scale))


def _split_off_plane(vertices: np.ndarray, triangles: np.ndarray, group: np.ndarray) -> np.ndarray:
    """Give a triangle that does not lie in its group's plane a group of its own.

    A group is one flat face of one primitive, so it is planar by construction;
    this is a safety net for the rare sliver the engine labels with a
    neighbouring face, so that no polygon is ever bent.
    """
    p = vertices[triangles]
    normals = _cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])  # length: twice the area
    count = group.max() + 1
    # (np.bincount with weights sums per group far faster than np.add.at)
    plane = np.column_stack([np.bincount(group, normals[:, k], count) for k in range(3)])
    length = _norm(plane)[:, None]
    plane = np.divide(plane, length, out=np.zeros_like(plane), where=length > 0)
    area = _norm(normals)
    centre = p.sum(axis=1) / 3
    per_triangle = plane[group]
    offset = np.bincount(group, area * np.einsum("ij,ij->i", centre, per_triangle), count)
    weight = np.bincount(group, area, count)
    offset = np.divide(offset, weight, out=np.zeros_like(offset), where=weight > 0)
    distance = np.abs(np.einsum("tkj,tj->tk", p, per_triangle) - offset[group][:, None]).max(axis=1)
    scale = max(1.0, float(np.abs(vertices).max())) if len(vertices) else 1.0
    stray = np.flatnonzero(distance > 1e-9 * scale)
    if len(stray):
        group = group.copy()
        group[stray] = count + np.arange(len(stray))
    return group


def merge(vertices: np.ndarray, triangles: np.ndarray, origin_ids: np.ndarray,
          face_ids: np.ndarray) -> Polygons:
    """Convex polygons made of the triangles, one origin each."""
    if len(triangles) == 0:
        return Polygons(np.zeros(1, np.int64), np.zeros(0, np.int64), np.zeros(0, np.int64))
    # A face ID names one flat face of one primitive (engine.triangles puts the
    # primitive's ID in its high bits), so it alone is the group key.
    _, group = np.unique(face_ids, return_inverse=True)
    group = _split_off_plane(vertices, triangles, group.ravel())
    counts = np.bincount(group)
    order = np.argsort(group, kind="stable")
    size = counts[group]

    out_sizes: list[np.ndarray] = []
    out_indices: list[np.ndarray] = []
    out_origin: list[np.ndarray] = []

    singles = np.flatnonzero(size == 1)
    out_sizes.append(np.full(len(singles), 3, np.int64))
    out_indices.append(triangles[singles].ravel())
    out_origin.append(origin_ids[singles])

    general: list[int] = []  # group numbers for the slow path
    pairs_mask = size[order] == 2
    pairs = order[pairs_mask].reshape(-1, 2)
    if len(pairs):
        quads, found = _pairs_to_quads(triangles[pairs])
        good = found.copy()
        good[found] = _convex_quads(vertices, quads[found])
        out_sizes.append(np.full(int(good.sum()), 4, np.int64))
        out_indices.append(quads[good].ravel())
        out_origin.append(origin_ids[pairs[good, 0]])
        bad = pairs[~good]
        out_sizes.append(np.full(2 * len(bad), 3, np.int64))
        out_indices.append(triangles[bad.ravel()].ravel())
        out_origin.append(origin_ids[bad.ravel()])

    big = order[size[order] > 2]
    if len(big):
        big_groups = group[big]
        bounds = np.flatnonzero(np.diff(big_groups)) + 1
        sizes, indices, origins = [], [], []
        for members in np.split(big, bounds):
            for poly in _merge_group(vertices, triangles[members]):
                sizes.append(len(poly))
                indices.extend(poly)
                origins.append(origin_ids[members[0]])
        out_sizes.append(np.array(sizes, np.int64))
        out_indices.append(np.array(indices, np.int64))
        out_origin.append(np.array(origins, np.int64))
    del general

    sizes = np.concatenate(out_sizes)
    offsets = np.zeros(len(sizes) + 1, np.int64)
    np.cumsum(sizes, out=offsets[1:])
    return Polygons(offsets, np.concatenate(out_indices).astype(np.int64),
                    np.concatenate(out_origin).astype(np.int64))


def as_triangles(triangles: np.ndarray, origin_ids: np.ndarray) -> Polygons:
    """The triangles themselves as polygons, for formats that hold triangles only."""
    offsets = np.arange(len(triangles) + 1, dtype=np.int64) * 3
    return Polygons(offsets, triangles.reshape(-1).astype(np.int64), origin_ids.astype(np.int64))

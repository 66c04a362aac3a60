"""Merge the triangles of a solid back into convex polygons.

Triangles are grouped by face number (one flat face of one use of a
primitive: castor.mesh.provenance), so a group is planar by construction.
Within a group, neighbouring polygons are merged across their shared edges
while the result stays convex (Hertel-Mehlhorn). Only interior edges are
removed, so every edge of the output is still shared by exactly two polygons
in opposite directions: no T-junctions. Groups of one triangle and of two
triangles forming a convex quad (the facets of spheres and cylinders) are
handled with numpy.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from castor.mesh.arrays import cross, digest, norm
from castor.mesh.caches import Bounded

# sin of the angle by which a corner may turn the wrong way and still count
# as convex (rounding in the engine's intersection points)
_CONVEX_SLACK = 1e-9


class Polygons(NamedTuple):
    offsets: np.ndarray  # (P + 1,) start of each polygon in indices
    indices: np.ndarray  # vertex numbers, counter-clockwise from outside
    origin_ids: np.ndarray  # (P,) origin of each polygon
    source: np.ndarray  # (P,) one triangle each polygon was made of


def _convex_quads(v: np.ndarray, quads: np.ndarray) -> np.ndarray:
    """Which quads (Q, 4) are convex, judged against their own normal."""
    p = v[quads]
    normal = cross(p[:, 2] - p[:, 0], p[:, 3] - p[:, 1])
    edges = np.roll(p, -1, axis=1) - p
    following = np.roll(edges, -1, axis=1)
    turn = cross(edges, following)
    dots = np.einsum("qkj,qj->qk", turn, normal)
    normal_length = norm(normal)
    scale = norm(edges) * norm(following) * normal_length[:, None]
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
    """Convex polygons covering one planar group of triangles.

    Groups are small (a cap, a face cut by a few booleans), so this works on
    Python lists: numpy's per-call cost would dominate. If the group's outline
    is one convex loop (a cylinder's cap), that loop is the answer; otherwise
    Hertel-Mehlhorn: remove diagonals, longest first, while both sides stay
    convex.
    """
    tri_list = tris.tolist()
    ids = sorted({i for t in tri_list for i in t})
    point = dict(zip(ids, v[ids].tolist()))
    normal = [0.0, 0.0, 0.0]
    for a, b, c in tri_list:
        n = _cross3(_sub(point[b], point[a]), _sub(point[c], point[a]))
        normal[0] += n[0]
        normal[1] += n[1]
        normal[2] += n[2]
    if normal == [0.0, 0.0, 0.0]:
        return [list(t) for t in tri_list]

    owner: dict[tuple[int, int], int] = {}
    for index, (a, b, c) in enumerate(tri_list):
        owner[(a, b)] = owner[(b, c)] = owner[(c, a)] = index
    outline = _single_loop([e for e in owner if (e[1], e[0]) not in owner])
    if outline is not None and _convex(point, outline, normal):
        return [outline]

    polys: dict[int, list[int]] = dict(enumerate(tri_list))
    interior = [(a, b) for (a, b) in owner if a < b and (b, a) in owner]

    def length(edge):
        d = _sub(point[edge[0]], point[edge[1]])
        return d[0] * d[0] + d[1] * d[1] + d[2] * d[2]

    for a, b in sorted(interior, key=length, reverse=True):
        pi, qi = owner.get((a, b)), owner.get((b, a))
        if pi is None or qi is None or pi == qi:
            continue
        merged = _join(polys[pi], polys[qi], a, b)
        if merged is None or not _convex(point, merged, normal):
            continue
        for poly in (polys[qi], polys[pi]):
            for k in range(len(poly)):
                owner.pop((poly[k], poly[(k + 1) % len(poly)]), None)
        del polys[qi]
        polys[pi] = merged
        for k in range(len(merged)):
            owner[(merged[k], merged[(k + 1) % len(merged)])] = pi
    return list(polys.values())


def _groups_polygons(vertices: np.ndarray, triangles: np.ndarray, members: np.ndarray,
                     starts: np.ndarray, known: Bounded | None):
    """``_merge_group`` of each group of triangles (``members``, the groups
    one after the other, each beginning at ``starts``), each on its own
    vertices numbered in their order (so the same polygons, whatever the other
    groups' vertices), or the polygons of a group with the same points and
    triangles merged before (``known``, caches.PROCESS.groups: a face that a
    parameter change did not touch, from one frame to the next). Every
    group's own numbering is made at once; only the merging of a group not
    known goes group by group. Returns each polygon's size, the vertex
    numbers, and each polygon's group."""
    n = len(vertices)
    ends = np.r_[starts[1:], len(members)]
    which = np.repeat(np.arange(len(starts), dtype=np.int64), ends - starts)
    corners = np.repeat(which * n, 3) + triangles[members].ravel()
    unique, inverse = np.unique(corners, return_inverse=True)
    first = np.searchsorted(unique, np.arange(len(starts), dtype=np.int64) * n)
    local = (inverse.ravel() - np.repeat(first[which], 3)).reshape(-1, 3)
    points = vertices[unique % n]
    last = np.r_[first[1:], len(unique)]
    sizes, flat, shift, group = [], [], [], []
    for k, (t0, t1, p0, p1) in enumerate(zip(starts.tolist(), ends.tolist(), first.tolist(),
                                              last.tolist())):
        group_points, group_local = points[p0:p1], local[t0:t1]
        key = None if known is None else digest(group_points, group_local)
        polygons = None if key is None else known.get(key)
        if polygons is None:
            polygons = _merge_group(group_points, group_local)
            if key is not None:
                known.put(key, polygons, len(group_local))
        for poly in polygons:
            sizes.append(len(poly))
            flat.extend(poly)
        shift.append(p0)
        group.append(len(polygons))
    sizes = np.array(sizes, np.int64)
    group = np.repeat(np.arange(len(starts)), group)
    indices = unique[np.array(flat, np.int64) + np.repeat(np.array(shift, np.int64)[group], sizes)] % n
    return sizes, indices, group


def _sub(p, q):
    return (p[0] - q[0], p[1] - q[1], p[2] - q[2])


def _cross3(p, q):
    return (p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2], p[0] * q[1] - p[1] * q[0])


def _single_loop(edges: list[tuple[int, int]]) -> list[int] | None:
    """The vertices of the outline if its edges form exactly one loop."""
    if len(edges) < 3:
        return None
    following: dict[int, int] = {}
    for a, b in edges:
        if a in following:
            return None  # a vertex where the outline touches itself
        following[a] = b
    start = edges[0][0]
    loop = [start]
    node = following[start]
    while node != start:
        loop.append(node)
        node = following.get(node)
        if node is None or len(loop) > len(edges):
            return None
    return loop if len(loop) == len(edges) else None


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


def _convex(point: dict, poly: list[int], normal) -> bool:
    """No corner of ``poly`` turns against ``normal`` (beyond rounding), and
    its corners turn once around, not twice (an outline that touches itself,
    two vertices at one place, can turn left at every corner and wind twice)."""
    n = len(poly)
    length = math.sqrt(normal[0] ** 2 + normal[1] ** 2 + normal[2] ** 2)
    total = 0.0
    for k in range(n):
        p0, p1, p2 = point[poly[k - 1]], point[poly[k]], point[poly[(k + 1) % n]]
        e1 = _sub(p1, p0)
        e2 = _sub(p2, p1)
        c = _cross3(e1, e2)
        turn = c[0] * normal[0] + c[1] * normal[1] + c[2] * normal[2]
        ahead = e1[0] * e2[0] + e1[1] * e2[1] + e1[2] * e2[2]
        if turn <= 0:
            size = (math.sqrt(e1[0] ** 2 + e1[1] ** 2 + e1[2] ** 2)
                    * math.sqrt(e2[0] ** 2 + e2[1] ** 2 + e2[2] ** 2) * length)
            if size == 0 or turn < -_CONVEX_SLACK * size:
                return False  # two corners at one place, or a turn the wrong way
            if ahead < 0 and turn <= _CONVEX_SLACK * size:
                return False  # a spike: the outline goes back the way it came
        if n > 4:
            total += math.atan2(turn / length, e1[0] * e2[0] + e1[1] * e2[1] + e1[2] * e2[2])
    return n <= 4 or total < 3 * math.pi


def _split_off_plane(vertices: np.ndarray, triangles: np.ndarray, group: np.ndarray) -> np.ndarray:
    """Give a triangle that does not lie in its group's plane a group of its own.

    A group is one flat face of one primitive, so it is planar by construction;
    this is a safety net for the rare sliver the engine labels with a
    neighbouring face, so that no polygon is ever bent.
    """
    p = vertices[triangles]
    normals = cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])  # length: twice the area
    count = group.max() + 1
    # (np.bincount with weights sums per group far faster than np.add.at)
    plane = np.column_stack([np.bincount(group, normals[:, k], count) for k in range(3)])
    length = norm(plane)[:, None]
    plane = np.divide(plane, length, out=np.zeros_like(plane), where=length > 0)
    area = norm(normals)
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
          face_ids: np.ndarray, groups: Bounded | None = None) -> Polygons:
    """Convex polygons made of the triangles, one origin each; ``groups``: the
    polygons of groups merged before, by their content (``_group_polygons``)."""
    if len(triangles) == 0:
        return Polygons(np.zeros(1, np.int64), np.zeros(0, np.int64), np.zeros(0, np.int64),
                        np.zeros(0, np.int64))
    # A face number names one flat face of one primitive (provenance.triangles), so
    # it alone is the group key.
    _, group = np.unique(face_ids, return_inverse=True)
    group = _split_off_plane(vertices, triangles, group.ravel())
    counts = np.bincount(group)
    order = np.argsort(group, kind="stable")
    size = counts[group]

    out_sizes: list[np.ndarray] = []
    out_indices: list[np.ndarray] = []
    out_source: list[np.ndarray] = []

    singles = np.flatnonzero(size == 1)
    out_sizes.append(np.full(len(singles), 3, np.int64))
    out_indices.append(triangles[singles].ravel())
    out_source.append(singles)

    general: list[int] = []  # group numbers for the slow path
    pairs_mask = size[order] == 2
    pairs = order[pairs_mask].reshape(-1, 2)
    if len(pairs):
        quads, found = _pairs_to_quads(triangles[pairs])
        good = found.copy()
        good[found] = _convex_quads(vertices, quads[found])
        out_sizes.append(np.full(int(good.sum()), 4, np.int64))
        out_indices.append(quads[good].ravel())
        out_source.append(pairs[good, 0])
        bad = pairs[~good]
        out_sizes.append(np.full(2 * len(bad), 3, np.int64))
        out_indices.append(triangles[bad.ravel()].ravel())
        out_source.append(bad.ravel())

    big = order[size[order] > 2]
    if len(big):
        starts = np.r_[0, np.flatnonzero(np.diff(group[big])) + 1]
        sizes, indices, owner = _groups_polygons(vertices, triangles, big, starts, groups)
        out_sizes.append(sizes)
        out_indices.append(indices)
        out_source.append(big[starts[owner]])
    del general

    sizes = np.concatenate(out_sizes)
    offsets = np.zeros(len(sizes) + 1, np.int64)
    np.cumsum(sizes, out=offsets[1:])
    source = np.concatenate(out_source).astype(np.int64)
    return Polygons(offsets, np.concatenate(out_indices).astype(np.int64), origin_ids[source],
                    source)


def as_triangles(triangles: np.ndarray, origin_ids: np.ndarray) -> Polygons:
    """The triangles themselves as polygons, for formats that hold triangles only."""
    offsets = np.arange(len(triangles) + 1, dtype=np.int64) * 3
    return Polygons(offsets, triangles.reshape(-1).astype(np.int64), origin_ids.astype(np.int64),
                    np.arange(len(triangles), dtype=np.int64))


def still_convex(vertices: np.ndarray, offsets: np.ndarray, indices: np.ndarray) -> bool:
    """Whether every polygon is planar and convex on these vertices (all at once)."""
    if len(indices) == 0:
        return True
    p = vertices[indices]
    starts = offsets[:-1]
    following = np.arange(1, len(indices) + 1)
    following[offsets[1:] - 1] = starts
    previous = np.arange(-1, len(indices) - 1)
    previous[starts] = offsets[1:] - 1
    normal = np.add.reduceat(cross(p, p[following]), starts, axis=0)
    sizes = np.diff(offsets)
    polygon = np.repeat(np.arange(len(sizes)), sizes)
    n = normal[polygon]
    e_in = p - p[previous]
    e_out = p[following] - p
    turn = np.einsum("ij,ij->i", cross(e_in, e_out), n)
    if np.any(turn < -_CONVEX_SLACK * norm(e_in) * norm(e_out) * norm(n)):
        return False
    length = norm(normal)
    if np.any(length == 0):
        return False
    unit = (normal / length[:, None])[polygon]
    centre = (np.add.reduceat(p, starts, axis=0) / sizes[:, None])[polygon]
    scale = max(1.0, float(np.abs(p).max()))
    return bool(np.all(np.abs(np.einsum("ij,ij->i", p - centre, unit)) <= 1e-9 * scale))


class Merger:
    """Merges parts into polygons, reusing the work for parts of one pattern.

    Copies of a shared object arrive as parts with the same triangles and the
    same faces, only moved: their polygons are the first copy's, once checked
    planar and convex where this copy stands (a copy only translated needs no
    check: its polygons are the first copy's, shifted).
    """

    LARGEST = 200_000  # triangles: bigger parts are merged afresh, not remembered

    def __init__(self, known: Bounded, parts: Bounded | None = None,
                 groups: Bounded | None = None):
        # the triangles and faces of a part -> its polygons and its vertices
        # (the process's cache, castor.mesh.caches: emptied for each frame)
        self.known = known
        # kept across frames (caches.PROCESS.merged, .groups): the polygons of
        # a part, and of a group, with the very same vertices, triangles and
        # faces (what merge gives for them, whatever was merged before)
        self.parts = parts
        self.groups = groups

    def merge(self, vertices, triangles, origin_ids, face_ids) -> Polygons:
        if len(triangles) > self.LARGEST or len(triangles) == 0:
            return merge(vertices, triangles, origin_ids, face_ids, self.groups)
        key = (triangles.tobytes(), face_ids.tobytes())
        known = self.known.get(key)
        if known is not None:
            polygons, first = known
            if _translated(first, vertices) or still_convex(vertices, polygons.offsets,
                                                              polygons.indices):
                return Polygons(polygons.offsets, polygons.indices, origin_ids[polygons.source],
                                polygons.source)
        polygons = self._same(vertices, triangles, origin_ids, face_ids)
        self.known.put(key, (polygons, vertices), len(triangles))
        return polygons

    def _same(self, vertices, triangles, origin_ids, face_ids) -> Polygons:
        """merge's polygons, or those of a part merged before with the same arrays."""
        if self.parts is None:
            return merge(vertices, triangles, origin_ids, face_ids, self.groups)
        key = digest(vertices, triangles, face_ids)
        found = self.parts.get(key)
        if found is not None:
            offsets, indices, source = found
            return Polygons(offsets, indices, origin_ids[source], source)
        polygons = merge(vertices, triangles, origin_ids, face_ids, self.groups)
        self.parts.put(key, (polygons.offsets, polygons.indices, polygons.source),
                       len(triangles))
        return polygons


def _translated(first: np.ndarray, vertices: np.ndarray) -> bool:
    """Whether ``vertices`` are ``first`` moved by one translation (to rounding)."""
    if first.shape != vertices.shape or len(first) == 0:
        return False
    shift = vertices - first
    scale = max(1.0, float(np.abs(vertices).max()), float(np.abs(first).max()))
    return bool(np.all(np.ptp(shift, axis=0) <= 1e-12 * scale))


# A triangle whose height is below this fraction of its longest side is flat:
# the engine's rounding, not a face of the solid.

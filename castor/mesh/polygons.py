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

import math
from typing import NamedTuple

import numpy as np

# sin of the angle by which a corner may turn the wrong way and still count
# as convex (rounding in the engine's intersection points)
_CONVEX_SLACK = 1e-9


class Polygons(NamedTuple):
    offsets: np.ndarray  # (P + 1,) start of each polygon in indices
    indices: np.ndarray  # vertex numbers, counter-clockwise from outside
    origin_ids: np.ndarray  # (P,) origin of each polygon
    source: np.ndarray  # (P,) one triangle each polygon was made of


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
        return Polygons(np.zeros(1, np.int64), np.zeros(0, np.int64), np.zeros(0, np.int64),
                        np.zeros(0, np.int64))
    # A face number names one flat face of one primitive (engine.triangles), so
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
        big_groups = group[big]
        bounds = np.flatnonzero(np.diff(big_groups)) + 1
        sizes, indices, sources = [], [], []
        for members in np.split(big, bounds):
            for poly in _merge_group(vertices, triangles[members]):
                sizes.append(len(poly))
                indices.extend(poly)
                sources.append(members[0])
        out_sizes.append(np.array(sizes, np.int64))
        out_indices.append(np.array(indices, np.int64))
        out_source.append(np.array(sources, np.int64))
    del general

    sizes = np.concatenate(out_sizes)
    offsets = np.zeros(len(sizes) + 1, np.int64)
    np.cumsum(sizes, out=offsets[1:])
    source = np.concatenate(out_source).astype(np.int64)
    return Polygons(offsets, np.concatenate(out_indices).astype(np.int64), origin_ids[source],
                    source)


def fan_triangles(offsets: np.ndarray, indices: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Each convex polygon as a fan of triangles; also the polygon of each triangle."""
    sizes = np.diff(offsets)
    per = np.maximum(sizes - 2, 0)
    polygon = np.repeat(np.arange(len(sizes)), per)
    first = offsets[:-1][polygon]
    k = np.arange(len(polygon)) - np.repeat(np.cumsum(per) - per, per)
    tris = np.column_stack([indices[first], indices[first + k + 1], indices[first + k + 2]])
    return tris, polygon


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
    normal = np.add.reduceat(_cross(p, p[following]), starts, axis=0)
    sizes = np.diff(offsets)
    polygon = np.repeat(np.arange(len(sizes)), sizes)
    n = normal[polygon]
    e_in = p - p[previous]
    e_out = p[following] - p
    turn = np.einsum("ij,ij->i", _cross(e_in, e_out), n)
    if np.any(turn < -_CONVEX_SLACK * _norm(e_in) * _norm(e_out) * _norm(n)):
        return False
    length = _norm(normal)
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

    def __init__(self):
        self.known: dict[tuple[bytes, bytes], tuple[Polygons, np.ndarray]] = {}
        self.remembered = 0  # triangles of the patterns in known

    def merge(self, vertices, triangles, origin_ids, face_ids) -> Polygons:
        if len(triangles) > self.LARGEST or len(triangles) == 0:
            return merge(vertices, triangles, origin_ids, face_ids)
        key = (triangles.tobytes(), face_ids.tobytes())
        known = self.known.get(key)
        if known is not None:
            polygons, first = known
            if _translated(first, vertices) or still_convex(vertices, polygons.offsets,
                                                              polygons.indices):
                return Polygons(polygons.offsets, polygons.indices, origin_ids[polygons.source],
                                polygons.source)
        polygons = merge(vertices, triangles, origin_ids, face_ids)
        if len(self.known) > 10_000 or self.remembered > 2_000_000:
            self.known.clear()  # a bound on what is remembered
            self.remembered = 0
        self.known[key] = (polygons, vertices)
        self.remembered += len(triangles)
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
_FLAT = 1e-10


def flat_triangles(vertices: np.ndarray, triangles: np.ndarray, chunk: int = 1 << 20) -> np.ndarray:
    """Which triangles have (about) zero area: a repeated vertex, or three in a line."""
    flat = np.zeros(len(triangles), bool)
    for start in range(0, len(triangles), chunk):  # in slices: a few temporaries of 3 x chunk
        t = triangles[start:start + chunk]
        p = vertices[t]
        e0, e1, e2 = p[:, 1] - p[:, 0], p[:, 2] - p[:, 1], p[:, 0] - p[:, 2]
        normal = _cross(e0, -e2)
        twice_area_squared = np.einsum("ij,ij->i", normal, normal)
        longest_squared = np.maximum(np.maximum(np.einsum("ij,ij->i", e0, e0),
                                                np.einsum("ij,ij->i", e1, e1)),
                                     np.einsum("ij,ij->i", e2, e2))
        flat[start:start + chunk] = (twice_area_squared <= (_FLAT * longest_squared) ** 2) | (
            (t[:, 0] == t[:, 1]) | (t[:, 1] == t[:, 2]) | (t[:, 2] == t[:, 0]))
    return flat


def without_flat_triangles(vertices: np.ndarray, triangles: np.ndarray, origin_ids: np.ndarray,
                           face_ids: np.ndarray, twins: bool = True):
    """The same closed surface with no flat triangle (LANGUAGE.md §7).

    The engine leaves a few: two vertices at one place, or closer than the
    rounding of the triangle's size (welded into one, and the triangles
    between them dropped), or three in a line (the triangle's
    long edge is flipped with the neighbour across it, which splits the
    neighbour at the middle vertex: the flat triangle's area, zero, goes to a
    triangle in the neighbour's plane). Every edge stays paired. Returns the
    arrays unchanged if there is nothing to do.
    """
    flat = flat_triangles(vertices, triangles)
    if twins:  # (False where no two faces can coincide)
        triangles, origin_ids, face_ids, flat = _without_twins_at_one_place(
            vertices, triangles, origin_ids, face_ids, flat)
    twins = _coincident(triangles) if twins else None
    if twins is not None:  # a sheet of coincident triangles turned towards each other
        keep = ~twins
        triangles, origin_ids, face_ids = triangles[keep], origin_ids[keep], face_ids[keep]
        flat = flat[keep]
    if not flat.any():
        return triangles, origin_ids, face_ids
    triangles = triangles.copy()
    # weld the vertices of flat triangles that are at one place, or closer
    # than rounding: needles, and fins of two flat triangles back to back
    corners = np.unique(triangles[flat])
    points = vertices[corners]
    scale = max(1.0, float(np.abs(points).max()))
    remap = {}
    for i in range(len(corners)):
        close = np.flatnonzero(np.abs(points[i + 1:] - points[i]).max(axis=1) <= 1e-12 * scale)
        for j in close.tolist():
            u, w = int(corners[i]), int(corners[i + 1 + j])
            ru, rw = remap.get(u, u), remap.get(w, w)
            if ru != rw:
                remap[max(ru, rw)] = min(ru, rw)
    if remap:
        table = np.arange(len(vertices))
        for u in sorted(remap):  # chains resolve to their smallest number
            table[u] = table[remap[u]]
        triangles = table[triangles]
    keep = ~((triangles[:, 0] == triangles[:, 1]) | (triangles[:, 1] == triangles[:, 2])
             | (triangles[:, 2] == triangles[:, 0]))
    keep &= ~_twins(triangles, corners)
    triangles, origin_ids, face_ids = triangles[keep], origin_ids[keep], face_ids[keep]
    flat = flat_triangles(vertices, triangles)
    if flat.any():
        triangles, origin_ids, face_ids = _flip_flat(vertices, triangles, origin_ids,
                                                     face_ids, flat)
    return triangles, origin_ids, face_ids


def row_hash(columns: np.ndarray) -> np.ndarray:
    """One number per row of integer columns (a multiplicative hash, wrapping):
    equal rows get equal numbers, so one sort finds them; two rows that share a
    number by chance are told apart by whoever needs them apart."""
    with np.errstate(over="ignore", invalid="ignore"):  # (casting huge rounded values too)
        columns = columns.astype(np.int64, copy=False)
        key = columns[:, 0] * np.int64(-7046029254386353131)
        for column in columns[:, 1:].T:
            key = key * np.int64(-4658895280553007687) + column
    return key


def shared_across(key: np.ndarray, owner: np.ndarray) -> bool:
    """Whether two owners have one key."""
    order = np.argsort(key, kind="stable")
    key, owner = key[order], owner[order]
    return bool(np.any((key[1:] == key[:-1]) & (owner[1:] != owner[:-1])))


def largest_of_each(area: np.ndarray, group: np.ndarray) -> np.ndarray:
    """For each group number, its member of largest area (the first of them,
    if several); -1 for a number no member has."""
    largest = np.full(int(group.max()) + 1, -1.0)
    np.maximum.at(largest, group, area)
    best = np.flatnonzero(area == largest[group])[::-1]
    first = np.full(len(largest), -1, np.int64)
    first[group[best]] = best
    return first


def same_place(vertices: np.ndarray) -> np.ndarray | None:
    """For each vertex, the first vertex at exactly its place; None if no two
    vertices share a place (the usual case, found with one sort)."""
    if len(vertices) < 2:
        return None
    bits = np.ascontiguousarray(vertices + 0.0).view(np.int64).reshape(-1, 3)  # -0 is 0
    key = row_hash(bits)
    order = np.argsort(key, kind="stable")
    sorted_key = key[order]
    repeated = np.flatnonzero(sorted_key[1:] == sorted_key[:-1])
    if not len(repeated):
        return None
    candidates = np.unique(np.concatenate([order[repeated], order[repeated + 1]]))
    _, first, group = np.unique(bits[candidates], axis=0, return_index=True, return_inverse=True)
    table = np.arange(len(vertices))
    table[candidates] = candidates[first][group.ravel()]
    return table if np.any(table != np.arange(len(vertices))) else None


def _without_twins_at_one_place(vertices, triangles, origin_ids, face_ids, flat):
    """Triangles that would be coincident twins turned the other way, but for
    a vertex the engine left twice at one place: both go, and those vertices
    are welded (the sheet they made is gone, and the surface closes there)."""
    table = same_place(vertices)
    if table is None:
        return triangles, origin_ids, face_ids, flat
    twins = _coincident(table[triangles])
    if twins is None:
        return triangles, origin_ids, face_ids, flat
    involved = np.isin(table, table[np.unique(triangles[twins])])
    weld = np.where(involved, table, np.arange(len(vertices)))
    keep = ~twins
    return weld[triangles[keep]], origin_ids[keep], face_ids[keep], flat[keep]


def _coincident(triangles: np.ndarray) -> np.ndarray | None:
    """Triangles whose three vertices another triangle has, turned the other
    way (None if there is none: the usual case, found in a few array passes)."""
    if len(triangles) < 2:
        return None
    t = triangles
    first = np.argmin(t, axis=1)[:, None]
    rows = np.arange(len(t))[:, None]
    forward = t[rows, (first + np.arange(3)) % 3]  # each turn from its smallest vertex
    backward = forward[:, [0, 2, 1]]
    n = int(t.max()) + 1
    if n ** 3 < 2 ** 62:
        key_f = (forward[:, 0] * n + forward[:, 1]) * n + forward[:, 2]
        key_b = (backward[:, 0] * n + backward[:, 1]) * n + backward[:, 2]
    else:
        return None
    # a triangle and its twin have the same corners: look for a repeated set
    # first (one sort), the usual case being that there is none
    corners = np.sort(t, axis=1)
    same = np.sort((corners[:, 0] * n + corners[:, 1]) * n + corners[:, 2])
    if not (same[1:] == same[:-1]).any():
        return None
    hit = np.isin(key_f, key_b)
    if not hit.any():
        return None
    # pair them one to one, so every edge keeps its partner
    found = np.zeros(len(t), bool)
    waiting: dict[int, list[int]] = {}
    for i in np.flatnonzero(hit).tolist():
        partners = waiting.get(int(key_b[i]))
        if partners:
            found[partners.pop()] = True
            found[i] = True
        else:
            waiting.setdefault(int(key_f[i]), []).append(i)
    return found if found.any() else None


def _twins(triangles: np.ndarray, corners: np.ndarray) -> np.ndarray:
    """Triangles near ``corners`` paired with another of the same three
    vertices turned the other way: a sheet of zero thickness, both go."""
    near = np.flatnonzero(np.isin(triangles, corners).any(axis=1))
    found = np.zeros(len(triangles), bool)
    seen: dict[tuple, list[int]] = {}
    for i in near.tolist():
        a, b, c = triangles[i].tolist()
        k = min((a, b, c), (b, c, a), (c, a, b))  # this turn, from its smallest vertex
        reverse = min((a, c, b), (c, b, a), (b, a, c))
        partners = seen.get(reverse)
        if partners:
            found[partners.pop()] = True
            found[i] = True
        else:
            seen.setdefault(k, []).append(i)
    return found


def _flip_flat(vertices, triangles, origin_ids, face_ids, flat):
    """Flip the long edge of each triangle with three vertices in a line."""
    corners = np.unique(triangles[flat])
    near = np.flatnonzero(np.isin(triangles, corners).any(axis=1))
    tris = {int(i): tuple(triangles[i].tolist()) for i in near}
    owner = {}
    for i, (a, b, c) in tris.items():
        owner[(a, b)] = owner[(b, c)] = owner[(c, a)] = i
    origin = origin_ids.copy()
    face = face_ids.copy()
    todo = [int(i) for i in np.flatnonzero(flat)]
    point = vertices
    for _ in range(4 * len(todo) + 16):
        if not todo:
            break
        i = todo.pop()
        t = tris.get(i)
        if t is None or not flat_triangles(point, np.array([t]))[0]:
            continue  # (a flip since it was found may have made it whole)
        p = point[list(t)]
        lengths = [float(np.dot(p[(k + 1) % 3] - p[k], p[(k + 1) % 3] - p[k])) for k in range(3)]
        k = int(np.argmax(lengths))
        u, w, m = t[k], t[(k + 1) % 3], t[(k + 2) % 3]  # long edge u->w, m between them
        n = owner.get((w, u))
        if n is None or n == i:
            continue
        a, b, c = tris[n]
        x = ({a, b, c} - {u, w}).pop() if len({a, b, c} - {u, w}) == 1 else None
        if x is None or x == m:
            continue
        for tri in (t, tris[n]):
            for e in ((tri[0], tri[1]), (tri[1], tri[2]), (tri[2], tri[0])):
                owner.pop(e, None)
        first, second = (m, u, x), (w, m, x)
        tris[i], tris[n] = first, second
        origin[i], face[i] = origin[n], face[n]
        for j, tri in ((i, first), (n, second)):
            for e in ((tri[0], tri[1]), (tri[1], tri[2]), (tri[2], tri[0])):
                owner[e] = j
            if flat_triangles(point, np.array([tri]))[0]:
                todo.append(j)
    rows = np.array(list(tris.keys()), np.int64)
    triangles = triangles.copy()
    triangles[rows] = np.array([tris[r] for r in rows.tolist()], np.int64)
    return triangles, origin, face


# --- sheets: coincident faces turned towards each other ------------------------

def without_sheets(vertices: np.ndarray, triangles: np.ndarray, origin_ids: np.ndarray,
                   face_ids: np.ndarray):
    """The same solid with no sheet: where triangles of one plane turned one way
    overlap triangles turned the other way (a fold or an inner sheet that the
    engine left where faces only touch), the overlap is taken out of both, as
    regularization requires (LANGUAGE.md §7).

    In each such plane, each triangle keeps what the opposite triangles do not
    cover (convex pieces, cut along their edges); the points where the cuts
    meet the edges are put into every triangle along those edges, so that no
    T-junction is left. Returns the arrays unchanged when there is no sheet,
    which is found with a few array passes.
    """
    if len(triangles) < 2:
        return vertices, triangles, origin_ids, face_ids
    planes = _opposed_planes(vertices, triangles, face_ids)
    if not planes:
        return vertices, triangles, origin_ids, face_ids
    return _Resolver(vertices, triangles, origin_ids, face_ids).resolve(planes)


def plane_sign(normals: np.ndarray) -> np.ndarray:
    """One sign for both sides of each plane (unit normals): that which makes
    its first component not about zero positive. (Not its largest component:
    two as large, as in (-0.61, 0.61, -0.5), are told apart by rounding, and
    the two sides of one plane got different signs.)"""
    significant = np.abs(normals) > 1e-3
    first = np.argmax(significant, axis=1)
    sign = np.sign(normals[np.arange(len(normals)), first])
    sign[sign == 0] = 1
    return sign


def _opposed_planes(vertices, triangles, face_ids,
                    chunk: int = 1 << 20) -> list[tuple[np.ndarray, np.ndarray, np.ndarray]]:
    """Groups of triangles in one plane with both orientations: (plane's unit
    normal, triangle numbers, which of them face along the normal).

    The triangles of one face number lie on one flat face of a primitive, so
    a plane is found per face, from its largest triangle (a sliver's normal is
    mostly rounding). Faces whose planes agree to 1e-7 (of the scene's size)
    are one plane: faces that coincide on paper but differ by rounding."""
    scale = max(1.0, float(np.abs(vertices).max()))
    normals, areas = [], []
    for start in range(0, len(triangles), chunk):
        t = triangles[start:start + chunk]
        p0 = vertices[t[:, 0]]
        n = _cross(vertices[t[:, 1]] - p0, vertices[t[:, 2]] - p0)
        normals.append(n)
        areas.append(_norm(n))
    n = np.concatenate(normals) if len(normals) > 1 else normals[0]
    area = np.concatenate(areas) if len(areas) > 1 else areas[0]
    _, face = np.unique(face_ids, return_inverse=True)
    face = face.ravel()
    first = largest_of_each(area, face)  # each face's largest triangle (every face has one)
    big_area = area[first]
    u = n[first] / np.where(big_area > 0, big_area, 1.0)[:, None]
    d = np.einsum("ij,ij->i", u, vertices[triangles[first]].mean(axis=1))
    sign = plane_sign(u)
    u = u * sign[:, None]
    d = d * sign
    key = np.column_stack([np.round(u * 1e7), np.round(d / scale * 1e7)]).astype(np.int64)
    solid_face = big_area > 1e-14 * scale * scale  # a face of only flat triangles has no plane
    key_order = np.lexsort(key.T[::-1])
    key_order = key_order[solid_face[key_order]]
    if len(key_order) < 2:
        return []
    k = key[key_order]
    starts = np.flatnonzero(np.r_[True, np.any(k[1:] != k[:-1], axis=1)])
    ends = np.r_[starts[1:], len(k)]
    # each triangle's own side, where it is no sliver: one face number can hold
    # both (two uses of one primitive at one place, inside results of the engine)
    facing = np.einsum("ij,ij->i", n, u[face]) * sign[face]
    turned = facing < -1e-6 * big_area[face]
    face_turns = np.zeros(len(first), bool)
    face_turns[face[turned]] = True
    positive = np.add.reduceat((sign[key_order] > 0).astype(np.int64), starts)
    both = np.add.reduceat(face_turns[key_order].astype(np.int64), starts) > 0
    mixed = np.flatnonzero(((positive > 0) & (positive < ends - starts)) | both)
    if not len(mixed):
        return []
    # the triangles of each mixed plane's faces
    plane_of_face = np.full(len(first), -1, np.int64)
    for g in mixed.tolist():
        plane_of_face[key_order[starts[g]:ends[g]]] = g
    plane = plane_of_face[face]
    members = np.flatnonzero(plane >= 0)
    members = members[np.argsort(plane[members], kind="stable")]
    bounds = np.flatnonzero(np.diff(plane[members])) + 1
    out = []
    for group in np.split(members, bounds):
        g = int(plane[group[0]])
        normal = u[key_order[starts[g]]]
        up = (sign[face[group]] > 0) != turned[group]
        out.append((normal, group, up))
    return out


class _Resolver:
    """Takes the overlaps of opposite triangles out of their planes (see without_sheets)."""

    def __init__(self, vertices, triangles, origin_ids, face_ids):
        self.vertices = vertices
        self.triangles = triangles
        self.origin_ids = origin_ids
        self.face_ids = face_ids
        self.scale = max(1.0, float(np.abs(vertices).max()))
        self.eps = 1e-12 * self.scale
        self.new_points: list[np.ndarray] = []
        self.crossings: dict[tuple, int] = {}
        self.on_edge: dict[tuple[int, int], set[int]] = {}

    # points: original vertices keep their numbers; new ones follow
    def point(self, v: int) -> np.ndarray:
        n = len(self.vertices)
        return self.vertices[v] if v < n else self.new_points[v - n]

    def resolve(self, planes):
        replaced: dict[int, list[list[int]]] = {}
        for normal, members, up in planes:
            self._plane(normal, members, up, replaced)
        if not replaced:
            return self.vertices, self.triangles, self.origin_ids, self.face_ids
        # every triangle along an edge that gained points gets them too
        touched = set(replaced)
        if self.on_edge:
            t = self.triangles
            a = np.minimum(t, np.roll(t, -1, axis=1))
            b = np.maximum(t, np.roll(t, -1, axis=1))
            n = len(self.vertices) + len(self.new_points) + 1
            keys = np.array([i * n + j for i, j in self.on_edge], dtype=np.int64)
            hit = np.isin(a * n + b, keys).any(axis=1)
            touched |= set(np.flatnonzero(hit).tolist())
        rows, origin, face = [], [], []
        for i in sorted(touched):
            outlines = replaced.get(i, [self.triangles[i].tolist()])
            for outline in outlines:
                for tri in self._fan(self._with_edge_points(outline)):
                    rows.append(tri)
                    origin.append(self.origin_ids[i])
                    face.append(self.face_ids[i])
        keep = np.ones(len(self.triangles), bool)
        keep[sorted(touched)] = False
        vertices = (np.vstack([self.vertices, np.array(self.new_points).reshape(-1, 3)])
                    if self.new_points else self.vertices)
        triangles = np.vstack([self.triangles[keep], np.array(rows, np.int64).reshape(-1, 3)])
        triangles = _welded_seams(vertices, triangles, self.eps)
        origin_ids = np.concatenate([self.origin_ids[keep], np.array(origin, np.int64)])
        face_ids = np.concatenate([self.face_ids[keep], np.array(face, np.int64)])
        return _without_t_junctions(vertices, triangles, origin_ids, face_ids, self.eps)

    def _plane(self, normal, members, up, replaced):
        # a 2D frame in the plane, turned so that x, y, normal is right-handed
        axis = np.eye(3)[int(np.argmin(np.abs(normal)))]
        e1 = np.cross(normal, axis)
        e1 /= np.linalg.norm(e1)
        e2 = np.cross(normal, e1)
        self.e1, self.e2 = e1, e2
        tiny = 1e-12 * self.scale ** 2
        # every triangle as a convex piece, counter-clockwise in the plane's
        # frame: (vertex, support of the edge that leaves it), and its triangle
        pieces = []  # [piece, triangle, facing up]
        for k, i in enumerate(members.tolist()):
            tri = self.triangles[i].tolist()
            outline = tri if up[k] else tri[::-1]
            pieces.append([[(outline[j], _edge(outline[j], outline[(j + 1) % 3])) for j in range(3)],
                           i, bool(up[k])])
        # Cancel overlaps one up against one down, until no up piece overlaps a
        # down piece: each cancellation takes the common part out of both, once,
        # so where the engine left a face twice over one place and one face
        # of the other side, one layer stays (what is left is the net cover).
        changed_triangles = set()
        for _ in range(4 * len(pieces) + 16):
            pair = self._overlapping(pieces, tiny)
            if pair is None:
                break
            a, b = pieces[pair[0]], pieces[pair[1]]
            cut_a = self._subtract(a[0], b[0])
            cut_b = self._subtract(b[0], a[0])
            changed_triangles.update((a[1], b[1]))
            for index in sorted(pair, reverse=True):
                pieces.pop(index)
            pieces += [[q, a[1], a[2]] for q in cut_a] + [[q, b[1], b[2]] for q in cut_b]
        for i in changed_triangles:
            kept = [(piece, facing) for piece, triangle, facing in pieces if triangle == i]
            # back to the triangle's own turn
            replaced[i] = [[v for v, _ in (piece if facing else piece[::-1])] for piece, facing in kept]

    def _overlapping(self, pieces, tiny):
        """An up piece and a down piece that overlap (their indices), the
        closest in area first; None if there is none."""
        flat = [[self._xy(v) for v, _ in piece] for piece, _, _ in pieces]
        boxes = [(min(x for x, _ in q), min(y for _, y in q), max(x for x, _ in q), max(y for _, y in q))
                 for q in flat]
        best = None
        for i, (_, _, facing_i) in enumerate(pieces):
            if not facing_i:
                continue
            for j, (_, _, facing_j) in enumerate(pieces):
                if facing_j or not _boxes_meet(boxes[i], boxes[j], self.eps):
                    continue
                common = _overlap_area(flat[i], flat[j])
                if common > tiny:
                    score = (abs(_area(flat[i]) - _area(flat[j])), -common)
                    if best is None or score < best[0]:
                        best = (score, (i, j))
        return None if best is None else best[1]

    def _xy(self, v):
        q = self.point(v)
        return (float(q @ self.e1), float(q @ self.e2))

    def _subtract(self, piece, cutter):
        """Convex pieces of ``piece`` outside the convex piece ``cutter`` (both
        counter-clockwise, as (vertex, support of the edge that leaves it))."""
        out = []
        rest = piece
        for k in range(len(cutter)):
            (a, line), (b, _) = cutter[k], cutter[(k + 1) % len(cutter)]
            outside = self._clip(rest, a, b, keep_left=False, line=line)
            if outside is not None:
                out.append(outside)
            rest = self._clip(rest, a, b, keep_left=True, line=line)
            if rest is None:
                break
        return out

    def _clip(self, poly, a, b, keep_left, line=None):
        """The part of a convex polygon ((vertex, support of the edge that
        leaves it), ...) on one side of the line a->b (whose support is
        ``line``, the edge a-b if None); None if it has no area."""
        ax, ay = self._xy(a)
        bx, by = self._xy(b)
        dx, dy = bx - ax, by - ay
        size = math.hypot(dx, dy)

        def side(v):
            x, y = self._xy(v)
            s = (dx * (y - ay) - dy * (x - ax)) / size
            s = s if keep_left else -s
            return 0.0 if abs(s) <= self.eps else s

        line = _edge(a, b) if line is None else line
        out = []
        n = len(poly)
        sides = [side(v) for v, _ in poly]
        for k in range(n):
            (u, su), (v, _) = poly[k], poly[(k + 1) % n]
            du, dv = sides[k], sides[(k + 1) % n]
            if du >= 0:
                out.append([u, line if (du == 0 and dv < 0) else su])
            if (du > 0 > dv) or (du < 0 < dv):
                x = self._crossing(su, line)
                out.append([x, line if du > 0 else su])
        if len(out) < 3:
            return None
        pts = [self._xy(v) for v, _ in out]
        area = sum(pts[k][0] * pts[(k + 1) % len(pts)][1] - pts[(k + 1) % len(pts)][0] * pts[k][1]
                   for k in range(len(pts))) / 2
        if area <= 1e-12 * self.scale ** 2:
            return None
        # drop a repeated vertex (a crossing at a corner)
        cleaned = []
        for v, s in out:
            if cleaned and cleaned[-1][0] == v:
                cleaned[-1][1] = s
                continue
            cleaned.append([v, s])
        if len(cleaned) > 1 and cleaned[0][0] == cleaned[-1][0]:
            cleaned.pop()
        return [tuple(x) for x in cleaned] if len(cleaned) >= 3 else None

    def _crossing(self, s1, s2) -> int:
        """The point where the edges s1 and s2 (as lines) cross, numbered once."""
        key = (s1, s2) if s1 <= s2 else (s2, s1)
        known = self.crossings.get(key)
        if known is not None:
            return known
        (i, j), (k, l) = key
        p, q = self.point(i), self.point(j)
        (px, py), (qx, qy) = self._xy(i), self._xy(j)
        (kx, ky), (lx, ly) = self._xy(k), self._xy(l)
        rx, ry, sx, sy = qx - px, qy - py, lx - kx, ly - ky
        den = rx * sy - ry * sx
        t = ((kx - px) * sy - (ky - py) * sx) / den if den != 0 else 0.0
        point = p + t * (q - p)
        vertex = None
        for candidate in (i, j, k, l):
            if np.abs(self.point(candidate) - point).max() <= self.eps:
                vertex = candidate
                break
        if vertex is None:  # three lines through one point: one point
            for k, known_point in enumerate(self.new_points):
                if np.abs(known_point - point).max() <= self.eps:
                    vertex = len(self.vertices) + k
                    break
        if vertex is None:
            vertex = len(self.vertices) + len(self.new_points)
            self.new_points.append(point)
        self.crossings[key] = vertex
        for s in key:
            if vertex not in s:
                self.on_edge.setdefault(s, set()).add(vertex)
        return vertex

    def _with_edge_points(self, outline: list[int]) -> list[int]:
        """The outline with the points that lie on its edges put in, in order."""
        out = []
        n = len(outline)
        for k in range(n):
            u, v = outline[k], outline[(k + 1) % n]
            out.append(u)
            points = self.on_edge.get(_edge(u, v))
            if not points:
                # an edge of a piece may lie along an original edge without
                # being one: look along every edge that holds points, its
                # ends included
                points = set()
                for (i, j), extra in self.on_edge.items():
                    line = {i, j} | extra
                    if u in line and v in line:
                        points |= line
            if points:
                pu, pv = self.point(u), self.point(v)
                d = pv - pu
                length = float(d @ d)
                inside = []
                for w in points - {u, v}:
                    t = float((self.point(w) - pu) @ d) / length
                    off = self.point(w) - (pu + t * d)
                    if self.eps < t * math.sqrt(length) < math.sqrt(length) - self.eps \
                            and np.abs(off).max() <= 1e3 * self.eps:
                        inside.append((t, w))
                out.extend(w for _, w in sorted(inside))
        return out

    def _fan(self, outline: list[int]) -> list[list[int]]:
        """Triangles of a convex outline; with points on its sides, a fan from
        a new point at its centre (a fan from a corner would give flat ones)."""
        if len(outline) == 3:
            return [outline]
        centre = np.mean([self.point(v) for v in outline], axis=0)
        c = len(self.vertices) + len(self.new_points)
        self.new_points.append(centre)
        return [[outline[k], outline[(k + 1) % len(outline)], c] for k in range(len(outline))]


def paired(triangles: np.ndarray) -> bool:
    """Whether every edge is used as often one way as the other (closed, oriented)."""
    if len(triangles) == 0:
        return True
    a = triangles.ravel()
    b = np.roll(triangles, -1, axis=1).ravel()
    n = int(triangles.max()) + 1
    forward, fc = np.unique(a * n + b, return_counts=True)
    backward, bc = np.unique(b * n + a, return_counts=True)
    return len(forward) == len(backward) and bool(np.all(forward == backward) and np.all(fc == bc))


def _welded_seams(vertices: np.ndarray, triangles: np.ndarray, eps: float) -> np.ndarray:
    """Two shells that met through a sheet now meet edge to edge, where each
    kept its own vertices (a rounding apart): the vertices of edges left
    without a partner are welded to those within ``eps``."""
    a = triangles.ravel()
    b = np.roll(triangles, -1, axis=1).ravel()
    n = len(vertices) + 1
    forward, backward = a * n + b, b * n + a
    lonely = ~np.isin(forward, backward)
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


def _without_t_junctions(vertices, triangles, origin_ids, face_ids, eps):
    """Where a cut put points along one side of an edge and not the other, the
    triangle on the other side is split at them, so that every edge is paired
    again: an edge left without a partner gets the ends of the other lonely
    edges that lie on it, in order, and its triangle becomes a fan from its
    opposite corner (or, with points on more than one side, from its centre)."""
    a = triangles.ravel()
    b = np.roll(triangles, -1, axis=1).ravel()
    n = len(vertices) + 1
    lonely = np.flatnonzero(~np.isin(a * n + b, b * n + a))
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


def _edge(a: int, b: int) -> tuple[int, int]:
    return (a, b) if a < b else (b, a)


def _boxes_meet(a, b, eps) -> bool:
    return a[0] < b[2] - eps and b[0] < a[2] - eps and a[1] < b[3] - eps and b[1] < a[3] - eps


def _area(p: list) -> float:
    return sum(p[k][0] * p[(k + 1) % len(p)][1] - p[(k + 1) % len(p)][0] * p[k][1]
               for k in range(len(p))) / 2


def _overlap_area(p: list, q: list) -> float:
    """Area common to two counter-clockwise convex polygons in 2D."""
    out = p
    for k in range(len(q)):
        (ax, ay), (bx, by) = q[k], q[(k + 1) % len(q)]
        points, n = [], len(out)
        for m in range(n):
            (ux, uy), (vx, vy) = out[m], out[(m + 1) % n]
            su = (bx - ax) * (uy - ay) - (by - ay) * (ux - ax)
            sv = (bx - ax) * (vy - ay) - (by - ay) * (vx - ax)
            if su >= 0:
                points.append((ux, uy))
            if (su > 0 > sv) or (su < 0 < sv):
                t = su / (su - sv)
                points.append((ux + t * (vx - ux), uy + t * (vy - uy)))
        out = points
        if len(out) < 3:
            return 0.0
    return sum(out[k][0] * out[(k + 1) % len(out)][1] - out[(k + 1) % len(out)][0] * out[k][1]
               for k in range(len(out))) / 2


def components(count: int, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """For ``count`` items joined in pairs (a[i], b[i]), the label of each item's
    connected group (its smallest member), by label propagation with pointer
    jumping: array operations, no Python loop over the items."""
    label = np.arange(count)
    while len(a):  # hook each root to the smallest label it meets, then jump
        la, lb = label[a], label[b]
        low = np.minimum(la, lb)
        np.minimum.at(label, la, low)
        np.minimum.at(label, lb, low)
        while True:
            jumped = label[label]
            if np.array_equal(jumped, label):
                break
            label = jumped
        if np.array_equal(label[a], label[b]):
            break
    return label

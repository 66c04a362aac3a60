"""Hidden-line removal: the edges a viewer sees, each cut where it passes
behind a face.

The edges drawn are the true edges of the solids, the creases
(castor.mesh.creases: between polygons that are not coplanar, unless they
are facets of one curved surface of one primitive), and the silhouettes, where a
face turned towards the viewer meets one turned away. Polygons come whole,
so a flat face is never crossed by the diagonals of its triangles. Each edge
is then tested against every triangle that could hide it (found through a
grid on the page): the part of the edge inside the triangle's outline and
behind its plane is an interval of the edge's parameter, computed exactly;
what is left of the edge once the intervals are taken away is seen. Beyond
a section plane, only what lies beyond it counts, both edges and faces.
"""

from __future__ import annotations

import math

import numpy as np

from castor.drawings.cut import polygon_edges
from castor.drawings.profile import profile_mask, split_at_junctions
from castor.mesh.arrays import fan_triangles
from castor.mesh.creases import creases, curved_kinds, guessed_same_surface, same_surface

PAIRS_PER_CHUNK = 1_000_000


def _normals(seen: np.ndarray, obj) -> tuple[np.ndarray, np.ndarray]:
    """Each polygon's unit normal (in page coordinates) and its triangles."""
    tris, polygon = fan_triangles(obj.offsets, obj.indices)
    p = seen[tris]
    cross = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    normals = np.zeros((obj.polygon_count, 3))
    np.add.at(normals, polygon, cross)
    length = np.linalg.norm(normals, axis=1)
    normals /= np.where(length > 0, length, 1)[:, None]
    return normals, tris


def _edges(obj, seen: np.ndarray, normals: np.ndarray, facing: float) -> np.ndarray:
    """(E, 2) vertex pairs of the object's drawn edges: creases and silhouettes
    touching a polygon turned towards the viewer."""
    a, b, polygon = polygon_edges(obj)
    if not len(a):
        return np.zeros((0, 2), np.int64)
    lo, hi = np.minimum(a, b), np.maximum(a, b)
    key = lo * (len(seen) + 1) + hi
    order = np.argsort(key, kind="stable")
    key, lo, hi, polygon = key[order], lo[order], hi[order], polygon[order]
    first = np.ones(len(key), bool)
    first[1:] = key[1:] != key[:-1]
    starts = np.flatnonzero(first)
    counts = np.diff(np.append(starts, len(key)))
    p = polygon[starts]
    twin = starts + 1
    has_twin = counts == 2
    q = np.where(has_twin, polygon[np.minimum(twin, len(key) - 1)], p)
    front = normals[:, 2] > facing
    cosine = np.einsum("ij,ij->i", normals[p], normals[q])
    crease = creases(cosine, _same_surface(obj, p, q, cosine))
    silhouette = front[p] != front[q]
    drawn = np.where(has_twin, (crease & (front[p] | front[q])) | silhouette, front[p])
    return np.column_stack([lo[starts], hi[starts]])[drawn]


def _same_surface(obj, p: np.ndarray, q: np.ndarray, cosine: np.ndarray) -> np.ndarray:
    """Whether polygons p and q are facets of one curved surface of one
    primitive: from the surfaces the frame carries, or guessed from their
    primitives' kinds where it carries none."""
    same_origin = obj.origin_of[p] == obj.origin_of[q]
    if obj.surface_of is not None:
        return same_surface(obj.origin_of[p], obj.origin_of[q], obj.surface_of[p],
                            obj.surface_of[q])
    curved = curved_kinds([o.kind for o in obj.origins])
    return guessed_same_surface(same_origin, curved[obj.origin_of[p]], cosine)


def _grid_cells(lo, hi, origin, cell, size):
    """Each box's grid cells: (box number, cell number) pairs."""
    i0 = np.clip(((lo - origin) / cell).astype(np.int64), 0, size - 1)
    i1 = np.clip(((hi - origin) / cell).astype(np.int64), 0, size - 1)
    nx = i1[:, 0] - i0[:, 0] + 1
    count = nx * (i1[:, 1] - i0[:, 1] + 1)
    item = np.repeat(np.arange(len(lo)), count)
    k = np.arange(len(item)) - np.repeat(np.cumsum(count) - count, count)
    cx = i0[item, 0] + k % nx[item]
    cy = i0[item, 1] + k // nx[item]
    return item, cy * size + cx


def _candidate_pairs(edge_lo, edge_hi, tri_lo, tri_hi):
    """(edge, triangle) pairs whose page boxes meet, through a uniform grid."""
    origin = np.minimum(edge_lo.min(axis=0), tri_lo.min(axis=0))
    extent = np.maximum(edge_hi.max(axis=0), tri_hi.max(axis=0)) - origin
    size = int(np.clip(math.sqrt(len(tri_lo)) / 2, 1, 256))
    cell = np.maximum(extent, 1e-12) / size
    e_item, e_cell = _grid_cells(edge_lo, edge_hi, origin, cell, size)
    t_item, t_cell = _grid_cells(tri_lo, tri_hi, origin, cell, size)
    order = np.argsort(t_cell, kind="stable")
    t_item, t_cell = t_item[order], t_cell[order]
    start = np.searchsorted(t_cell, e_cell, "left")
    count = np.searchsorted(t_cell, e_cell, "right") - start
    edges = np.repeat(e_item, count)
    k = np.arange(len(edges)) - np.repeat(np.cumsum(count) - count, count)
    tris = t_item[np.repeat(start, count) + k]
    pairs = np.unique(edges * len(tri_lo) + tris)
    edges, tris = pairs // len(tri_lo), pairs % len(tri_lo)
    meet = np.all((edge_lo[edges] <= tri_hi[tris]) & (tri_lo[tris] <= edge_hi[edges]), axis=1)
    return edges[meet], tris[meet]


def _hidden_intervals(p0, p1, tri, plane, depth, eps2d, epsz):
    """For edges p0→p1 (N, 3) and triangles tri (N, 3, 3), the interval
    (t0, t1) of each edge hidden by its triangle (t0 >= t1: nothing hidden)."""
    n = len(p0)
    t0, t1 = np.zeros(n), np.ones(n)

    def constrain(alpha, beta):
        # alpha + beta t > 0
        nonlocal t0, t1
        with np.errstate(divide="ignore", invalid="ignore"):
            root = -alpha / beta
        t0 = np.where(beta > 0, np.maximum(t0, root), t0)
        t1 = np.where(beta < 0, np.minimum(t1, root), t1)
        t1 = np.where((beta == 0) & (alpha <= 0), -1.0, t1)

    d = p1 - p0
    area = ((tri[:, 1, 0] - tri[:, 0, 0]) * (tri[:, 2, 1] - tri[:, 0, 1])
            - (tri[:, 1, 1] - tri[:, 0, 1]) * (tri[:, 2, 0] - tri[:, 0, 0]))
    orient = np.sign(area)
    for k in range(3):
        a, b = tri[:, k, :2], tri[:, (k + 1) % 3, :2]
        e = b - a
        length = np.maximum(np.hypot(e[:, 0], e[:, 1]), 1e-300)
        # signed distance of p0 + t d to the side a→b, positive inside
        alpha = orient * (e[:, 0] * (p0[:, 1] - a[:, 1]) - e[:, 1] * (p0[:, 0] - a[:, 0])) / length
        beta = orient * (e[:, 0] * d[:, 1] - e[:, 1] * d[:, 0]) / length
        constrain(alpha + eps2d, beta)  # a hair larger: no crack between triangles
    # the triangle's depth over the page: z = c + gx x + gy y
    gx, gy, c = plane[:, 0], plane[:, 1], plane[:, 2]
    z0 = c + gx * p0[:, 0] + gy * p0[:, 1]
    dz = gx * d[:, 0] + gy * d[:, 1]
    constrain(z0 - p0[:, 2] - epsz, dz - d[:, 2])  # the triangle is nearer than the edge
    if depth is not None:
        constrain(depth + epsz - z0, -dz)  # and beyond the section plane
    return t0, t1


def _visible_pieces(count, edge, t0, t1, tol):
    """(edge number, t start, t end) of the seen parts of ``count`` edges."""
    order = np.lexsort((t0, edge))
    edge, t0, t1 = edge[order], t0[order], t1[order]
    lo, hi = t0 + 2 * edge, t1 + 2 * edge
    reach = np.maximum.accumulate(hi)
    before = np.concatenate([[-np.inf], reach[:-1]])
    start = np.maximum(before, 2 * edge)
    gap = lo - start > tol
    pieces = [np.column_stack([edge[gap], start[gap] - 2 * edge[gap], t0[gap]])]
    last = np.ones(len(edge), bool)
    last[:-1] = edge[1:] != edge[:-1]
    end = reach[last] - 2 * edge[last]
    tail = end < 1 - tol
    pieces.append(np.column_stack([edge[last][tail], np.maximum(end[tail], 0), np.ones(tail.sum())]))
    untouched = np.setdiff1d(np.arange(count), edge)
    pieces.append(np.column_stack([untouched, np.zeros(len(untouched)), np.ones(len(untouched))]))
    return np.concatenate(pieces)


def seen_lines(objects, view, depth: float | None) -> list[tuple[np.ndarray, np.ndarray]]:
    """For each object, (L, 2, 2): the seen segments of its edges on the page
    (metres), beyond the section plane at ``depth`` if there is one, and (L,)
    which of them are profile (castor.drawings.profile)."""
    if not objects:
        return []
    basis = view.basis()
    all_p0, all_p1, owner, tris_all, planes = [], [], [], [], []
    for k, obj in enumerate(objects):
        seen = obj.vertices @ basis.T
        normals, tris = _normals(seen, obj)
        pairs = _edges(obj, seen, normals, 1e-9)
        p0, p1 = seen[pairs[:, 0]], seen[pairs[:, 1]]
        if depth is not None:  # keep what lies beyond the plane
            z0, z1 = p0[:, 2] - depth, p1[:, 2] - depth
            keep = (z0 <= 0) | (z1 <= 0)
            p0, p1, z0, z1 = p0[keep], p1[keep], z0[keep], z1[keep]
            with np.errstate(divide="ignore", invalid="ignore"):
                t = np.where(z0 != z1, z0 / (z0 - z1), 0.0)[:, None]
            cut = p0 + t * (p1 - p0)
            p0 = np.where((z0 > 0)[:, None], cut, p0)
            p1 = np.where((z1 > 0)[:, None], cut, p1)
        all_p0.append(p0)
        all_p1.append(p1)
        owner.append(np.full(len(p0), k))
        t = seen[tris]
        nz = np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0])
        length = np.linalg.norm(nz, axis=1)
        occluding = nz[:, 2] > 1e-9 * np.maximum(length, 1e-300)
        if depth is not None:  # cut solids show their insides: every face may hide
            occluding = (np.abs(nz[:, 2]) > 1e-9 * np.maximum(length, 1e-300)) \
                & (t[:, :, 2].min(axis=1) <= depth)
        t, nz = t[occluding], nz[occluding]
        gx, gy = -nz[:, 0] / nz[:, 2], -nz[:, 1] / nz[:, 2]
        c = t[:, 0, 2] - gx * t[:, 0, 0] - gy * t[:, 0, 1]
        tris_all.append(t)
        planes.append(np.column_stack([gx, gy, c]))
    p0, p1 = np.concatenate(all_p0), np.concatenate(all_p1)
    owner = np.concatenate(owner)
    short = np.hypot(*(p1[:, :2] - p0[:, :2]).T) > 0
    p0, p1, owner = p0[short], p1[short], owner[short]
    tris, planes = np.concatenate(tris_all), np.concatenate(planes)
    if not len(p0):
        return [(np.zeros((0, 2, 2)), np.zeros(0, bool)) for _ in objects]
    extent = float(np.ptp(np.concatenate([p0, p1]), axis=0).max()) or 1.0
    eps2d, epsz = extent * 1e-9, extent * 1e-7
    pieces = np.zeros((0, 3))
    if len(tris):
        edge_lo, edge_hi = np.minimum(p0, p1), np.maximum(p0, p1)
        tri_lo, tri_hi = tris.min(axis=1), tris.max(axis=1)
        edges, cand = _candidate_pairs(edge_lo[:, :2], edge_hi[:, :2], tri_lo[:, :2], tri_hi[:, :2])
        nearer = tri_hi[cand, 2] > edge_lo[edges, 2] + epsz
        edges, cand = edges[nearer], cand[nearer]
        hidden_edge, hidden_t0, hidden_t1 = [], [], []
        for s in range(0, len(edges), PAIRS_PER_CHUNK):
            e, c = edges[s:s + PAIRS_PER_CHUNK], cand[s:s + PAIRS_PER_CHUNK]
            t0, t1 = _hidden_intervals(p0[e], p1[e], tris[c], planes[c], depth, eps2d, epsz)
            some = t1 > t0
            hidden_edge.append(e[some])
            hidden_t0.append(t0[some])
            hidden_t1.append(t1[some])
        edge = np.concatenate(hidden_edge) if hidden_edge else np.zeros(0, np.int64)
        pieces = _visible_pieces(len(p0), edge,
                                 np.concatenate(hidden_t0) if hidden_t0 else np.zeros(0),
                                 np.concatenate(hidden_t1) if hidden_t1 else np.zeros(0), 1e-9)
    else:
        pieces = np.column_stack([np.arange(len(p0)), np.zeros(len(p0)), np.ones(len(p0))])
    e = pieces[:, 0].astype(np.int64)
    a = p0[e, :2] + pieces[:, 1:2] * (p1[e, :2] - p0[e, :2])
    b = p0[e, :2] + pieces[:, 2:3] * (p1[e, :2] - p0[e, :2])
    segments = np.stack([a, b], axis=1)
    long_enough = np.hypot(*(b - a).T) > extent * 1e-7
    segments, e = segments[long_enough], e[long_enough]
    order = np.argsort(e, kind="stable")  # edges in a steady order
    segments, e = segments[order], e[order]
    segments, by = split_at_junctions(segments, owner[e], extent, _candidate_pairs)
    tri_owner = np.repeat(np.arange(len(tris_all)), [len(t) for t in tris_all])
    tri_lo, tri_hi = tris.min(axis=1)[:, :2], tris.max(axis=1)[:, :2]
    profile = profile_mask(segments, by, tris, tri_owner, planes, depth, extent,
                           lambda points: _candidate_pairs(points, points, tri_lo, tri_hi))
    return [(segments[by == k], profile[by == k]) for k in range(len(objects))]

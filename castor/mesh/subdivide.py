"""Catmull–Clark subdivision with sharp creases, refined to a tolerance (LANGUAGE.md §7.1).

``@s(A) x`` makes the facets of ``x`` the control mesh of a subdivision
surface. Catmull–Clark's scheme is used on castor's convex polygons rather than
Loop's on the engine's triangles: a face of a box is one quadrilateral, so a
box rounds the same way along its three axes, where Loop's result follows the
diagonals the triangulation happened to choose.

Creases (Hoppe et al. 1994, the Catmull–Clark form of DeRose et al. 1998): an
edge whose two faces' outward normals turn by more than A degrees, or an edge
not shared by exactly two faces, is a crease and stays one at every level
(its halves are creases). A crease edge's new point is its midpoint; a vertex
on exactly two crease edges follows the cubic B-spline curve rule
(1/8, 6/8, 1/8) and has the curve's limit (1/6, 4/6, 1/6); a vertex on three
or more is a corner and stays put; other vertices follow the smooth rule.

Everything is numpy, vectorized over the polygons and edges of a level: a
level is the arrays of one quad mesh, its vertices, its quads' corners, the
control face each quad comes from, and which of its edges are creases.

Refinement: after each level the vertices are pushed to their limit positions
and each quad of that level (two triangles) is compared with the next
level's limit points at the middle of its edges and of its two diagonals;
the greatest gap is the quad's distance to the limit surface. A quad within
the tolerance is written as it is; the others are looked at in the next
level, and a level's quads are all written once their distance, or a third
of it (the distance falls by about four a level), is within the tolerance.
So a control mesh that is already fine in places (a smooth solid in a
boolean smoothed again) is refined only where it is still far from the
limit. Where a quad meets finer ones, its side takes their vertices and it
becomes a fan from its centre: no crack.

A level is made only where it is needed: the quads still too far, and two
rings of quads around them (every quad sharing a vertex with one, twice).
A limit position needs a vertex's ring of quads, a point of the next level
the quads around it, so two rings keep every position that is used exactly
what the whole level would give, and the next level's two rings lie inside
the children of this level's first. Vertices keep their numbers from level
to level (a level's vertex points take the numbers of the vertices they
come from; numbers of vertices outside the part refined are left unused).
The caller's limit on triangles is checked before each level is made,
against what that level will actually hold: a rounded end of a long
smoothed box makes only the end's quads, not the whole box four times over.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from castor.mesh import crossings

# bytes per triangle at the peak of a level (the level being made and the one
# before, their edges sorted, then the engine's copy): see benchmarks/smooth.py
BYTES_PER_TRIANGLE = 500


class SubdivisionLimit(Exception):
    """The smooth solid would need more triangles than the caller allows."""

    def __init__(self, triangles: int, limit: int):
        self.triangles = triangles
        self.limit = limit
        super().__init__(f"smoothing would need at least {triangles:,} triangles "
                         f"(about {triangles * BYTES_PER_TRIANGLE / 2 ** 30:.1f} GB), more "
                         f"than the limit of {limit:,}")


class Smoothed(NamedTuple):
    """The refined surface: triangles, each with the control face it comes from."""

    vertices: np.ndarray  # (V, 3) float64, on the limit surface
    triangles: np.ndarray  # (T, 3) int64, counter-clockwise from outside
    faces: np.ndarray  # (T,) the control polygon each triangle comes from
    levels: int  # how many times the control mesh was subdivided
    distance: float  # the estimated distance of the triangles to the limit surface


class _Level(NamedTuple):
    vertices: np.ndarray  # (V, 3)
    offsets: np.ndarray  # (P + 1,) polygon starts (quads after level 0)
    indices: np.ndarray  # polygon corners
    faces: np.ndarray  # (P,) control polygon of each polygon
    edges: np.ndarray  # (E, 2) vertex pairs, low first
    edge_of: np.ndarray  # (corners,) the edge from each corner to the next
    crease: np.ndarray  # (E,) bool
    corner_next: np.ndarray  # (corners,) the next corner of the same polygon


def _topology(vertices, offsets, indices):
    """The edges of a polygon mesh: (E, 2) pairs, the edge after each corner,
    the number of polygons on each edge, and each corner's successor."""
    n = len(indices)
    following = np.arange(1, n + 1)
    following[offsets[1:] - 1] = offsets[:-1]
    a, b = indices, indices[following]
    low, high = np.minimum(a, b), np.maximum(a, b)
    key = low.astype(np.int64) * (len(vertices) + 1) + high
    unique, first, edge_of, count = np.unique(key, return_index=True, return_inverse=True,
                                              return_counts=True)
    edges = np.column_stack([low[first], high[first]])
    return edges, edge_of.ravel(), count, following


def _normals(vertices, offsets, indices, following):
    """Each polygon's unit normal (Newell's method: right for any planar polygon)."""
    p, q = vertices[indices], vertices[indices[following]]
    cross = np.cross(p, q)
    polygon = np.repeat(np.arange(len(offsets) - 1), np.diff(offsets))
    total = np.zeros((len(offsets) - 1, 3))
    np.add.at(total, polygon, cross)
    length = np.linalg.norm(total, axis=1)
    return total / np.where(length > 0, length, 1.0)[:, None]


def creases(vertices, offsets, indices, angle: float) -> np.ndarray:
    """Which edges of the control mesh are creases for ``@s(angle)``, in the
    order of ``_topology``'s edges: normals turning by more than ``angle``
    degrees, and edges not shared by exactly two polygons."""
    edges, edge_of, count, following = _topology(vertices, offsets, indices)
    normal = _normals(vertices, offsets, indices, following)
    polygon = np.repeat(np.arange(len(offsets) - 1), np.diff(offsets))
    order = np.argsort(edge_of, kind="stable")
    start = np.concatenate([[0], np.cumsum(count)[:-1]])
    pair = count == 2
    first = polygon[order[start[pair]]]
    second = polygon[order[start[pair] + 1]]
    cosine = np.clip(np.einsum("ij,ij->i", normal[first], normal[second]), -1.0, 1.0)
    turn = np.degrees(np.arccos(cosine))
    crease = np.ones(len(edges), bool)
    crease[pair] = turn > angle
    return crease


def _control(vertices, offsets, indices, faces, angle) -> _Level:
    edges, edge_of, _count, following = _topology(vertices, offsets, indices)
    return _Level(vertices, offsets, indices, faces, edges, edge_of,
                  creases(vertices, offsets, indices, angle), following)


def _per_vertex_crease(level: _Level):
    """How many crease edges meet at each vertex, and the sum of their other ends."""
    n = len(level.vertices)
    ends = level.edges[level.crease]
    count = np.bincount(ends.ravel(), minlength=n)
    other = np.zeros((n, 3))
    np.add.at(other, ends[:, 0], level.vertices[ends[:, 1]])
    np.add.at(other, ends[:, 1], level.vertices[ends[:, 0]])
    return count, other


def _sum_at(index, values, n):
    """Row sums of ``values`` grouped by ``index`` (a vectorized scatter-add)."""
    out = np.empty((n, values.shape[1]))
    for axis in range(values.shape[1]):
        out[:, axis] = np.bincount(index, weights=values[:, axis], minlength=n)
    return out


def _refine(level: _Level) -> _Level:
    """One Catmull–Clark step with sharp creases: every polygon becomes one
    quad per corner; vertices are (old vertices, edge points, face points)."""
    v, offsets, indices = level.vertices, level.offsets, level.indices
    nv, ne, npoly = len(v), len(level.edges), len(offsets) - 1
    sides = np.diff(offsets)
    polygon = np.repeat(np.arange(npoly), sides)
    face_point = _sum_at(polygon, v[indices], npoly) / sides[:, None]

    # edge points: the average of the ends and the two face points; the
    # midpoint on a crease
    a, b = level.edges[:, 0], level.edges[:, 1]
    midpoint = (v[a] + v[b]) / 2
    faces_sum = _sum_at(level.edge_of, face_point[polygon], ne)
    faces_count = np.bincount(level.edge_of, minlength=ne)[:, None]
    smooth_edge = (v[a] + v[b] + faces_sum) / (2 + faces_count)
    edge_point = np.where(level.crease[:, None], midpoint, smooth_edge)

    # vertex points: (F + 2R + (n - 3) P) / n, the crease rule, or a corner
    valence = np.bincount(indices, minlength=nv)
    f_avg = _sum_at(indices, face_point[polygon], nv) / np.maximum(valence, 1)[:, None]
    # each edge is seen from two corners at each end: the corner's own edge
    # and the one before it, so the edge midpoints add up twice
    previous_edge = np.empty_like(level.edge_of)
    previous_edge[level.corner_next] = level.edge_of
    r_avg = (_sum_at(indices, midpoint[level.edge_of] + midpoint[previous_edge], nv)
             / (2 * np.maximum(valence, 1))[:, None])
    n = np.maximum(valence, 1)[:, None].astype(float)
    smooth_vertex = (f_avg + 2 * r_avg + (n - 3) * v) / n
    count, other = _per_vertex_crease(level)
    crease_vertex = (other + 6 * v) / 8
    vertex_point = np.where((count == 2)[:, None], crease_vertex,
                            np.where((count >= 3)[:, None], v, smooth_vertex))

    vertices = np.concatenate([vertex_point, edge_point, face_point])
    quads = np.column_stack([indices, nv + level.edge_of, nv + ne + polygon,
                             nv + previous_edge]).ravel()
    corners = len(indices)
    # the new edges, numbered without a sort: the two halves of each old
    # edge (2e from its low end, 2e + 1 from its high end), then one edge
    # from each corner's edge point to its face point (2E + corner)
    halves = np.column_stack([level.edges.ravel(), np.repeat(nv + np.arange(ne), 2)])
    inside = np.column_stack([nv + level.edge_of, nv + ne + polygon])
    edges = np.concatenate([halves, inside])
    crease = np.concatenate([np.repeat(level.crease, 2), np.zeros(corners, bool)])
    previous_corner = np.empty_like(level.corner_next)
    previous_corner[level.corner_next] = np.arange(corners)
    own_half = 2 * level.edge_of + (indices != level.edges[level.edge_of, 0])
    previous_half = 2 * previous_edge + (indices != level.edges[previous_edge, 0])
    edge_of = np.column_stack([own_half, 2 * ne + np.arange(corners),
                               2 * ne + previous_corner, previous_half]).ravel()
    new_corners = np.arange(4 * corners)
    following = new_corners - new_corners % 4 + (new_corners + 1) % 4
    return _Level(vertices, np.arange(0, 4 * corners + 1, 4), quads, level.faces[polygon],
                  edges, edge_of, crease, following)


def _rings(level: _Level, seed: np.ndarray, count: int) -> np.ndarray:
    """The quads of a quad level that share a vertex with one of ``seed``'s
    (a mask), ``count`` times over."""
    quads = level.indices.reshape(-1, 4)
    chosen = seed
    for _ in range(count):
        touched = np.zeros(len(level.vertices), bool)
        touched[quads[chosen].ravel()] = True
        chosen = touched[quads].any(axis=1)
    return chosen


def _part(level: _Level, keep: np.ndarray) -> tuple[_Level, np.ndarray]:
    """The quads ``keep`` of a quad level as a level of their own (the same
    vertex numbers, their edges numbered anew), and each old edge's new
    number (-1 where no kept quad has it)."""
    corners = np.repeat(keep, 4)
    used, edge_of = np.unique(level.edge_of[corners], return_inverse=True)
    renumber = np.full(len(level.edges), -1, np.int64)
    renumber[used] = np.arange(len(used))
    count = 4 * int(keep.sum())
    new_corners = np.arange(count)
    following = new_corners - new_corners % 4 + (new_corners + 1) % 4
    return _Level(level.vertices, np.arange(0, count + 1, 4), level.indices[corners],
                  level.faces[keep], level.edges[used], edge_of.ravel(), level.crease[used],
                  following), renumber


def limit_positions(level: _Level) -> np.ndarray:
    """Where each vertex of a quad level lies on the limit surface:
    (n² P + 4 Σ edge neighbours + Σ diagonal neighbours) / (n (n + 5)) on the
    smooth part, (a + 4 P + b) / 6 on a crease, the vertex itself at a corner."""
    v, indices = level.vertices, level.indices
    nv = len(v)
    quads = indices.reshape(-1, 4)
    # each corner with its following, opposite and preceding corner
    rolled = [np.roll(quads, -k, axis=1).ravel() for k in range(4)]
    here, after, opposite, before = rolled
    valence = np.bincount(here, minlength=nv).astype(float)
    # every edge neighbour is after one corner and before another: 2 Σ e
    edge_sum = _sum_at(here, v[after] + v[before], nv)
    diagonal_sum = _sum_at(here, v[opposite], nv)
    n = np.maximum(valence, 1)[:, None]
    smooth = (n * n * v + 2 * edge_sum + diagonal_sum) / (n * (n + 5))
    count, other = _per_vertex_crease(level)
    crease = (other + 4 * v) / 6
    return np.where((count == 2)[:, None], crease, np.where((count >= 3)[:, None], v, smooth))


def _quad_gaps(coarse: _Level, coarse_limit: np.ndarray, fine_limit: np.ndarray) -> np.ndarray:
    """How far each quad of ``coarse`` (its two triangles, vertices at their
    limit) is from the limit surface: the gap, across the surface, between
    the middle of each of its edges and of its two diagonals and the limit
    point the next level puts there. Only the part along the normal counts:
    on a flat face around a vertex of 3 or 5 edges the points keep sliding
    along the plane from level to level, which moves no facet off the surface."""
    nv, ne = len(coarse.vertices), len(coarse.edges)
    quads = coarse.indices.reshape(-1, 4)
    p = coarse_limit
    normal = np.cross(p[quads[:, 2]] - p[quads[:, 0]], p[quads[:, 3]] - p[quads[:, 1]])
    edge_normal = _sum_at(coarse.edge_of, np.repeat(normal, 4, axis=0), ne)
    normal /= np.maximum(np.linalg.norm(normal, axis=1), 1e-300)[:, None]
    edge_normal /= np.maximum(np.linalg.norm(edge_normal, axis=1), 1e-300)[:, None]
    a, b = coarse.edges[:, 0], coarse.edges[:, 1]
    gap = fine_limit[nv:nv + ne] - (p[a] + p[b]) / 2
    edge_gap = np.abs(np.einsum("ij,ij->i", gap, edge_normal))
    gaps = edge_gap[coarse.edge_of].reshape(-1, 4).max(axis=1)
    centre = fine_limit[nv + ne:]
    for i, j in ((0, 2), (1, 3)):
        gap = centre - (p[quads[:, i]] + p[quads[:, j]]) / 2
        gaps = np.maximum(gaps, np.abs(np.einsum("ij,ij->i", gap, normal)))
    return gaps


def _triangles(quads: np.ndarray, positions: np.ndarray) -> np.ndarray:
    """Each quad as two triangles, cut along its shorter diagonal."""
    p = positions
    first = np.linalg.norm(p[quads[:, 0]] - p[quads[:, 2]], axis=1)
    second = np.linalg.norm(p[quads[:, 1]] - p[quads[:, 3]], axis=1)
    along_first = (first <= second)[:, None]
    t0 = np.where(along_first, quads[:, [0, 1, 2]], quads[:, [1, 2, 3]])
    t1 = np.where(along_first, quads[:, [0, 2, 3]], quads[:, [3, 0, 1]])
    return np.stack([t0, t1], axis=1).reshape(-1, 3)


def _leaf_triangles(levels: list, leaves: list, parents: list, renumbers: list,
                    positions: np.ndarray):
    """The triangles of the quads chosen at each level (``leaves[k]``, a mask
    over the quads of ``levels[k]``; a quad is chosen, or its children are
    looked at, or an ancestor was chosen, or it is only there as a ring
    around those), without cracks: where a chosen quad meets finer ones
    across a side, that side carries their vertices too, and the quad is a
    fan from its centre (the face point of the next level, on the limit
    surface). ``parents[k]`` numbers the quad of ``levels[k - 1]`` each quad
    of ``levels[k]`` comes from, ``renumbers[k]`` its edges (None: as the
    step from ``levels[k - 1]`` made them). Vertices are numbered once for
    all levels (a level's vertices keep their numbers in the next), so the
    pieces meet at the same points."""
    count = len(levels)
    split = []  # which quads of each level have children that are looked at
    active = np.ones(len(levels[0].faces), bool)
    for k in range(count):
        split.append(active & ~leaves[k])
        if k + 1 < count:
            active = split[-1][parents[k + 1]]
    # every side of every chosen quad, as segments (quad, from, to) that are
    # cut in two while the edge they lie on is cut on the other side
    quad_ids, starts, ends, edge, level_of = [], [], [], [], []
    offset = 0
    for k, level in enumerate(levels):
        chosen = np.flatnonzero(leaves[k])
        corners = (4 * chosen[:, None] + np.arange(4)).ravel()
        quads = level.indices.reshape(-1, 4)
        quad_ids.append(offset + np.repeat(chosen, 4))
        starts.append(level.indices[corners])
        ends.append(quads[chosen][:, [1, 2, 3, 0]].ravel())
        edge.append(level.edge_of[corners])
        level_of.append(np.full(len(corners), k))
        offset += len(quads)
    quad_ids, starts, ends, edge, level_of = map(np.concatenate, (quad_ids, starts, ends, edge,
                                                                  level_of))
    for k, level in enumerate(levels[:-1]):
        cut_edges = np.zeros(len(level.edges), bool)
        corners = (4 * np.flatnonzero(split[k])[:, None] + np.arange(4)).ravel()
        cut_edges[level.edge_of[corners]] = True
        cut = (level_of == k) & cut_edges[np.where(level_of == k, edge, 0)]
        if not cut.any():
            continue
        e, a, b = edge[cut], starts[cut], ends[cut]
        middle = len(level.vertices) + e
        low = level.edges[e, 0]
        quad_ids = np.concatenate([quad_ids[~cut], quad_ids[cut], quad_ids[cut]])
        starts = np.concatenate([starts[~cut], a, middle])
        ends = np.concatenate([ends[~cut], middle, b])
        halves = np.concatenate([2 * e + (a != low), 2 * e + (b != low)])
        if renumbers[k + 1] is not None:
            halves = renumbers[k + 1][halves]
        edge = np.concatenate([edge[~cut], halves])
        level_of = np.concatenate([level_of[~cut], np.full(2 * len(e), k + 1)])
    pieces = np.bincount(quad_ids, minlength=offset)
    triangles, faces = [], []
    offset = 0
    for k, level in enumerate(levels):
        quads = level.indices.reshape(-1, 4)
        whole = leaves[k] & (pieces[offset:offset + len(quads)] == 4)
        triangles.append(_triangles(quads[whole], positions))
        faces.append(np.repeat(level.faces[whole], 2))
        offset += len(quads)
    fan = pieces[quad_ids] > 4
    first_quad = np.cumsum([0] + [len(level.faces) for level in levels])
    k = np.searchsorted(first_quad, quad_ids[fan], side="right") - 1
    local = quad_ids[fan] - first_quad[k]
    centre = np.array([len(level.vertices) + len(level.edges) for level in levels])[k] + local
    triangles.append(np.column_stack([centre, starts[fan], ends[fan]]))
    faces.append(np.concatenate([level.faces for level in levels])[quad_ids[fan]])
    return np.concatenate(triangles), np.concatenate(faces)


def has_smooth_edges(vertices, offsets, indices, angle: float) -> bool:
    """Whether ``@s(angle)`` changes this mesh at all (some edge is not a crease)."""
    if len(offsets) < 2:
        return False
    return not creases(vertices, offsets, indices, angle).all()


def smooth(vertices, offsets, indices, angle: float, tolerance: float,
           max_triangles: int) -> Smoothed | None:
    """The control mesh (a closed polygon mesh, polygons counter-clockwise from
    outside) refined until its triangles are within ``tolerance`` of the
    Catmull–Clark limit surface with the creases of ``@s(angle)``; the triangles'
    ``faces`` number the control polygons. None when every edge is a crease
    (the surface is the control mesh itself). Raises ``SubdivisionLimit``
    before a level would exceed ``max_triangles``."""
    vertices = np.asarray(vertices, dtype=np.float64)
    offsets = np.asarray(offsets, dtype=np.int64)
    indices = np.asarray(indices, dtype=np.int64)
    if len(offsets) < 2:
        return None
    level = _control(vertices, offsets, indices, np.arange(len(offsets) - 1), angle)
    if level.crease.all():
        return None
    tolerance = max(float(tolerance), 1e-12)

    def checked_refine(current: _Level) -> _Level:
        quads = len(current.indices)  # one quad per corner of the part refined
        if 2 * quads > max_triangles:
            raise SubdivisionLimit(2 * quads, max_triangles)
        return _refine(current)

    current = checked_refine(level)
    current_limit = limit_positions(current)
    levels, leaves = [], []
    parents, renumbers = [None], [None]  # how each level's quads come from the one before
    written = []  # (vertex numbers, their limit positions) of what may be written
    active = np.ones(len(current.faces), bool)  # quads whose ancestors are all too far
    gap = 0.0
    while True:
        following = checked_refine(current)
        following_limit = limit_positions(following)
        gaps = np.where(active, _quad_gaps(current, current_limit, following_limit), 0.0)
        # what this level may write: the corners of its quads still looked
        # at, and the next level's points on and in them (cut sides, fans)
        near_vertices = np.unique(current.indices.reshape(-1, 4)[active])
        children = np.unique(following.indices.reshape(-1, 4)[np.repeat(active, 4)])
        written += [(near_vertices, current_limit[near_vertices]),
                    (children, following_limit[children])]
        # a level kept for the triangles needs no positions of its own
        levels.append(current._replace(vertices=np.empty((len(current.vertices), 0))))
        worst = float(gaps.max(initial=0.0))
        near = active & (gaps <= tolerance)
        if worst <= tolerance or not math.isfinite(worst):
            leaves.append(active)
            gap = max(gap, worst)
            break
        leaves.append(near)
        gap = max(gap, float(gaps[near].max(initial=0.0)))
        active = np.repeat(active & ~near, 4)
        if worst / 3 <= tolerance:
            levels.append(following._replace(vertices=np.empty((len(following.vertices), 0))))
            parents.append(np.arange(len(following.faces)) // 4)
            renumbers.append(None)
            leaves.append(active)
            gap = max(gap, worst / 3)
            break
        keep = _rings(following, active, 2)
        if keep.all():
            parents.append(np.arange(len(following.faces)) // 4)
            renumbers.append(None)
        else:
            parents.append(np.flatnonzero(keep) // 4)
            following, renumber = _part(following, keep)
            renumbers.append(renumber)
            active = active[keep]
        current, current_limit = following, following_limit
    positions = np.full((len(following_limit), 3), np.nan)
    for numbers, points in written:
        positions[numbers] = points
    triangles, faces = _leaf_triangles(levels, leaves, parents, renumbers, positions)
    corner = np.zeros(len(positions), bool)
    corner[:len(vertices)] = _per_vertex_crease(level)[0] >= 3
    control_normal = _normals(vertices, offsets, indices, level.corner_next)
    triangles, faces = unturned(positions, triangles, faces, control_normal, corner)
    # the two sides of a thin wall that went through each other: a face that
    # stayed flat (its triangles in its control polygon's plane: between
    # creases, alone or with polygons of its plane) stays where it is, the
    # curved side goes back
    anchor = vertices[indices[offsets[:-1]]][faces]  # a corner of each one's control polygon
    on = np.abs(np.einsum("ijk,ik->ij", positions[triangles] - anchor[:, None],
                          control_normal[faces])).max(axis=1)
    size = max(1.0, float(np.abs(vertices).max()))
    flat = np.ones(len(offsets) - 1, bool)
    np.logical_and.at(flat, faces, on <= 1e-9 * size)
    movable = ~corner
    movable[triangles[flat[faces]].ravel()] = False
    positions = crossings.uncrossed(positions, triangles, movable, tolerance)
    used, triangles = np.unique(triangles, return_inverse=True)
    return Smoothed(positions[used], triangles.reshape(-1, 3), faces, len(levels), gap)


def turned(positions: np.ndarray, triangles: np.ndarray, faces: np.ndarray,
           control_normal: np.ndarray) -> np.ndarray:
    """The triangles turned over: facing away from the control polygon they
    come from, and either folded against a neighbour across one of their
    sides (their normals more than 120 degrees apart) or facing away from
    the triangles around them (every triangle that shares a corner with it,
    weighted by area). Facing away from its control polygon alone is no
    fold: a control mesh sheared hard (a cube under a strong ``@m``) has a
    limit surface that turns past its control polygons' normals near their
    corners, smooth all the same, and taking those triangles out moved the
    surface by five times the tolerance."""
    p = positions[triangles]
    normal = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    away = np.einsum("ij,ij->i", normal, control_normal[faces]) < 0
    if not away.any():
        return away
    at_corner = np.zeros((len(positions), 3))
    for k in range(3):
        np.add.at(at_corner, triangles[:, k], normal)
    around = at_corner[triangles].sum(axis=1) - 3 * normal
    against_around = np.einsum("ij,ij->i", normal, around) < 0
    # each side once each way: a side (a, b) of one triangle is (b, a) of its neighbour
    count = len(triangles)
    starts = triangles.ravel()
    ends = triangles[:, [1, 2, 0]].ravel()
    owner = np.repeat(np.arange(count), 3)
    size = len(positions)
    key = starts * size + ends
    order = np.argsort(key)
    twin_key = ends * size + starts
    at = np.clip(np.searchsorted(key[order], twin_key), 0, len(key) - 1)
    paired = key[order][at] == twin_key
    unit = normal / np.maximum(np.linalg.norm(normal, axis=1), 1e-300)[:, None]
    facing = np.ones(3 * count)
    neighbour = owner[order][at]
    facing[paired] = np.einsum("ij,ij->i", unit[owner[paired]], unit[neighbour[paired]])
    folded = facing.reshape(-1, 3).min(axis=1) < -0.5
    return away & (against_around | folded)


def unturned(positions: np.ndarray, triangles: np.ndarray, faces: np.ndarray,
             control_normal: np.ndarray, fixed: np.ndarray, rounds: int = 40):
    """The refined triangles without the slivers turned over. Where a control
    polygon is itself a sliver (three of its corners almost on one line, as a
    boolean of smooth solids leaves beside its seams), Catmull–Clark's limit
    surface folds over itself along it (the reference subdivision folds
    there too): a triangle a hair wide faces inward, a sheet §7 rules out.
    Each such triangle loses its shortest side that can go (both ends become
    one point, at their middle, or at the end that is a ``fixed`` corner;
    not where the ends have other neighbours in common than the side's two
    triangles, which would pinch the surface): the sliver and its neighbour
    across that side go, and the surface moves by the sliver's width.
    ``positions`` is changed in place."""
    for _ in range(rounds):
        bad = np.flatnonzero(turned(positions, triangles, faces, control_normal))
        if not len(bad):
            break
        sides = np.concatenate([triangles[:, [0, 1]], triangles[:, [1, 2]], triangles[:, [2, 0]]])
        order = np.argsort(sides[:, 0], kind="stable")
        starts = np.searchsorted(sides[order, 0], np.arange(len(positions) + 1))

        def ring(v):
            return set(sides[order[starts[v]:starts[v + 1]], 1].tolist())

        merge_into = np.arange(len(positions))
        touched: set = set()
        for t in bad.tolist():
            corners = triangles[t].tolist()
            pairs = [(corners[k], corners[(k + 1) % 3]) for k in range(3)]
            pairs.sort(key=lambda ab: float(np.linalg.norm(positions[ab[0]] - positions[ab[1]])))
            for a, b in pairs:
                if a in touched or b in touched or (fixed[a] and fixed[b]):
                    continue
                around_a, around_b = ring(a), ring(b)
                if len(around_a & around_b) != 2:
                    continue
                if fixed[b]:
                    a, b = b, a
                if not fixed[a]:
                    positions[a] = (positions[a] + positions[b]) / 2
                merge_into[b] = a
                touched |= {a, b} | around_a | around_b
                break
        if not touched:
            break
        triangles = merge_into[triangles]
        whole = ((triangles[:, 0] != triangles[:, 1]) & (triangles[:, 1] != triangles[:, 2])
                 & (triangles[:, 2] != triangles[:, 0]))
        triangles, faces = triangles[whole], faces[whole]
    return triangles, faces


def patches(vertices, offsets, indices, angle: float) -> np.ndarray:
    """For each control polygon, the smooth patch it belongs to: polygons that
    meet across an edge that is no crease for ``@s(angle)`` share one (their
    refined facets are one curved surface; a crease bounds it)."""
    edges, edge_of, count, following = _topology(vertices, offsets, indices)
    crease = creases(vertices, offsets, indices, angle)
    polygon = np.repeat(np.arange(len(offsets) - 1), np.diff(offsets))
    order = np.argsort(edge_of, kind="stable")
    start = np.concatenate([[0], np.cumsum(count)[:-1]])
    smooth_pair = (count == 2) & ~crease
    first = polygon[order[start[smooth_pair]]]
    second = polygon[order[start[smooth_pair] + 1]]
    label = np.arange(len(offsets) - 1)
    while True:  # each polygon takes the least label of its smooth neighbours
        low = np.minimum(label[first], label[second])
        new = label.copy()
        np.minimum.at(new, first, low)
        np.minimum.at(new, second, low)
        new = new[new]  # jump along chains
        if np.array_equal(new, label):
            return label
        label = new

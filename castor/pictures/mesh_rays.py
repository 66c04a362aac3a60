"""Where rays are inside a closed triangle mesh: the spans of a smooth solid.

A smooth solid (LANGUAGE.md §7.1) has no exact surface of its own: pictures
trace it through its refined facets. ``MeshRays`` answers in the form
``castor.pictures.spans`` gives for a primitive: for rays ``o + t d`` (``t``
over the whole line, ``d`` of any length), two (n, 2K) arrays, ``t`` (entry,
exit, ...; sorted; ``inf`` where a ray has fewer spans) and ``face`` (the
triangle each crossing lies on), and ``normal(p, face)`` the outward normal.

The crossings come from Intel Embree's bounding volume hierarchy (the
``embreex`` binding): Embree gives a ray's first hit; the ray then starts
again just past it until it leaves the mesh, each pass for the rays still
going only. Embree works in single precision: the mesh is moved to its
centre first, and a crossing is known to about 1e-6 of the mesh's size,
which is what a picture needs (a mesh written to a file keeps the doubles).
Entries and exits are told apart by the side of the triangle the ray comes
from, and a ray's spans are where it is inside at least once (a hit on the
edge of two triangles counts once, the next pass starting past it).
"""

from __future__ import annotations

import numpy as np

INF = np.inf
FACE_BITS = 32  # as castor.pictures.trace numbers faces
FACE_MASK = (1 << FACE_BITS) - 1
# a ray passes through at most this many facets (a comb of thin teeth)
MAX_CROSSINGS = 256


class MeshRays:
    """A closed, outward-oriented triangle mesh, ready for rays."""

    def __init__(self, vertices: np.ndarray, triangles: np.ndarray, groups=None):
        from embreex import rtcore_scene
        from embreex.mesh_construction import TriangleMesh

        self.vertices = np.asarray(vertices, dtype=np.float64)
        self.triangles = np.asarray(triangles, dtype=np.int64).reshape(-1, 3)
        if len(self.triangles):
            self.low = self.vertices[self.triangles].reshape(-1, 3).min(axis=0)
            self.high = self.vertices[self.triangles].reshape(-1, 3).max(axis=0)
        else:
            self.low = self.high = np.zeros(3)
        self.centre = (self.low + self.high) / 2
        self.size = float(np.max(self.high - self.low)) if len(self.triangles) else 0.0
        p = self.vertices[self.triangles]
        self.normals = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
        # a crossing's face is its triangle, with its group (its colour) above
        # FACE_BITS: the ray tracer reads the group as one leaf of its own
        self.group_bits = (None if groups is None
                           else np.asarray(groups, dtype=np.int64) << FACE_BITS)
        # the surface each triangle lies on, for the edges of pictures: its own
        # until told (smooth_leaf names each one's smooth patch)
        self.surfaces = np.arange(len(self.triangles), dtype=np.int64)
        # the smooth surface each triangle lies on, for its normals (None:
        # each triangle its own plane); the normals at its corners, made once
        self.smooth_groups: np.ndarray | None = None
        self._corner_normals: np.ndarray | None = None
        self._scene = rtcore_scene.EmbreeScene(robust=True)  # watertight: no ray slips between two triangles
        if len(self.triangles):
            TriangleMesh(scene=self._scene,
                         vertices=(self.vertices - self.centre).astype(np.float32),
                         indices=self.triangles.astype(np.int32))

    def box(self) -> tuple[np.ndarray, np.ndarray]:
        return self.low.copy(), self.high.copy()

    def normal(self, points: np.ndarray, face: np.ndarray) -> np.ndarray:
        """The outward (unnormalised) normal at ``points`` on the triangles
        ``face``: the triangle's own, or, once ``smooth_groups`` says which
        triangles are facets of one smooth surface, the normals at its
        corners interpolated across it (Phong's normals: a smooth solid
        shaded as smooth as its limit surface, its creases and flat faces
        kept sharp)."""
        face = np.asarray(face, dtype=np.int64) & FACE_MASK
        if self.smooth_groups is None:
            return self.normals[face]
        if self._corner_normals is None:
            self._corner_normals = corner_normals(self.vertices, self.triangles, self.normals,
                                                  self.smooth_groups)
        p = self.vertices[self.triangles[face]]
        weights = _barycentric(np.asarray(points, dtype=np.float64), p)
        return np.einsum("ij,ijk->ik", weights, self._corner_normals[face])

    def crossings(self, origins: np.ndarray, directions: np.ndarray):
        """(t, triangle), each (n, K), sorted along each ray; t = inf past a ray's last.

        A closed mesh is crossed an even number of times; a ray that slips
        through a vertex in single precision is cast again, moved aside by
        1e-7 of the mesh's size (invisible in a picture)."""
        o = np.asarray(origins, dtype=np.float64)
        d = np.asarray(directions, dtype=np.float64)
        t, face = self._crossings(o, d)
        for attempt in range(1, 4):
            odd = np.flatnonzero(np.isfinite(t).sum(axis=1) % 2 == 1)
            if not len(odd):
                break
            aside = np.cross(d[odd], [0.6, 0.48, 0.64])
            aside /= np.maximum(np.linalg.norm(aside, axis=1), 1e-300)[:, None]
            again_t, again_face = self._crossings(o[odd] + attempt * 1e-7 * self.size * aside,
                                                  d[odd])
            width = max(t.shape[1], again_t.shape[1])
            t, face = _widened(t, width, INF), _widened(face, width, 0)
            t[odd] = _widened(again_t, width, INF)
            face[odd] = _widened(again_face, width, 0)
        return t, face

    def _crossings(self, o: np.ndarray, d: np.ndarray):
        n = len(o)
        if n == 0 or not len(self.triangles):
            return np.full((n, 0), INF), np.zeros((n, 0), np.int64)
        # start each ray just before it enters the mesh's box
        margin = 1e-3 * max(self.size, 1e-300)
        with np.errstate(divide="ignore", invalid="ignore"):
            inverse = 1.0 / d
            a = (self.low - margin - o) * inverse
            b = (self.high + margin - o) * inverse
        a = np.where(np.isnan(a), -INF, a)  # a ray parallel to a slab, inside it
        b = np.where(np.isnan(b), INF, b)
        enter = np.minimum(a, b).max(axis=1)
        leave = np.maximum(a, b).min(axis=1)
        going = np.flatnonzero(enter <= leave)
        start = enter.copy()
        length = np.linalg.norm(d, axis=1)
        # each pass starts this far past the last hit: 1e-6 of the mesh's size
        step = 1e-6 * max(self.size, 1e-300) / np.where(length > 0, length, 1.0)
        found_t: list[np.ndarray] = []
        found_face: list[np.ndarray] = []
        for _ in range(MAX_CROSSINGS):
            if not len(going):
                break
            at = (o[going] + start[going, None] * d[going]) - self.centre
            hit = self._scene.run(at.astype(np.float32), d[going].astype(np.float32),
                                  output=1)
            ok = hit["primID"] >= 0
            rows = going[ok]
            t = start[rows] + hit["tfar"][ok].astype(np.float64)
            column_t = np.full(n, INF)
            column_face = np.zeros(n, np.int64)
            column_t[rows] = t
            column_face[rows] = hit["primID"][ok]
            found_t.append(column_t)
            found_face.append(column_face)
            start[rows] = t + step[rows]
            going = rows
        if not found_t:
            return np.full((n, 0), INF), np.zeros((n, 0), np.int64)
        return np.column_stack(found_t), np.column_stack(found_face)

    def spans(self, origins: np.ndarray, directions: np.ndarray):
        """(t, face), each (n, 2K): where each ray is inside the mesh."""
        t, face = self.crossings(origins, directions)
        n = len(t)
        if t.shape[1] == 0:
            return np.full((n, 2), INF), np.zeros((n, 2), np.int64)
        d = np.asarray(directions, dtype=np.float64)
        real = np.isfinite(t)
        facing = np.einsum("ijk,ik->ij", self.normals[face], d)
        # +1 entering (against the normal), -1 leaving
        step = np.where(real, np.where(facing < 0, 1, -1), 0)
        depth = np.cumsum(step, axis=1)
        before = depth - step
        opens = real & (step > 0) & (before <= 0) & (depth > 0)
        closes = real & (step < 0) & (before > 0) & (depth <= 0)
        keep = opens | closes
        count = keep.sum(axis=1)
        width = max(2, int(count.max()) + int(count.max()) % 2)
        t, face = _widened(t, width, INF), _widened(face, width, 0)
        keep, opens = _widened(keep, width, False), _widened(opens, width, False)
        order = np.argsort(~keep, axis=1, kind="stable")[:, :width]
        kept_t = np.take_along_axis(np.where(keep, t, INF), order, axis=1)
        kept_face = np.take_along_axis(face, order, axis=1)
        kept_open = np.take_along_axis(opens, order, axis=1)
        # a ray whose crossings do not pair up (a miss on an edge) keeps the
        # spans that do: an entry never followed by an exit is dropped
        pairs = kept_open[:, 0::2] & np.isfinite(kept_t[:, 1::2])
        kept_t[:, 0::2] = np.where(pairs, kept_t[:, 0::2], INF)
        kept_t[:, 1::2] = np.where(pairs, kept_t[:, 1::2], INF)
        if self.group_bits is not None:
            kept_face = kept_face | self.group_bits[kept_face]
        return kept_t, kept_face


def corner_normals(vertices, triangles, normals, groups) -> np.ndarray:
    """(T, 3, 3) unit normals at each triangle's corners: at a vertex, the
    mean of the normals (weighted by area) of the triangles around it of the
    same ``groups`` number; a vertex on a crease, or on the edge of a flat
    face, has one normal for each side."""
    n = len(vertices)
    key = np.asarray(groups, dtype=np.int64)[:, None] * n + triangles
    unique, slot = np.unique(key.ravel(), return_inverse=True)
    total = np.zeros((len(unique), 3))
    for axis in range(3):
        total[:, axis] = np.bincount(slot, weights=np.repeat(normals[:, axis], 3),
                                     minlength=len(unique))
    total /= np.maximum(np.linalg.norm(total, axis=1), 1e-300)[:, None]
    return total[slot].reshape(-1, 3, 3)


def _barycentric(points: np.ndarray, corners: np.ndarray) -> np.ndarray:
    """(n, 3) weights of the corners (n, 3, 3) of triangles for points on (or
    next to) them, clipped into the triangle."""
    v0, v1 = corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]
    v2 = points - corners[:, 0]
    d00, d01, d11 = (np.einsum("ij,ij->i", a, b) for a, b in ((v0, v0), (v0, v1), (v1, v1)))
    d20, d21 = np.einsum("ij,ij->i", v2, v0), np.einsum("ij,ij->i", v2, v1)
    denominator = d00 * d11 - d01 * d01
    denominator = np.where(np.abs(denominator) > 0, denominator, 1.0)
    v = (d11 * d20 - d01 * d21) / denominator
    w = (d00 * d21 - d01 * d20) / denominator
    weights = np.clip(np.column_stack([1 - v - w, v, w]), 0, None)
    total = weights.sum(axis=1, keepdims=True)
    return np.where(total > 0, weights / np.where(total > 0, total, 1), 1 / 3)


_FACETIZER = []


def smooth_leaf(node, matrix: np.ndarray, leaves: list, make_leaf):
    """The ray tracer's leaf for a smooth solid (a ``tree.Smooth`` placed by
    the 4x4 ``matrix``): its refined facets, made by the facetizer (once per
    key), as ``MeshRays``; one leaf number for each colour of its faces, the
    first traced, the others naming the colour of a crossing."""
    from castor.mesh import provenance
    from castor.mesh.facetize import Facetizer

    if abs(np.linalg.det(matrix[:3, :3])) < 1e-300:
        return None
    if not _FACETIZER:
        _FACETIZER.append(Facetizer())
    solid = _FACETIZER[0].solid(node)  # in the space above the node
    if solid.empty:
        return None
    tri = provenance.triangles(solid.parts, solid.origins)
    colours = np.array([solid.origins[int(i)].colour for i in range(len(solid.origins))])
    table, group = np.unique(colours[tri.origin_ids], axis=0, return_inverse=True)
    rays = MeshRays(tri.vertices, tri.triangles, group.ravel())
    rays.surfaces = _surfaces(solid.origins, tri.origin_ids, tri.face_ids)
    rays.smooth_groups = _smooth_groups(solid.origins, tri.origin_ids, tri.face_ids)
    inverse = np.linalg.inv(matrix)[:3, :]
    low, high = rays.box()
    corners = np.array([[x, y, z, 1.0] for x in (low[0], high[0]) for y in (low[1], high[1])
                        for z in (low[2], high[2])])
    placed = corners @ matrix[:3, :].T
    pad = 1e-9 * (1 + np.abs(placed).max())
    first = None
    for colour in table:
        leaf = make_leaf(len(leaves), "smooth", rays, tuple(float(c) for c in colour), inverse,
                         placed.min(axis=0) - pad, placed.max(axis=0) + pad)
        leaves.append(leaf)
        first = first or leaf
    return first


def _patches(origins, origin_ids: np.ndarray, face_ids: np.ndarray):
    """For each triangle of a smooth solid, its face number and its smooth
    patch (castor.mesh.smooth), -1 on a flat control face."""
    face = face_ids & 0xFFFFFFFF
    patch = np.full(len(face), -1, np.int64)
    for entry in np.unique(origin_ids):
        rows = origin_ids == entry
        surfaces = origins[int(entry)].surfaces
        if surfaces is not None:
            table = surfaces.of_face
            known = face[rows] < len(table)
            patch[rows] = np.where(known, table[np.minimum(face[rows], len(table) - 1)], -1)
    return face, patch


def _smooth_groups(origins, origin_ids: np.ndarray, face_ids: np.ndarray) -> np.ndarray:
    """For each triangle of a smooth solid, the surface its normals are
    shared on: its smooth patch, whatever the origin (a smoothed union is
    smooth across the seam of its colours), or its flat face."""
    face, patch = _patches(origins, origin_ids, face_ids)
    return np.where(patch < 0, -1 - face, patch)


def _surfaces(origins, origin_ids: np.ndarray, face_ids: np.ndarray) -> np.ndarray:
    """For each triangle of a smooth solid, a number for the surface it lies on
    (castor.mesh.smooth): its smooth patch, or its flat control face, of its
    origin; numbered from 0, equal only within one surface."""
    face, patch = _patches(origins, origin_ids, face_ids)
    flat = patch < 0
    surface = np.where(flat, face, patch)
    _, number = np.unique(np.column_stack([origin_ids, flat, surface]), axis=0,
                          return_inverse=True)
    return number.ravel().astype(np.int64)


def _widened(a: np.ndarray, width: int, fill) -> np.ndarray:
    """``a`` with columns of ``fill`` added up to ``width``."""
    if a.shape[1] >= width:
        return a
    return np.concatenate([a, np.full((len(a), width - a.shape[1]), fill, a.dtype)], axis=1)

"""Solids taken apart and put elsewhere, for the take-off (castor.quantities)
and the base quantities (measures): the section of a solid at a height, its
separate shells, the smallest rectangle around its plan, and a solid made
once moved to each copy of its shared subtree (``Copy``).
"""

from __future__ import annotations

import numpy as np

from castor.mesh.arrays import components
from castor.mesh.frame import FrameObject


def section_area(obj: FrameObject, z: float) -> float:
    """The area of the object's section by the plane at height ``z``: each
    polygon crossing it gives a segment, oriented by its outward normal so that
    the shoelace sum of the segments is the area inside (no loop over them)."""
    from castor.mesh.arrays import fan_triangles

    if obj.polygon_count == 0:
        return 0.0
    tris, _ = fan_triangles(obj.offsets, obj.indices)
    corners = obj.vertices[tris]  # (T, 3, 3)
    above = corners[:, :, 2] > z
    crossing = above.any(axis=1) & ~above.all(axis=1)
    corners = corners[crossing]
    above = above[crossing]
    if len(corners) == 0:
        return 0.0
    points = []
    for i, j in ((0, 1), (1, 2), (2, 0)):
        a, b = corners[:, i], corners[:, j]
        cut = above[:, i] != above[:, j]
        t = np.where(cut, (z - a[:, 2]) / np.where(cut, b[:, 2] - a[:, 2], 1.0), 0.0)
        points.append((a + (b - a) * t[:, None], cut))
    # two of the three sides are cut: the segment's ends
    ends = np.stack([p for p, _ in points], axis=1)  # (T, 3, 3)
    cuts = np.stack([c for _, c in points], axis=1)  # (T, 3)
    order = np.argsort(~cuts, axis=1, kind="stable")[:, :2]
    p = np.take_along_axis(ends, order[:, 0, None, None].repeat(3, axis=2), axis=1)[:, 0]
    q = np.take_along_axis(ends, order[:, 1, None, None].repeat(3, axis=2), axis=1)[:, 0]
    normal = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    # the inside is on the left going along z x normal
    along = np.stack([-normal[:, 1], normal[:, 0]], axis=1)
    flip = ((q - p)[:, :2] * along).sum(axis=1) < 0
    p, q = np.where(flip[:, None], q, p), np.where(flip[:, None], p, q)
    return float((p[:, 0] * q[:, 1] - p[:, 1] * q[:, 0]).sum() / 2)


def shells(obj: FrameObject) -> list[FrameObject]:
    """The object's separate closed surfaces, each an object of its own."""
    if obj.polygon_count == 0:
        return []
    following = np.arange(1, len(obj.indices) + 1)
    following[obj.offsets[1:] - 1] = obj.offsets[:-1]
    label = components(len(obj.vertices), obj.indices, obj.indices[following])
    of_polygon = label[obj.indices[obj.offsets[:-1]]]
    pieces = []
    for value in np.unique(of_polygon):
        chosen = np.flatnonzero(of_polygon == value)
        lengths = np.diff(obj.offsets)[chosen]
        starts = obj.offsets[:-1][chosen]
        take = np.concatenate([np.arange(s, s + n) for s, n in zip(starts, lengths)])
        used, indices = np.unique(obj.indices[take], return_inverse=True)
        offsets = np.concatenate([[0], np.cumsum(lengths)])
        pieces.append(FrameObject(obj.vertices[used], offsets, indices.reshape(-1),
                                  obj.origin_of[chosen], obj.origins, obj.name))
    return pieces


def footprint(vertices: np.ndarray) -> tuple[float, float, tuple[float, float]]:
    """The smallest rectangle around the vertices seen from above: its long
    side, its short side and the long side's direction. A block cut in a wall
    at any angle has the wall's length along the long side and its thickness
    across it."""
    points = np.unique(np.round(vertices[:, :2], 9), axis=0)
    if len(points) < 3:
        span = points.max(axis=0) - points.min(axis=0) if len(points) else np.zeros(2)
        return float(max(span)), float(min(span)), (1.0, 0.0)
    hull = _hull(points)
    edges = np.roll(hull, -1, axis=0) - hull
    lengths = np.linalg.norm(edges, axis=1)
    keep = lengths > 1e-12
    along = edges[keep] / lengths[keep, None]
    across = np.stack([-along[:, 1], along[:, 0]], axis=1)
    u = hull @ along.T  # (points, directions)
    v = hull @ across.T
    a, b = u.max(axis=0) - u.min(axis=0), v.max(axis=0) - v.min(axis=0)
    best = int(np.argmin(a * b))
    # prefer the axes when they are as good (a box in a wall along x or y)
    spans = hull.max(axis=0) - hull.min(axis=0)
    if spans.prod() <= a[best] * b[best] * (1 + 1e-9):
        return (float(spans.max()), float(spans.min()),
                (1.0, 0.0) if spans[0] >= spans[1] else (0.0, 1.0))
    if a[best] >= b[best]:
        return float(a[best]), float(b[best]), tuple(map(float, along[best]))
    return float(b[best]), float(a[best]), tuple(map(float, across[best]))


def _hull(points: np.ndarray) -> np.ndarray:
    """The convex hull of a few points in the plane, counter-clockwise
    (Andrew's monotone chain; ``points`` sorted and distinct)."""
    def half(seq):
        chain: list = []
        for p in seq:
            while len(chain) >= 2 and _turn(chain[-2], chain[-1], p) <= 0:
                chain.pop()
            chain.append(p)
        return chain[:-1]

    return np.array(half(points) + half(points[::-1]))


def _turn(a, b, c) -> float:
    return float((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))


EMPTY = FrameObject(np.zeros((0, 3)), np.zeros(1, np.int64), np.zeros(0, np.int64),
                     np.zeros(0, np.int64), [])


def chain(node) -> list:
    """The uses from ``node`` down to the first node that is not a use (a shared
    subtree moved by each): empty when ``node`` is not a use."""
    from castor.csg import tree

    chain = []
    while type(node) is tree.Use and node.shared.child is not None:
        chain.append(node)
        node = node.shared.child
    return chain


class Copy:
    """A solid that is its unit's (the innermost use of ``chain``, made once at
    the identity) moved by the chain's matrices, its paths under the chain's
    names as the facetizer puts them (castor.mesh.facetize: each use puts its
    shared subtree's name, then its own path, in front)."""

    __slots__ = ("unit", "matrix", "prefixes", "rigid", "translation")

    def __init__(self, unit: str, chain: list):
        from castor.csg import tree

        self.unit = unit
        matrix = tree.IDENTITY
        for use in chain:
            matrix = tree.compose(matrix, use.matrix)
        self.matrix = np.array(matrix, dtype=np.float64).reshape(3, 4)
        prefixes = [chain[-1].path] if chain[-1].path else []
        for use in reversed(chain[:-1]):
            prefixes.append(f"({use.shared.name})")
            if use.path:
                prefixes.append(use.path)
        self.prefixes = prefixes
        linear = self.matrix[:, :3]
        # rotations and translations keep volumes, areas, colours and shells;
        # a mirror or a scale does not keep them all: measured again
        self.rigid = bool(np.abs(linear.T @ linear - np.eye(3)).max() <= 1e-12
                          and np.linalg.det(linear) > 0)
        self.translation = bool((linear == np.eye(3)).all())

    def moved(self, solid: FrameObject) -> FrameObject:
        """``solid`` moved and renamed; a mirror turns each polygon round, so
        that it stays counter-clockwise seen from outside."""
        from dataclasses import replace

        if solid.polygon_count == 0:
            return solid
        linear, shift = self.matrix[:, :3], self.matrix[:, 3]
        vertices = solid.vertices @ linear.T + shift
        indices = solid.indices
        if np.linalg.det(linear) < 0:
            sizes = np.diff(solid.offsets)
            starts = np.repeat(solid.offsets[:-1], sizes)
            local = np.arange(len(indices)) - starts
            indices = indices[starts + np.repeat(sizes, sizes) - 1 - local]
        origins = solid.origins
        for prefix in self.prefixes:
            origins = [o._replace(steps=o.steps.under(prefix)) for o in origins]
        return replace(solid, vertices=vertices, indices=indices, origins=origins)

"""The exact solids of a frame as snapping reads them: which points are
inside, which planes bound each primitive, where a face of the evaluated
solid lies.

``Solids`` wraps the ray tracer's compiled frame (castor.pictures.trace):
``inside`` classifies points against the CSG tree, a node's operands asked
only about the points inside its box, each primitive by its own exact spans
(castor.primitives) along a line through the point; ``carries`` says where a
plane holds a face of the evaluated solid (the solid on one side of it and
not on the other), which is how a corner that no primitive has (a wall's top
meeting the roof) is told from a seam inside a union. ``planes`` are the flat
faces each primitive declares (the faces its mesh marks flat), placed in the
scene, with each face's centre.
"""

from __future__ import annotations

import numpy as np

from castor.pictures.spans import SPANS
from castor.pictures.trace import TracedBoolean, TracedLeaf, TracedTree

# a direction along which no face of an architect's scene lies: the lines
# that classify points go this way
_SLANT = np.array([0.5377, 0.6742, 0.5062]) / np.linalg.norm([0.5377, 0.6742, 0.5062])
_UNIT_TOLERANCE = 0.02  # facets of a unit primitive's flat faces: only their planes matter


class Planes:
    """The flat faces of one primitive in the scene: unit outward normals,
    offsets (n . x = offset on the face) and centres, one row per face."""

    __slots__ = ("normals", "offsets", "centres")

    def __init__(self, normals: np.ndarray, offsets: np.ndarray, centres: np.ndarray):
        self.normals = normals
        self.offsets = offsets
        self.centres = centres


_unit_planes: dict[tuple, tuple] = {}


def unit_planes(kind: str, shape: tuple) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The flat faces of a unit primitive, from its declared mesh: normals,
    offsets and centres (area-weighted centroids)."""
    key = (kind, shape)
    if key in _unit_planes:
        return _unit_planes[key]
    from castor.primitives import FLAT, PRIMITIVES

    declared = PRIMITIVES[kind]
    counts = declared.facet_counts(shape, (1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0),
                                   _UNIT_TOLERANCE)
    mesh = declared.mesh(shape, counts)
    vertices = np.asarray(mesh.vertices, np.float64)
    triangles = np.asarray(mesh.triangles)
    faces = np.asarray(mesh.faces)
    surfaces = np.asarray(mesh.surfaces)
    a, b, c = (vertices[triangles[:, k]] for k in range(3))
    cross = np.cross(b - a, c - a)
    areas = np.linalg.norm(cross, axis=1)
    middles = (a + b + c) / 3
    normals, offsets, centres = [], [], []
    for face in np.flatnonzero(surfaces == FLAT):
        rows = faces == face
        total = areas[rows].sum()
        if total <= 0:
            continue
        n = cross[rows].sum(axis=0)
        n /= np.linalg.norm(n)
        centre = (middles[rows] * areas[rows, None]).sum(axis=0) / total
        normals.append(n)
        offsets.append(float(n @ centre))
        centres.append(centre)
    found = (np.array(normals).reshape(-1, 3), np.array(offsets), np.array(centres).reshape(-1, 3))
    _unit_planes[key] = found
    return found


class Solids:
    """A compiled frame, asked about points and planes."""

    def __init__(self, traced: TracedTree):
        self.traced = traced
        leaves = traced.leaves
        self.lows = np.array([leaf.low for leaf in leaves]).reshape(-1, 3)
        self.highs = np.array([leaf.high for leaf in leaves]).reshape(-1, 3)
        low, high = traced.box
        self.size = max(float(np.linalg.norm(high - low)), 1.0)
        # how far from a point its neighbours are sampled, along a face and across it
        self.step = 2e-6 * self.size
        self.across = self.step / 20
        self._planes: dict[int, Planes] = {}
        self._region = None  # (low, high, the tree cut to that box): around()

    # --- points

    def inside(self, points: np.ndarray) -> np.ndarray:
        """Whether each point is inside the frame's solids (a point on a face
        may go either way: ask about points off the faces)."""
        points = np.asarray(points, np.float64).reshape(-1, 3)
        if self.traced.root is None or len(points) == 0:
            return np.zeros(len(points), bool)
        if self._region is None:
            return _inside(self.traced.root, points, np.arange(len(points)))
        low, high, root = self._region
        result = np.zeros(len(points), bool)
        near = np.all((low <= points) & (points <= high), axis=1)
        rows = np.flatnonzero(near)
        if len(rows) and root is not None:
            result[rows] = _inside(root, points, rows)
        rows = np.flatnonzero(~near)
        if len(rows):
            result[rows] = _inside(self.traced.root, points, rows)
        return result

    def around(self, point: np.ndarray, radius: float) -> "Solids":
        """The same solids, asked about points near ``point`` through a tree
        cut down to the nodes whose boxes come within ``radius`` of it."""
        local = Solids.__new__(Solids)
        local.__dict__.update(self.__dict__)
        low, high = point - radius, point + radius
        local._region = (low, high, None if self.traced.root is None
                         else _pruned(self.traced.root, low, high))
        return local

    def carries(self, normals: np.ndarray, points: np.ndarray) -> np.ndarray:
        """Whether a face of the solid lies on each plane (its unit normal) at each
        point of it: the solid on one side and not on the other."""
        offset = normals * self.across
        both = self.inside(np.concatenate([points - offset, points + offset]))
        return both[:len(points)] != both[len(points):]

    # --- primitives

    def near(self, point: np.ndarray, radius: float) -> np.ndarray:
        """The leaves whose boxes come within ``radius`` of ``point``."""
        if len(self.lows) == 0:
            return np.zeros(0, np.int64)
        ok = np.all((self.lows - radius <= point) & (point <= self.highs + radius), axis=1)
        return np.flatnonzero(ok)

    def along(self, start: np.ndarray, direction: np.ndarray) -> np.ndarray:
        """The leaves whose boxes the line through ``start`` along ``direction`` crosses."""
        if len(self.lows) == 0:
            return np.zeros(0, np.int64)
        with np.errstate(divide="ignore", invalid="ignore"):
            inverse = 1.0 / direction
            t0 = (self.lows - start) * inverse
            t1 = (self.highs - start) * inverse
        flat = direction == 0
        low = np.where(flat, np.where((self.lows <= start) & (start <= self.highs), -np.inf,
                                      np.inf), np.fmin(t0, t1))
        high = np.where(flat, np.where((self.lows <= start) & (start <= self.highs), np.inf,
                                       -np.inf), np.fmax(t0, t1))
        return np.flatnonzero(low.max(axis=1) <= high.min(axis=1))

    def planes(self, number: int) -> Planes:
        """The flat faces of leaf ``number``, placed in the scene."""
        found = self._planes.get(number)
        if found is None:
            leaf = self.traced.leaves[number]
            if leaf.kind == "smooth":  # traced through facets: no exact plane of its own
                found = Planes(np.zeros((0, 3)), np.zeros(0), np.zeros((0, 3)))
            else:
                normals, offsets, centres = unit_planes(leaf.kind, leaf.shape)
                linear, shift = leaf.inverse[:, :3], leaf.inverse[:, 3]
                placed = normals @ linear  # the inverse transpose carries normals
                length = np.linalg.norm(placed, axis=1)
                forward = np.linalg.inv(np.vstack([leaf.inverse, [0.0, 0.0, 0.0, 1.0]]))[:3]
                found = Planes(placed / length[:, None],
                               (offsets - normals @ shift) / length,
                               centres @ forward[:, :3].T + forward[:, 3])
            self._planes[number] = found
        return found

    def gathered(self, numbers) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """The planes of several leaves: normals, offsets, centres and leaf numbers."""
        parts = [(self.planes(int(k)), int(k)) for k in numbers]
        if not parts:
            return np.zeros((0, 3)), np.zeros(0), np.zeros((0, 3)), np.zeros(0, np.int64)
        return (np.concatenate([p.normals for p, _ in parts]),
                np.concatenate([p.offsets for p, _ in parts]),
                np.concatenate([p.centres for p, _ in parts]),
                np.concatenate([np.full(len(p.offsets), k) for p, k in parts]))


def distinct(normals: np.ndarray, offsets: np.ndarray, scale: float) -> np.ndarray:
    """The rows of the first of each set of planes that coincide (either way round)."""
    if len(offsets) == 0:
        return np.zeros(0, np.int64)
    first = np.argmax(np.abs(normals) > 1e-9, axis=1)
    sign = np.sign(normals[np.arange(len(normals)), first])
    keys = np.column_stack([normals * sign[:, None], offsets * sign / scale])
    rounded = np.round(keys * 1e8)
    _, rows = np.unique(rounded, axis=0, return_index=True)
    return np.sort(rows)


def edge_along(solids: Solids, points: np.ndarray, plane, u: np.ndarray) -> np.ndarray:
    """Whether the solid has an edge along ``u`` (one direction, or one for each
    point) at each point of a line in ``plane`` (its normal first: one, or one
    for each point): the plane carries a face on one side of the line only."""
    n = plane[0]
    w = np.cross(n, u)
    step, across = solids.step, solids.across
    probes = np.concatenate([points + w * step + n * across, points + w * step - n * across,
                             points - w * step + n * across, points - w * step - n * across])
    inside = solids.inside(probes).reshape(4, -1)
    left = inside[0] != inside[1]  # a face on the plane on this side of the line
    right = inside[2] != inside[3]
    return left != right


def edge_middle(solids: Solids, plane, line) -> np.ndarray | None:
    """The middle of the edge along ``line`` (its point near the ray, its
    direction): its ends are where the planes of the primitives along it cut
    it and the edge stops."""
    start, u = line
    crossing = solids.along(start, u)
    normals, offsets, _, _ = solids.gathered(crossing)
    with np.errstate(divide="ignore", invalid="ignore"):
        s = (offsets - normals @ start) / (normals @ u)
    low, high = solids.traced.box
    extent = float(np.abs(np.concatenate([low - start, high - start])).max()) * 2 + 1
    s = np.unique(np.concatenate([s[np.isfinite(s) & (np.abs(s) <= extent)], [-extent, extent]]))
    if len(s) < 2:
        return None
    middles = (s[:-1] + s[1:]) / 2
    ok = edge_along(solids, start + middles[:, None] * u, plane, u)
    here = int(np.searchsorted(s, 0.0, side="right")) - 1
    here = min(max(here, 0), len(ok) - 1)
    if not ok[here]:
        return None
    first = last = here
    while first > 0 and ok[first - 1]:
        first -= 1
    while last < len(ok) - 1 and ok[last + 1]:
        last += 1
    if first == 0 or last == len(ok) - 1:
        return None  # runs out of the scene: no end
    return start + (s[first] + s[last + 1]) / 2 * u


def is_corner(solids: Solids, point: np.ndarray, normals, offsets) -> bool:
    """Whether faces of the solid on three planes through ``point``, whose
    normals span space, meet there."""
    through = np.flatnonzero(np.abs(normals @ point - offsets) < 1e-8 * solids.size)
    if len(through) < 3:
        return False
    angles = np.linspace(0, 2 * np.pi, 12, endpoint=False)
    rows, probes, probe_normals = [], [], []
    for k in through:
        n = normals[k]
        u = np.cross(n, [1.0, 0.0, 0.0] if abs(n[0]) < 0.9 else [0.0, 1.0, 0.0])
        u /= np.linalg.norm(u)
        v = np.cross(n, u)
        ring = point + solids.step * (np.cos(angles)[:, None] * u + np.sin(angles)[:, None] * v)
        probes.append(ring)
        probe_normals.append(np.broadcast_to(n, ring.shape))
        rows.append(np.full(len(ring), k))
    carried = solids.carries(np.concatenate(probe_normals), np.concatenate(probes))
    rows = np.concatenate(rows)
    carrying = np.unique(rows[carried])
    if len(carrying) < 3:
        return False
    return np.linalg.matrix_rank(normals[carrying], tol=1e-6) == 3


def _pruned(node, low: np.ndarray, high: np.ndarray):
    """The part of a compiled tree that decides about the points of the box
    (low, high): nodes whose boxes miss it are empty there."""
    if np.any(node.high < low) or np.any(node.low > high):
        return None
    if isinstance(node, TracedLeaf):
        return node
    operands = [_pruned(o, low, high) for o in node.operands]
    if node.op == "I":
        if any(o is None for o in operands):
            return None
    elif node.op == "D":
        if operands[0] is None:
            return None
        if operands[1] is None:
            return operands[0]
    else:
        operands = [o for o in operands if o is not None]
        if len(operands) <= 1:
            return operands[0] if operands else None
    return TracedBoolean(node.op, operands, node.low, node.high)


def _inside(node, points: np.ndarray, rows: np.ndarray) -> np.ndarray:
    p = points[rows]
    result = np.zeros(len(rows), bool)
    within = np.flatnonzero(np.all((node.low <= p) & (p <= node.high), axis=1))
    if len(within) == 0:
        return result
    rows = rows[within]
    if isinstance(node, TracedLeaf):
        local = points[rows] @ node.inverse[:, :3].T + node.inverse[:, 3]
        direction = np.broadcast_to(node.inverse[:, :3] @ _SLANT, local.shape)
        t, _ = SPANS[node.kind].spans(node.shape, local, np.ascontiguousarray(direction))
        if t.shape[1]:
            result[within] = np.any((t[:, 0::2] < 0) & (t[:, 1::2] > 0), axis=1)
        return result
    assert isinstance(node, TracedBoolean)
    if node.op == "U":
        found = np.zeros(len(rows), bool)
        for operand in node.operands:
            rest = np.flatnonzero(~found)
            if len(rest) == 0:
                break
            found[rest] = _inside(operand, points, rows[rest])
    elif node.op == "I":
        found = np.ones(len(rows), bool)
        for operand in node.operands:
            rest = np.flatnonzero(found)
            if len(rest) == 0:
                break
            found[rest] = _inside(operand, points, rows[rest])
    else:
        found = _inside(node.operands[0], points, rows)
        rest = np.flatnonzero(found)
        if len(rest):
            found[rest] = ~_inside(node.operands[1], points, rows[rest])
    result[within] = found
    return result

"""Rays against the evaluated CSG tree of a frame: the booleans taken on spans.

``compile_frame`` compiles a ``castor.csg.tree.FrameTree`` once into a
``TracedTree`` of ``TracedLeaf`` and ``TracedBoolean`` nodes: every primitive with the
inverse of its matrix to the scene (shared subtrees expanded for each use),
every node with its bounding box in the scene. ``spans`` gives, for a batch of
rays, the spans where each ray is inside the frame's solids: a primitive's
spans come from ``castor.pictures.spans`` in its own space; a boolean merges
its operands' entries and exits sorted along the ray and keeps the stretches
where its operator holds. A node is evaluated only for the rays that cross its
box, and a difference's cutters only for the rays inside its first operand.
Each crossing carries the primitive and face it lies on, so a cut face shows
the cutter's colour, as in the meshes.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from castor.csg import tree
from castor.csg.paths import join
from castor.pictures.mesh_rays import smooth_leaf
from castor.pictures.spans import SPANS

INF = np.inf
FACE_BITS = 32  # a crossing's face: (primitive number << FACE_BITS) | face of the primitive
FACE_MASK = (1 << FACE_BITS) - 1


@dataclass
class TracedLeaf:
    number: int
    kind: str
    shape: tuple
    colour: tuple
    inverse: np.ndarray  # (3, 4): scene point -> the primitive's own space
    low: np.ndarray
    high: np.ndarray
    # where it comes from, for tools that name what a ray met (castor.editing):
    # the tree's Primitive (or Smooth) and the path of the shared subtrees above it
    # (as a chain: above_text writes it)
    origin: tuple = ()


@dataclass
class TracedBoolean:
    op: str  # "U", "I" or "D"
    operands: list
    low: np.ndarray
    high: np.ndarray


@dataclass
class TracedTree:
    root: object  # TracedLeaf, TracedBoolean or None (nothing to draw)
    leaves: list = field(default_factory=list)

    @property
    def box(self) -> tuple[np.ndarray, np.ndarray]:
        if self.root is None:
            return np.zeros(3), np.zeros(3)
        return self.root.low, self.root.high

    def spans(self, origins: np.ndarray, directions: np.ndarray, near: float = 0.0,
              projection: "Projection | None" = None):
        """(t, face), each (n, 2K): the spans of the rays inside the solids
        (t = inf beyond a ray's last span), from ``near`` on along each ray.
        ``projection``, which the rays must share (a point they start from, or
        their direction), lets boxes be tested in two dimensions."""
        n = len(origins)
        if self.root is None or n == 0:
            return np.full((n, 0), INF), np.zeros((n, 0), np.int64)
        rays = self._rays(origins, directions, near, projection)
        return _evaluate(self.root, rays, np.arange(n))

    @staticmethod
    def _rays(origins, directions, near, projection) -> "_Rays":
        if projection is None:
            with np.errstate(divide="ignore"):
                inverse = 1.0 / directions
            return _Rays(origins, directions, inverse, near, None, None, None)
        u, v = projection.coordinates(origins, directions)
        return _Rays(origins, directions, None, near, projection, u, v)

    def first_hit(self, origins, directions, near: float = 0.0, projection=None):
        """The distance to the first surface along each ray (inf: none) and its face."""
        n = len(origins)
        if self.root is None or n == 0:
            return np.full(n, INF), np.zeros(n, np.int64)
        return _first(self.root, self._rays(origins, directions, near, projection),
                      np.arange(n))

    def blocked(self, origins, directions, near: float, projection=None) -> np.ndarray:
        """Whether each ray meets a solid beyond ``near`` (a shadow ray)."""
        n = len(origins)
        if self.root is None or n == 0:
            return np.zeros(n, bool)
        return _blocked(self.root, self._rays(origins, directions, near, projection),
                        np.arange(n))

    def normals(self, points: np.ndarray, faces: np.ndarray) -> np.ndarray:
        """Unit normals of the surfaces at the points (on the faces given), in the scene."""
        normals = np.zeros_like(points)
        numbers = faces >> FACE_BITS
        order = np.argsort(numbers, kind="stable")
        sorted_numbers = numbers[order]
        bounds = np.flatnonzero(np.diff(sorted_numbers)) + 1
        for rows in np.split(order, bounds):
            if len(rows) == 0:
                continue
            leaf = self.leaves[int(numbers[rows[0]])]
            linear = leaf.inverse[:, :3]
            local = points[rows] @ linear.T + leaf.inverse[:, 3]
            n = SPANS[leaf.kind].normal(leaf.shape, local, faces[rows] & FACE_MASK)
            normals[rows] = n @ linear  # the inverse transpose carries normals
        length = np.linalg.norm(normals, axis=1, keepdims=True)
        return np.divide(normals, length, out=np.zeros_like(normals), where=length > 0)

    def colours(self, faces: np.ndarray) -> np.ndarray:
        table = np.array([leaf.colour for leaf in self.leaves] or [(0.0, 0.0, 0.0)])
        return table[faces >> FACE_BITS]

    def surface_keys(self, faces: np.ndarray) -> np.ndarray:
        """For the edges of a picture, the surface each face lies on: the face
        itself, but for the facets of a smooth solid, which name their smooth
        patch (castor.pictures.mesh_rays: one curved surface, no lines inside)."""
        smooth = [leaf.number for leaf in self.leaves if leaf.kind == "smooth"]
        if not smooth or not len(faces):
            return faces
        keys = faces.copy()
        numbers = faces >> FACE_BITS
        for number in smooth:
            rows = numbers == number
            if rows.any():
                surfaces = self.leaves[number].shape.surfaces
                keys[rows] = (number << FACE_BITS) | surfaces[faces[rows] & FACE_MASK]
        return keys


@dataclass
class _Rays:
    origins: np.ndarray
    directions: np.ndarray
    inverse: np.ndarray | None
    near: float
    projection: "Projection | None"
    u: np.ndarray | None
    v: np.ndarray | None


class Projection:
    """Rays from one point (``eye``) or along one direction, with coordinates
    on a plane across them, so that whether a ray can cross a box is four
    comparisons against the box's projected rectangle (kept per node)."""

    def __init__(self, eye, direction, right=None, up=None):
        self.eye = None if eye is None else np.asarray(eye, dtype=np.float64)
        d = np.asarray(direction, dtype=np.float64)
        d = d / np.linalg.norm(d)
        if right is None:
            helper = np.array([1.0, 0.0, 0.0]) if abs(d[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
            right = np.cross(d, helper)
            right /= np.linalg.norm(right)
            up = np.cross(right, d)
        self.forward, self.right, self.up = d, np.asarray(right), np.asarray(up)
        self.rects: dict[int, tuple] = {}

    def coordinates(self, origins, directions):
        if self.eye is None:
            return origins @ self.right, origins @ self.up
        z = directions @ self.forward
        return (directions @ self.right) / z, (directions @ self.up) / z

    def rect(self, node) -> tuple:
        rect = self.rects.get(id(node))
        if rect is None:
            corners = np.array([[x, y, z] for x in (node.low[0], node.high[0])
                                for y in (node.low[1], node.high[1])
                                for z in (node.low[2], node.high[2])])
            if self.eye is None:
                u, v = corners @ self.right, corners @ self.up
            else:
                rel = corners - self.eye
                z = rel @ self.forward
                if np.any(z <= 1e-9 * (1 + np.abs(rel).max())):
                    rect = (-INF, INF, -INF, INF)  # the box reaches behind the eye
                    self.rects[id(node)] = rect
                    return rect
                u, v = (rel @ self.right) / z, (rel @ self.up) / z
            pad = 1e-9 * (1 + max(np.abs(u).max(), np.abs(v).max()))
            rect = (u.min() - pad, u.max() + pad, v.min() - pad, v.max() + pad)
            self.rects[id(node)] = rect
        return rect


def compile_frame(frame_tree: tree.FrameTree) -> TracedTree:
    """The frame's objects as one scene of primitives placed in the scene."""
    traced = TracedTree(None)
    roots = []
    for obj in frame_tree.objects:
        if obj.root is not None:
            node = _compile(obj.root, np.eye(4), traced.leaves, "")
            if node is not None:
                roots.append(node)
    traced.root = _grouped(_make("U", roots))
    return traced


GROUP = 4  # operands of a union beyond which they are grouped by place


def _grouped(node):
    """The tree with each large union split into nested unions of nearby
    operands (a bounding volume hierarchy), so that a ray meets the boxes of
    a few groups rather than of every operand."""
    if not isinstance(node, TracedBoolean):
        return node
    operands = [_grouped(o) for o in node.operands]
    if node.op != "U" or len(operands) <= GROUP:
        return TracedBoolean(node.op, operands, node.low, node.high)
    return _group(operands)


def _group(operands: list):
    if len(operands) == 1:
        return operands[0]
    lows = np.array([o.low for o in operands])
    highs = np.array([o.high for o in operands])
    low, high = lows.min(axis=0), highs.max(axis=0)
    if len(operands) <= GROUP:
        return TracedBoolean("U", operands, low, high)
    centres = (lows + highs) / 2
    axis = int(np.argmax(centres.max(axis=0) - centres.min(axis=0)))
    order = np.argsort(centres[:, axis], kind="stable")
    half = len(operands) // 2
    return TracedBoolean("U", [_group([operands[i] for i in order[:half]]),
                      _group([operands[i] for i in order[half:]])], low, high)


def _matrix(values) -> np.ndarray:
    m = np.eye(4)
    m[:3, :] = np.asarray(values, dtype=np.float64).reshape(3, 4)
    return m


def above_text(above) -> str:
    """The path a leaf's ``origin`` holds (down to the nearest shared subtree,
    tree.leaves's prefix) as text. It is kept as a chain of (above, path,
    name), one link a shared subtree, and written only when asked: the text of
    every level of a chain of 30,000 named objects took 3.5 GB (issue 29)."""
    if isinstance(above, str):
        return above
    pieces: list[str] = []
    while above:
        above, path, name = above
        pieces += (name, path)
    return join(reversed(pieces))


def _compile(node, matrix: np.ndarray, leaves: list, above):
    """``above``: the path down to the nearest shared subtree (``above_text``)."""
    if isinstance(node, tree.Primitive):
        return _leaf(node, matrix @ _matrix(node.matrix), leaves, above)
    if isinstance(node, tree.Use):
        if node.shared.child is None:
            return None
        return _compile(node.shared.child, matrix @ _matrix(node.matrix), leaves,
                        (above, node.path, f"({node.shared.name})"))
    if isinstance(node, tree.Smooth):  # traced through its refined facets
        first = len(leaves)
        made = smooth_leaf(node, matrix, leaves, TracedLeaf)
        for leaf in leaves[first:]:
            leaf.origin = (node, above)
        return made
    operands = [_compile(child, matrix, leaves, above) for child in node.operands]
    if node.op == "D":
        if not operands or operands[0] is None:
            return None
        cutters = [c for c in operands[1:] if c is not None]
        if not cutters:
            return operands[0]
        return TracedBoolean("D", [operands[0], _make("U", cutters)], operands[0].low,
                    operands[0].high)
    if node.op == "I" and any(o is None for o in operands):
        return None
    return _make(node.op, [o for o in operands if o is not None])


def _make(op: str, operands: list):
    """An n-ary union or intersection (nested ones of the same kind flattened)."""
    flat = []
    for o in operands:
        if isinstance(o, TracedBoolean) and o.op == op and op in "UI":
            flat.extend(o.operands)
        else:
            flat.append(o)
    if not flat:
        return None
    if len(flat) == 1:
        return flat[0]
    lows = np.array([o.low for o in flat])
    highs = np.array([o.high for o in flat])
    if op == "U":
        low, high = lows.min(axis=0), highs.max(axis=0)
    else:
        low, high = lows.max(axis=0), highs.min(axis=0)
        if np.any(low > high):
            return None
    return TracedBoolean(op, flat, low, high)


def _leaf(primitive: tree.Primitive, matrix: np.ndarray, leaves: list, above=""):
    if abs(np.linalg.det(matrix[:3, :3])) < 1e-300:
        return None  # flat: no volume
    inverse = np.linalg.inv(matrix)[:3, :]
    low, high = SPANS[primitive.kind].box(primitive.shape)
    corners = np.array([[x, y, z, 1.0] for x in (low[0], high[0]) for y in (low[1], high[1])
                        for z in (low[2], high[2])])
    placed = corners @ matrix[:3, :].T
    pad = 1e-9 * (1 + np.abs(placed).max())
    leaf = TracedLeaf(len(leaves), primitive.kind, tuple(primitive.shape), primitive.colour,
                inverse, placed.min(axis=0) - pad, placed.max(axis=0) + pad, (primitive, above))
    leaves.append(leaf)
    return leaf


def _crosses_box(node, rays: _Rays, rows: np.ndarray) -> np.ndarray:
    if rays.projection is not None:
        u0, u1, v0, v1 = rays.projection.rect(node)
        u, v = rays.u[rows], rays.v[rows]
        return (u >= u0) & (u <= u1) & (v >= v0) & (v <= v1)
    o = rays.origins[rows]
    inv = rays.inverse[rows]
    with np.errstate(invalid="ignore"):
        t0 = (node.low - o) * inv
        t1 = (node.high - o) * inv
    low, high = np.fmin(t0, t1), np.fmax(t0, t1)
    enter = np.fmax(np.fmax(low[:, 0], low[:, 1]), low[:, 2])
    leave = np.fmin(np.fmin(high[:, 0], high[:, 1]), high[:, 2])
    return (leave >= enter) & (leave >= rays.near)


def _evaluate(node, rays: _Rays, rows: np.ndarray):
    """The spans of the rays ``rows`` inside ``node``: (t, face), (len(rows), 2K)."""
    n = len(rows)
    hit = np.flatnonzero(_crosses_box(node, rays, rows))
    if len(hit) == 0:
        return np.full((n, 0), INF), np.zeros((n, 0), np.int64)
    inner = rows[hit]
    if isinstance(node, TracedLeaf):
        t, face = _leaf_spans(node, rays, inner)
    elif node.op == "D":
        t, face = _difference(node, rays, inner)
    else:
        parts = [_evaluate(o, rays, inner) for o in node.operands]
        t, face = combine(node.op, parts)
    if len(hit) == n:
        return t, face
    full_t = np.full((n, t.shape[1]), INF)
    full_face = np.zeros((n, t.shape[1]), np.int64)
    full_t[hit], full_face[hit] = t, face
    return full_t, full_face


def _first(node, rays: _Rays, rows: np.ndarray):
    """The first surface along the rays ``rows`` at or beyond ``near``: (t, face),
    each (len(rows),); a union is the nearest of its operands' first surfaces."""
    n = len(rows)
    t_best, face_best = np.full(n, INF), np.zeros(n, np.int64)
    if n == 0:
        return t_best, face_best
    if isinstance(node, TracedBoolean) and node.op == "U":
        hit = np.flatnonzero(_crosses_box(node, rays, rows))
        if len(hit) == 0:  # no ray comes near: nothing below is asked (one ray: a snap)
            return t_best, face_best
        for operand in node.operands:
            t, face = _first(operand, rays, rows[hit])
            nearer = t < t_best[hit]
            t_best[hit[nearer]], face_best[hit[nearer]] = t[nearer], face[nearer]
        return t_best, face_best
    t, face = _evaluate(node, rays, rows)
    if t.shape[1] == 0:
        return t_best, face_best
    # the first entry at or beyond ``near`` (a ray starting inside sees its exit)
    ahead = t >= rays.near
    column = np.argmax(ahead, axis=1)
    found = np.any(ahead, axis=1)
    picked = np.arange(n)
    t_best = np.where(found, t[picked, column], INF)
    face_best = face[picked, column]
    return t_best, face_best


def _blocked(node, rays: _Rays, rows: np.ndarray) -> np.ndarray:
    """Whether the rays ``rows`` meet a solid beyond ``near``; a union asks
    each operand only about the rays not yet blocked."""
    n = len(rows)
    if isinstance(node, TracedBoolean) and node.op == "U":
        blocked = np.zeros(n, bool)
        open_rows = np.flatnonzero(_crosses_box(node, rays, rows))
        for operand in node.operands:
            if len(open_rows) == 0:
                break
            now = _blocked(operand, rays, rows[open_rows])
            blocked[open_rows[now]] = True
            open_rows = open_rows[~now]
        return blocked
    t, _ = _evaluate(node, rays, rows)
    exits = t[:, 1::2]
    return np.any(np.isfinite(exits) & (exits > rays.near), axis=1)


def _leaf_spans(leaf: TracedLeaf, rays: _Rays, rows: np.ndarray):
    linear, shift = leaf.inverse[:, :3], leaf.inverse[:, 3]
    o = rays.origins[rows] @ linear.T + shift
    d = rays.directions[rows] @ linear.T
    t, face = SPANS[leaf.kind].spans(leaf.shape, o, d)
    return t, face + (leaf.number << FACE_BITS)


def _difference(node: TracedBoolean, rays: _Rays, rows: np.ndarray):
    t, face = _evaluate(node.operands[0], rays, rows)
    if t.shape[1] == 0:
        return t, face
    inside = np.flatnonzero(np.isfinite(t[:, 0]))
    if len(inside) == 0:
        return t[:, :0], face[:, :0]
    cut_t, cut_face = _evaluate(node.operands[1], rays, rows[inside])
    if cut_t.shape[1] == 0:
        return t, face
    some = np.flatnonzero(np.isfinite(cut_t[:, 0]))
    if len(some) == 0:
        return t, face
    rows_cut = inside[some]
    new_t, new_face = combine("D", [(t[rows_cut], face[rows_cut]),
                                    (cut_t[some], cut_face[some])])
    width = max(t.shape[1], new_t.shape[1])
    out_t = np.full((len(rows), width), INF)
    out_face = np.zeros((len(rows), width), np.int64)
    out_t[:, :t.shape[1]], out_face[:, :t.shape[1]] = t, face
    out_t[rows_cut] = INF
    out_t[rows_cut, :new_t.shape[1]] = new_t
    out_face[rows_cut, :new_t.shape[1]] = new_face
    keep = _columns(out_t)
    return out_t[:, :keep], out_face[:, :keep]


def _columns(t: np.ndarray) -> int:
    """Columns holding at least one span end (an even number)."""
    if t.shape[1] == 0:
        return 0
    used = np.flatnonzero(np.any(np.isfinite(t), axis=0))
    keep = int(used[-1]) + 1 if len(used) else 0
    return keep + keep % 2


def combine(op: str, parts: list):
    """The spans of ``op`` ("U", "I" or "D": the first minus the others) of
    the operands' spans along the same rays."""
    n = len(parts[0][0])
    if op == "I" and any(p[0].shape[1] == 0 for p in parts):
        return np.full((n, 0), INF), np.zeros((n, 0), np.int64)
    if op != "I":
        first = parts[0]
        parts = [first] + [p for p in parts[1:] if p[0].shape[1]]
        if op == "U":
            parts = [p for p in parts if p[0].shape[1]]
            if not parts:
                return np.full((n, 0), INF), np.zeros((n, 0), np.int64)
        if len(parts) == 1:
            return parts[0]
    if op == "U":
        return _union(parts)
    return _merge(op, parts)


def _union(parts: list):
    """A union where most rays are inside one operand at most: those rays keep
    that operand's spans, the others are merged."""
    n = len(parts[0][0])
    busy = np.zeros(n, np.int32)
    for t, _ in parts:
        busy += np.isfinite(t[:, 0])
    width = max(t.shape[1] for t, _ in parts)
    out_t = np.full((n, width), INF)
    out_face = np.zeros((n, width), np.int64)
    single = busy == 1
    for t, face in parts:
        rows = np.flatnonzero(single & np.isfinite(t[:, 0]))
        out_t[rows, :t.shape[1]] = t[rows]
        out_face[rows, :t.shape[1]] = face[rows]
    many = np.flatnonzero(busy > 1)
    if len(many) == 0:
        keep = _columns(out_t)
        return out_t[:, :keep], out_face[:, :keep]
    merged_t, merged_face = _merge("U", [(t[many], face[many]) for t, face in parts])
    if merged_t.shape[1] > width:
        grow = merged_t.shape[1] - width
        out_t = np.concatenate([out_t, np.full((n, grow), INF)], axis=1)
        out_face = np.concatenate([out_face, np.zeros((n, grow), np.int64)], axis=1)
    out_t[many] = INF
    out_t[many, :merged_t.shape[1]] = merged_t
    out_face[many, :merged_t.shape[1]] = merged_face
    keep = _columns(out_t)
    return out_t[:, :keep], out_face[:, :keep]


def _take(a: np.ndarray, order: np.ndarray) -> np.ndarray:
    """a[i, order[i, j]] for every row i (take_along_axis without its checks)."""
    rows, cols = a.shape
    flat = order + (np.arange(rows) * cols)[:, None]
    return a.ravel()[flat]


def _merge(op: str, parts: list):
    """The operands' entries and exits sorted along each ray, and the
    stretches where the operator holds."""
    n = len(parts[0][0])
    # entries before exits, so that at equal t an entry comes first (stable sort)
    entries = [p[0][:, 0::2] for p in parts]
    exits = [p[0][:, 1::2] for p in parts]
    t = np.concatenate(entries + exits, axis=1)
    face = np.concatenate([p[1][:, 0::2] for p in parts] + [p[1][:, 1::2] for p in parts],
                          axis=1)
    widths = [e.shape[1] for e in entries]
    half = sum(widths)
    delta = np.concatenate([np.ones(half, np.int8), -np.ones(half, np.int8)])
    order = np.argsort(t, axis=1, kind="stable")
    t = _take(t, order)
    face = _take(face, order)
    steps = delta[order]
    if op == "U":
        inside = np.cumsum(steps, axis=1, dtype=np.int32) > 0
    elif op == "I":
        inside = np.cumsum(steps, axis=1, dtype=np.int32) == len(parts)
    else:
        mine = np.concatenate([np.ones(widths[0], bool), np.zeros(half - widths[0], bool)])
        first = np.concatenate([mine, mine])[order]
        in_first = np.cumsum(np.where(first, steps, 0), axis=1, dtype=np.int32) > 0
        in_rest = np.cumsum(np.where(first, 0, steps), axis=1, dtype=np.int32) > 0
        inside = in_first & ~in_rest
    before = np.zeros_like(inside)
    before[:, 1:] = inside[:, :-1]
    change = (inside != before) & np.isfinite(t)
    count = change.sum(axis=1)
    keep = int(count.max()) if n else 0
    keep += keep % 2
    if keep == 0:
        return np.full((n, 0), INF), np.zeros((n, 0), np.int64)
    pick = np.argsort(~change, axis=1, kind="stable")[:, :keep]
    out_t = _take(t, pick)
    out_face = _take(face, pick)
    out_t[np.arange(keep)[None, :] >= count[:, None]] = INF
    if op == "U":
        return out_t, out_face
    return _without_slivers(out_t, out_face)


# A span shorter than this (relative to its distance) is rounding between faces
# that coincide on paper, as a cutter flush with a wall's foot: regularized away.
SLIVER = 1e-9


def _without_slivers(t: np.ndarray, face: np.ndarray):
    """The spans of zero thickness removed, the others packed to the left."""
    entry, exit_ = t[:, 0::2], t[:, 1::2]
    with np.errstate(invalid="ignore"):
        thin = np.isfinite(entry) & (exit_ - entry <= SLIVER * (1.0 + np.abs(entry)))
    if not thin.any():
        return t, face
    order = np.argsort(thin | ~np.isfinite(entry), axis=1, kind="stable")
    columns = np.stack([2 * order, 2 * order + 1], axis=2).reshape(len(t), -1)
    kept_t, kept_face = _take(t, columns), _take(face, columns)
    dropped = np.take_along_axis(thin, order, axis=1)
    kept_t[np.repeat(dropped, 2, axis=1)] = INF
    keep = _columns(kept_t)
    return kept_t[:, :keep], kept_face[:, :keep]

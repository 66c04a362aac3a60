"""Whether a frame is certainly empty, told from its evaluated tree alone.

A run facetizes each frame and warns of one that has no polygons (LANGUAGE.md
§7: "frame 1 is empty: its objects have no volume"). ``castor --check`` and
the language server evaluate the frames but never facetize them; they give the
same warning where the tree shows the frame empty without building a solid:

- a difference whose first operand lies inside a box it subtracts: a ``!cu``
  under any affine map (also through named objects, in a union, an
  intersection of such boxes, or smoothed by ``@s`` with an angle under 90
  degrees, which keeps every edge of a cube), holding the bounding box of
  the first operand;
- an intersection of operands whose bounding boxes do not overlap (touching
  is empty too: two solids that only touch have an empty intersection);
- a union, difference or smoothing of empty operands.

The same rules tell a door or window that certainly cuts nothing from its
wall (``idle_openings``): the block it takes out is an intersection.

It says "empty" only when that is certain, never a frame a run would write
with polygons; a frame emptied in a way these rules do not see (a sphere
subtracted from a smaller sphere) is said by a run only. A bounding box is
that of the primitives' unit boxes under their matrices, widened by the
facet tolerance around a curved primitive (its facets may stray that far
from the surface), so that what the facetizer makes lies inside it.
"""

from __future__ import annotations

from castor.csg import tree
from castor.primitives import PRIMITIVES

# how far outside a subtracted box a corner may lie (in the box's unit space)
# and still be inside: rounding of coordinates that coincide on paper, which
# the facetizer treats as coinciding (LANGUAGE.md §7)
_SLACK = 1e-9
# '@s' with a smaller angle keeps every edge of a cube (90 degrees): the cube itself
_CUBE_KEPT_BELOW = 90.0

Box = tuple[tuple[float, float, float], tuple[float, float, float]]


def empty_message(number: int) -> str:
    """The warning for a frame without polygons, as every output says it."""
    return f"frame {number} is empty: its objects have no volume"


def certainly_empty(frame: tree.FrameTree) -> bool:
    """Whether the frame's objects certainly have no volume (a frame with rooms
    never is: its rooms are written)."""
    if frame.spaces:
        return False
    judge = _Judge()
    try:
        return all(obj.root is None or judge.empty(obj.root, tree.IDENTITY)
                   for obj in frame.objects)
    except RecursionError:  # deeper than this walk goes: not known, so not said
        return False


def idle_openings(frame: tree.FrameTree) -> list:
    """The doors and windows (castor.csg.elements.Opening) that certainly cut
    nothing from the element they are subtracted from: their box does not
    overlap that element's (a door moved off its wall). What a run's take-off
    says of them (castor.csg.elements.cuts_nothing), told without a solid."""
    if frame.classes is None:
        return []
    from castor.csg.elements import find, opening_tree

    _, openings = find(frame)
    # the trees held while judged: the judge keys its booleans by id
    blocks = [opening_tree(frame, o) for o in openings]
    judge = _Judge()
    try:
        return [o for o, block in zip(openings, blocks) if judge.empty(block, tree.IDENTITY)]
    except RecursionError:  # deeper than this walk goes: not known, so not said
        return []


class _Judge:
    """One frame's walk: each shared subtree judged and boxed once, in its own space."""

    def __init__(self):
        # shared subtrees and booleans judged and boxed so far (by id: the tree
        # holds them while the walk runs; a shared subtree's key is a digest
        # that an analysis never otherwise works out), so that nested booleans
        # are walked once, not once per level
        self.empties: dict[int, bool] = {}
        self.boxes: dict[int, Box | None] = {}
        self.judged: dict[int, bool] = {}
        self.boxed: dict[tuple, Box | None] = {}

    def empty(self, node, outer: tree.Matrix) -> bool:
        kind = type(node)
        if kind is tree.Primitive:
            return False
        if kind is tree.Boolean:
            found = self.judged.get(id(node))
            if found is None:
                found = self.judged[id(node)] = self._empty_boolean(node, outer)
            return found
        if kind is tree.Use:
            return self._shared_empty(node.shared)
        if kind is tree.Smooth:
            return self.empty(node.operand, tree.IDENTITY)
        return False

    def _empty_boolean(self, node: tree.Boolean, outer: tree.Matrix) -> bool:
        operands = node.operands
        if node.op == "U":
            return all(self.empty(o, outer) for o in operands)
        if node.op == "I":
            if any(self.empty(o, outer) for o in operands):
                return True
            boxes = [self.box(o, outer) for o in operands]
            return any(a is not None and b is not None and _apart(a, b)
                       for k, a in enumerate(boxes) for b in boxes[k + 1:])
        if self.empty(operands[0], outer):
            return True
        if not any(self.covers(o, None, outer, probe=True) for o in operands[1:]):
            return False  # no box subtracted: the first operand's box is not needed
        box = self.box(operands[0], outer)
        return box is not None and any(self.covers(o, box, outer) for o in operands[1:])

    def _shared_empty(self, shared: tree.Shared) -> bool:
        found = self.empties.get(id(shared))
        if found is None:
            found = self.empties[id(shared)] = shared.child is None or self.empty(
                shared.child, tree.IDENTITY)
        return found

    # --- bounding boxes
    def box(self, node, outer: tree.Matrix) -> Box | None:
        """A box that holds the node's facets under ``outer`` (None: unknown)."""
        if type(node) is not tree.Boolean:
            return self._box(node, outer)
        key = (id(node), outer)
        if key not in self.boxed:
            self.boxed[key] = self._box(node, outer)
        return self.boxed[key]

    def _box(self, node, outer: tree.Matrix) -> Box | None:
        kind = type(node)
        if kind is tree.Primitive:
            declared = PRIMITIVES[node.kind]
            matrix = tree.compose(outer, node.matrix)
            box = tree.placed_box(matrix, *declared.box(node.shape))
            if declared.curved:
                box = _widened(box, node.tolerance * _stretch(outer))
            return box
        if kind is tree.Use:
            local = self._shared_box(node.shared)
            if local is None:
                return None
            return tree.placed_box(tree.compose(outer, node.matrix), *local)
        if kind is tree.Smooth:  # inside the convex hull of its control mesh
            return self.box(node.operand, tree.compose(outer, node.matrix))
        if kind is not tree.Boolean:
            return None
        if node.op == "D":
            return self.box(node.operands[0], outer)
        boxes = [self.box(o, outer) for o in node.operands]
        if node.op == "U":
            if any(b is None for b in boxes):
                return None
            return (tuple(min(b[0][i] for b in boxes) for i in range(3)),
                    tuple(max(b[1][i] for b in boxes) for i in range(3)))
        known = [b for b in boxes if b is not None]
        if not known:
            return None
        return (tuple(max(b[0][i] for b in known) for i in range(3)),
                tuple(min(b[1][i] for b in known) for i in range(3)))

    def _shared_box(self, shared: tree.Shared) -> Box | None:
        if id(shared) not in self.boxes:
            self.boxes[id(shared)] = None if shared.child is None else self.box(
                shared.child, tree.IDENTITY)
        return self.boxes[id(shared)]

    # --- what a subtracted operand certainly holds
    def covers(self, node, box: Box | None, outer: tree.Matrix, probe: bool = False) -> bool:
        """Whether the node's solid holds the whole ``box``; with ``probe``, only
        whether it could (it is made of boxes), before any box is worked out."""
        kind = type(node)
        if kind is tree.Primitive:
            return node.kind == "cu" and (probe or _inside_cube(box, tree.compose(
                outer, node.matrix)))
        if kind is tree.Use:
            child = node.shared.child
            return child is not None and self.covers(child, box, tree.compose(
                outer, node.matrix), probe)
        if kind is tree.Smooth:  # a box's right-angled edges are kept below 90 degrees
            return node.angle < _CUBE_KEPT_BELOW and type(node.operand) is tree.Primitive and \
                _right_angled(tree.compose(node.matrix, node.operand.matrix)) and \
                self.covers(node.operand, box, tree.compose(outer, node.matrix), probe)
        if kind is not tree.Boolean or node.op == "D":
            return False
        if node.op == "U":
            return any(self.covers(o, box, outer, probe) for o in node.operands)
        return all(self.covers(o, box, outer, probe) for o in node.operands)


def _right_angled(m: tree.Matrix) -> bool:
    """Whether the matrix keeps right angles (its columns orthogonal): a cube it
    places keeps its right-angled edges, which a smoothing below 90 degrees
    keeps (LANGUAGE.md §4.2); a shear or a scale across a turn makes obtuse
    edges, which it rounds off."""
    columns = [(m[j], m[4 + j], m[8 + j]) for j in range(3)]
    for a in range(3):
        for b in range(a + 1, 3):
            u, v = columns[a], columns[b]
            dot = u[0] * v[0] + u[1] * v[1] + u[2] * v[2]
            size = (sum(x * x for x in u) * sum(x * x for x in v)) ** 0.5
            if abs(dot) > 1e-9 * size:
                return False
    return True


def _corners(box: Box):
    (x0, y0, z0), (x1, y1, z1) = box
    return [(x, y, z) for x in (x0, x1) for y in (y0, y1) for z in (z0, z1)]


def _apply(m: tree.Matrix, p) -> tuple[float, float, float]:
    x, y, z = p
    return (m[0] * x + m[1] * y + m[2] * z + m[3], m[4] * x + m[5] * y + m[6] * z + m[7],
            m[8] * x + m[9] * y + m[10] * z + m[11])


def _widened(box: Box, margin: float) -> Box:
    return (tuple(v - margin for v in box[0]), tuple(v + margin for v in box[1]))


def _stretch(m: tree.Matrix) -> float:
    """An upper bound of how much ``m`` lengthens a vector (its Frobenius norm)."""
    return sum(m[i] * m[i] for i in (0, 1, 2, 4, 5, 6, 8, 9, 10)) ** 0.5


def _apart(a: Box, b: Box) -> bool:
    """Whether two boxes have no volume in common (they may touch)."""
    return any(a[1][i] <= b[0][i] or b[1][i] <= a[0][i] for i in range(3))


def _inside_cube(box: Box, m: tree.Matrix) -> bool:
    """Whether ``box`` lies inside the unit cube placed by ``m``."""
    inverse = _inverse(m)
    if inverse is None:
        return False
    for corner in _corners(box):
        if not all(-_SLACK <= v <= 1 + _SLACK for v in _apply(inverse, corner)):
            return False
    return True


def _inverse(m: tree.Matrix) -> tree.Matrix | None:
    a, b, c, tx, d, e, f, ty, g, h, i, tz = m
    det = a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g)
    if not abs(det) > 1e-300:
        return None
    r = (
        (e * i - f * h) / det, (c * h - b * i) / det, (b * f - c * e) / det,
        (f * g - d * i) / det, (a * i - c * g) / det, (c * d - a * f) / det,
        (d * h - e * g) / det, (b * g - a * h) / det, (a * e - b * d) / det)
    return (r[0], r[1], r[2], -(r[0] * tx + r[1] * ty + r[2] * tz),
            r[3], r[4], r[5], -(r[3] * tx + r[4] * ty + r[5] * tz),
            r[6], r[7], r[8], -(r[6] * tx + r[7] * ty + r[8] * tz))

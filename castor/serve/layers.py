"""Which element, of which class, each face the page draws belongs to
(LANGUAGE.md §11): what lets the page show the classes as layers and name a
face's element when it is pointed at.

A face comes from a primitive, whose path the page has already; most
primitives' faces all belong to one element, the innermost classed object on
the primitive's way down (castor.csg.elements shares an object's solid out by
the same rule: into the first operand of a difference, into the operand of an
intersection that holds a classed object). A primitive subtracted from a solid
(a window's box cut out of the walls) makes faces on the elements of what it
was subtracted from: each such face goes to the first of those elements, the
innermost first, whose box holds its middle. The page's table of origins then
has one entry per primitive and element, and each triangle the number of its
entry; nothing else of the frame changes.
"""

from __future__ import annotations

from dataclasses import replace

from castor.csg import tree
from castor.csg.paths import join

UNCLASSED = None  # the class of an element no annotation classes

# corner k of a box: bit ``axis`` of k chooses its high (1) or low (0) coordinate
_CORNER_BITS = tuple(tuple(bool((k >> axis) & 1) for axis in range(3)) for k in range(8))


class _Walker:
    """Walks a frame's tree once for the element of each primitive's faces."""

    def __init__(self, declared):
        from castor.csg.elements import Boxes

        self.declared = declared
        self.holds: dict[object, bool] = {}
        self.boxes = Boxes()
        # (node, matrix) -> its box in the scene: the primitives cut out of one
        # solid share its elements' boxes (held alive in ``self.rules``)
        self.placed: dict[tuple, object] = {}
        # path -> candidates: (label, node, matrix) in order; one: all its faces
        self.rules: dict[str, list] = {}

    def mark(self, node):
        if self.declared is None or type(node) is not tree.Use:
            return None
        mark = self.declared.of(node.shared.location)
        return mark if mark is not None and mark.role != "space" else None

    def has_classes(self, node) -> bool:
        if self.declared is None:
            return False
        kind = type(node)
        key = node.shared.key if kind is tree.Use else id(node)
        if key not in self.holds:
            self.holds[key] = False
            if kind is tree.Use:
                child = node.shared.child
                held = self.mark(node) is not None or (child is not None
                                                       and self.has_classes(child))
            elif kind is tree.Boolean:
                held = any(self.has_classes(o) for o in node.operands)
            else:
                held = False  # a primitive; a smooth solid is one piece
            self.holds[key] = held
        return self.holds[key]

    def chosen(self, node: tree.Boolean) -> int:
        """The operand of an intersection whose elements have its solid."""
        return next((k for k, o in enumerate(node.operands) if self.has_classes(o)), 0)

    def walk(self, root, owner) -> None:
        stack = [(root, tree.IDENTITY, "", owner, None, True)]
        while stack:
            node, matrix, prefix, owner, cut, open_ = stack.pop()
            kind = type(node)
            if kind is tree.Primitive:
                self.rules[join((prefix, node.path))] = cut or [(owner, None, None)]
            elif kind is tree.Use:
                if node.shared.child is None:
                    continue
                mark = self.mark(node) if open_ and cut is None else None
                if mark is not None:
                    owner = (node.shared.name, mark.short)
                stack.append((node.shared.child, tree.compose(matrix, node.matrix),
                              join((prefix, node.path, f"({node.shared.name})")), owner, cut,
                              open_))
            elif kind is tree.Smooth:
                stack.append((node.operand, tree.compose(matrix, node.matrix), prefix, owner,
                              cut, False))
            elif kind is tree.Boolean:
                keep = (0 if node.op == "D" else self.chosen(node) if node.op == "I" else None)
                if keep is not None and cut is None and open_:
                    held = self.regions(node.operands[keep], matrix, owner)
                else:
                    held = cut
                for k in reversed(range(len(node.operands))):
                    inside = keep is None or k == keep
                    stack.append((node.operands[k], matrix, prefix, owner,
                                  cut if inside else held, open_))

    def regions(self, node, matrix, owner) -> list:
        """The elements that share out ``node``'s solid, the innermost first, then
        ``owner`` (the rest of it), each (label, node, matrix to the scene)."""
        found = []
        stack = [(node, matrix, 0)]
        while stack:
            node_, m, depth = stack.pop()
            if not self.has_classes(node_):
                continue
            kind = type(node_)
            if kind is tree.Use:
                mark = self.mark(node_)
                if mark is not None:
                    found.append((depth, (node_.shared.name, mark.short), node_, m))
                if node_.shared.child is not None:
                    stack.append((node_.shared.child, tree.compose(m, node_.matrix), depth + 1))
            elif kind is tree.Boolean:
                operands = (node_.operands if node_.op == "U" else (node_.operands[0],)
                            if node_.op == "D" else (node_.operands[self.chosen(node_)],))
                stack.extend((o, m, depth + 1) for o in operands)
        found.sort(key=lambda f: -f[0])
        return [(label, n, m) for _, label, n, m in found] + [(owner, node, matrix)]

    def box(self, node, matrix):
        """The box, in the scene, that holds the node's solid, with the slack
        of its test (None: none)."""
        key = (id(node), id(matrix))
        if key not in self.placed:
            import numpy as np

            box = self._box(node, matrix)
            self.placed[key] = None if box is None else (
                box, 1e-6 * max(1.0, float(np.abs(np.concatenate(box)).max())))
        return self.placed[key]

    def _box(self, node, matrix):
        import numpy as np

        box = self.boxes.of(node)  # where the node stands: its own matrix applied
        if box is None:
            return None
        low, high = np.asarray(box[0], float), np.asarray(box[1], float)
        corners = np.where(_CORNER_BITS, high, low)  # the 8 corners, bit k of x, y, z
        m = np.asarray(matrix, float).reshape(3, 4)
        placed = corners @ m[:, :3].T + m[:, 3]
        return placed.min(axis=0), placed.max(axis=0)


def classified(frame, frame_tree: tree.FrameTree):
    """``frame`` (castor.serve.evaluation.DrawnFrame) with each face's element and
    class: its origins split by element where a primitive's faces lie on
    several, ``layers`` giving each origin's (element, class short name or None)."""
    import numpy as np

    walker = _Walker(frame_tree.classes)
    try:
        for obj in frame_tree.objects:
            if obj.root is not None:
                walker.walk(obj.root, (obj.name, UNCLASSED))
    except RecursionError:
        return frame  # too deep to say: the faces say their paths only
    n = frame.triangles
    numbers = np.frombuffer(frame.data, "<u4", n, offset=n * 36)
    table = _Table(frame.origins)
    rules = [walker.rules.get(path) or [((None, UNCLASSED), None, None)]
             for path, _ in frame.origins]
    # a primitive whose faces are all one element's: one entry, looked up at once
    single = np.array([table.entry(k, rule[0][0]) if len(rule) == 1 else 0
                       for k, rule in enumerate(rules)] or [0], "<u4")
    renumbered = single[numbers] if n else np.zeros(0, "<u4")
    split = np.array([len(rule) > 1 for rule in rules] or [False])
    if split.any():
        corners = np.frombuffer(frame.data, "<f4", n * 9).reshape(n, 3, 3)
        faces = np.nonzero(split[numbers])[0]
        faces = faces[np.argsort(numbers[faces], kind="stable")]
        bounds = np.searchsorted(numbers[faces], np.arange(len(rules) + 1))
        for k in np.nonzero(split)[0]:
            mine = faces[bounds[k]:bounds[k + 1]]
            for label, inside in _shared_out(walker, rules[k], corners[mine]):
                renumbered[mine[inside]] = table.entry(int(k), label)
    data = frame.data[:n * 36] + renumbered.astype("<u4").tobytes()
    return replace(frame, origins=tuple(table.origins), layers=tuple(table.layers), data=data)


class _Table:
    """The page's table of origins: one entry per primitive and element."""

    def __init__(self, given):
        self.given = given
        self.origins: list = []
        self.layers: list = []
        self.index: dict = {}

    def entry(self, k: int, label) -> int:
        key = (k, label)
        if key not in self.index:
            self.index[key] = len(self.origins)
            self.origins.append(self.given[k])
            self.layers.append(label)
        return self.index[key]


def _shared_out(walker: _Walker, rule: list, corners):
    """(label, which faces) of the faces of a subtracted primitive: each to the
    first element whose box holds its middle, the last (the rest) taking the others."""
    import numpy as np

    middles = corners.astype(float).mean(axis=1)
    left = np.ones(len(middles), bool)
    for place, (label, node, matrix) in enumerate(rule):
        if not left.any():
            return
        held = walker.box(node, matrix) if place < len(rule) - 1 else None
        if held is None:
            inside = left.copy()
        else:
            box, slack = held
            inside = left & np.all((middles >= box[0] - slack)
                                   & (middles <= box[1] + slack), axis=1)
        if inside.any():
            left &= ~inside
            yield label, inside

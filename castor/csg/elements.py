"""The elements of a frame (LANGUAGE.md §11): what each part of its solids is.

Each use of a classed object in a frame's evaluated tree is one ``Element``
(its class, predefined type, settings, names, ``FILE:LINE``), nested classed
objects their own elements, the rest of each '>' object the object's element.
A ``door`` or ``window`` subtracted from an element (the second operand of a
``$D``, at any depth of unions) is an ``Opening`` instead. Spaces are taken
out of the tree before anything is made of it (``without_spaces``) and kept
as ``SpaceUse``s.

Everything here is plain data found by walking the tree, without making any
solid: an element holds its *address* in the tree (the operand taken at each
node from its object's root), from which ``element_tree`` and
``opening_tree`` build the CSG tree of its own solid when an output asks
(castor.quantities.Takeoff makes and measures them). Which solid is whose: a point
of an object's solid belongs to the innermost classed object on its way
down, going into the first operand of a union that holds it, into the first
operand of a difference, and into the operand of an intersection that holds
a classed object (else the first): so the elements of an object share its
solid out without overlap.
"""

from __future__ import annotations

from castor.csg import tree
from castor.records import Record


# what the take-off, the IFC and --check say of a door or window that cuts nothing
IDLE = "it is left out of the take-off and the IFC (no opening, no element)"


class Element(Record):
    """One element of a frame: a use of a classed object, or the rest of a '>'
    object (``classification`` None: unclassed, a proxy)."""

    __slots__ = ("number", "name", "classification", "object", "address", "where", "parts")

    def __init__(self, number: int, name: str, classification, object: int,
                 address: tuple[int, ...], where: str, parts: tuple[tuple[int, ...], ...]):
        self.number = number  # 1, 2, ... in the frame, in the order of the tree
        self.name = name  # the object's name
        self.classification = classification  # castor.language.classes.Classification or None
        self.object = object  # index of its '>' object in the frame
        self.address = address  # operand indices from the object's root to its Use
        self.where = where  # FILE:LINE of its definition
        # addresses (from its own node) of the classed objects inside it, whose
        # solids are theirs, not its
        self.parts = parts

    @property
    def ifc_class(self) -> str:
        from castor.language.classes import PROXY

        return PROXY if self.classification is None else self.classification.ifc_class


class Opening(Record):
    """A door or window subtracted from an element: the part of the solid it
    cut (``opening_tree``), hosted by one of the elements it was cut from."""

    __slots__ = ("number", "name", "classification", "object", "address", "cut", "where")

    def __init__(self, number: int, name: str, classification, object: int,
                 address: tuple[int, ...], cut: tuple[int, ...], where: str):
        self.number = number
        self.name = name
        self.classification = classification  # its door or window class, with hinge and swing
        self.object = object
        self.address = address  # of the door's or window's Use
        self.cut = cut  # of the '$D' node it is subtracted by
        self.where = where


class SpaceUse(Record):
    """A room: a use of a ``space`` object, placed in the scene, never built."""

    __slots__ = ("name", "classification", "matrix", "shared", "where")

    def __init__(self, name: str, classification, matrix: tree.Matrix, shared: tree.Shared,
                 where: str):
        self.name = name
        self.classification = classification
        self.matrix = matrix  # from the space's own units to the scene
        self.shared = shared
        self.where = where


def _children(node) -> tuple:
    kind = type(node)
    if kind is tree.Boolean:
        return node.operands
    if kind is tree.Use:
        return () if node.shared.child is None else (node.shared.child,)
    return ()  # a primitive; a smooth solid is one piece, its parts not elements


def _where(location) -> str:
    return f"{location.file}:{location.line}" if location is not None else ""


class _Finder:
    """Walks a frame's tree once for its elements and openings."""

    def __init__(self, declared):
        self.declared = declared
        self.holds: dict[str, bool] = {}  # shared key: holds a classed object
        self.elements: list[Element] = []
        self.openings: list[Opening] = []

    def classed(self, node):
        return self.declared.of(node.shared.location) if type(node) is tree.Use else None

    def has_classes(self, node) -> bool:
        """Whether a classed object is anywhere under ``node``."""
        if type(node) is tree.Use:
            key = node.shared.key
            if key not in self.holds:
                self.holds[key] = False  # (a tree has no cycles; this is a memo)
                self.holds[key] = self.classed(node) is not None or any(
                    self.has_classes(c) for c in _children(node))
            return self.holds[key]
        return any(self.has_classes(c) for c in _children(node))

    def walk(self, node, index: int, address: tuple[int, ...], owner: list) -> None:
        """Note the elements and openings under ``node``; ``owner`` collects the
        addresses of the classed objects directly inside the element above."""
        mark = self.classed(node)
        if mark is not None and mark.role != "space":
            parts: list = []
            element = Element(0, node.shared.name, mark, index, address,
                              _where(node.shared.location), ())
            self.elements.append(element)
            owner.append(address)
            for k, child in enumerate(_children(node)):
                self.walk(child, index, address + (k,), parts)
            self.elements[self.elements.index(element)] = element.replace(
                parts=tuple(a[len(address):] for a in parts))
            return
        if type(node) is tree.Boolean and node.op == "D":
            self.walk(node.operands[0], index, address + (0,), owner)
            self._cutters(node.operands[1], index, address + (1,), address)
            return
        for k, child in enumerate(_children(node)):
            if self.has_classes(child):
                self.walk(child, index, address + (k,), owner)
                if type(node) is tree.Boolean and node.op == "I":
                    return  # the classed objects of the other operands are this one's

    def _cutters(self, node, index: int, address: tuple[int, ...], cut: tuple[int, ...]) -> None:
        """Doors and windows in the subtracted operand of a '$D', through unions."""
        mark = self.classed(node)
        if mark is not None:
            if mark.role == "opening":
                self.openings.append(Opening(0, node.shared.name, mark, index, address, cut,
                                             _where(node.shared.location)))
                return
        if type(node) is tree.Boolean and node.op != "U":
            return
        for k, child in enumerate(_children(node)):
            if self.has_classes(child):
                self._cutters(child, index, address + (k,), cut)


def find(frame_tree: tree.FrameTree) -> tuple[list[Element], list[Opening]]:
    """The elements and openings of a frame, numbered in the tree's order: for
    each '>' object, its classed objects, then the rest of it (an element of
    its own class if the object is classed, else unclassed) when it is not
    wholly theirs."""
    elements: list[Element] = []
    openings: list[Opening] = []
    declared = frame_tree.classes
    for index, obj in enumerate(frame_tree.objects):
        if obj.root is None:
            continue
        if declared is None:
            elements.append(Element(0, obj.name, None, index, (), obj.where, ()))
            continue
        finder = _Finder(declared)
        top: list = []
        finder.walk(obj.root, index, (), top)
        if () not in top:  # the object is not itself a classed object's use
            elements.append(Element(0, obj.name, None, index, (), obj.where, tuple(top)))
        elements.extend(finder.elements)
        openings.extend(finder.openings)
    elements = [e.replace(number=k) for k, e in enumerate(elements, 1)]
    openings = [o.replace(number=k) for k, o in enumerate(openings, 1)]
    return elements, openings


def cuts_nothing(opening: Opening, consequence: str = IDLE) -> str:
    """The warning for a door or window that cuts nothing from the element it is
    subtracted from (its block is empty), as every output words it; ``consequence``
    says what the output does without it (the drawings: "no symbol is drawn")."""
    return (f"{opening.classification.short} '{opening.name}' ({opening.where}) cuts "
            f"nothing from the element it is subtracted from: {consequence}")


# --- the CSG tree of an element's own solid


def _node_at(root, address):
    node = root
    for k in address:
        node = _children(node)[k]
    return node


def _wrap(use: tree.Use, child, suffix: str) -> tree.Use:
    """``use`` with its shared subtree's content replaced by ``child``."""
    shared = use.shared
    name = f"{shared.name}{suffix}"
    return tree.Use(use.matrix, use.path,
                    tree.Shared(shared.name, child, tree.content_key(name, child),
                                shared.location))


class Boxes:
    """Boxes that hold the solids of tree nodes, from their primitives' boxes
    (never smaller than the solid; a difference keeps its first operand's),
    each shared subtree's made once: what lets an element's tree leave out the
    operands its solid cannot meet."""

    def __init__(self):
        self.memo: dict[str, tuple | None] = {}

    def of(self, node):
        kind = type(node)
        if kind is tree.Primitive:
            from castor.primitives import PRIMITIVES

            low, high = PRIMITIVES[node.kind].box(node.shape)
            return tree.placed_box(node.matrix, low, high)
        if kind is tree.Use:
            key = node.shared.key
            if key not in self.memo:
                child = node.shared.child
                self.memo[key] = None if child is None else self.of(child)
            box = self.memo[key]
            return None if box is None else tree.placed_box(node.matrix, *box)
        if kind is tree.Smooth:
            box = self.of(node.operand)
            return None if box is None else tree.placed_box(node.matrix, *box)
        boxes = [self.of(o) for o in node.operands]
        if node.op == "D":
            return boxes[0]
        if node.op == "U":
            boxes = [b for b in boxes if b is not None]
            if not boxes:
                return None
            return (tuple(min(b[0][i] for b in boxes) for i in range(3)),
                    tuple(max(b[1][i] for b in boxes) for i in range(3)))
        if any(b is None for b in boxes):
            return None
        low = tuple(max(b[0][i] for b in boxes) for i in range(3))
        high = tuple(min(b[1][i] for b in boxes) for i in range(3))
        return (low, high) if all(a <= b for a, b in zip(low, high)) else None

    def share(self, a, b) -> bool:
        """Whether the solids of ``a`` and ``b`` (in one space) may have a
        volume in common: False only where their boxes show they have none,
        seen down their trees (a union's operands each apart from the other
        solid; a difference's first operand apart, or where it could meet the
        other solid taken out by an axis-aligned cube). Solids that only touch
        — a floor slab in a ring of walls, a stair in the floor's well — are
        apart: cutting one with the other would change nothing but leave the
        other's faces and their points on it."""
        return not _Apart(self).apart((a, tree.IDENTITY), (b, tree.IDENTITY))


class _Apart:
    """The proof that two solids have no volume in common (Boxes.share), each
    node with the matrix that places it, at most ``budget`` steps of it."""

    def __init__(self, boxes: Boxes, budget: int = 400):
        self.boxes, self.budget = boxes, budget

    def box(self, placed):
        node, matrix = placed
        box = self.boxes.of(node)
        return None if box is None else tree.placed_box(matrix, *box)

    def apart(self, a, b) -> bool:
        box_a, box_b = self.box(a), self.box(b)
        if box_a is None or box_b is None or not all(
                box_a[0][i] < box_b[1][i] and box_b[0][i] < box_a[1][i] for i in range(3)):
            return True  # no common interior
        self.budget -= 1
        if self.budget < 0:
            return False
        return self.parts_apart(b, a) or self.parts_apart(a, b)

    def parts_apart(self, placed, other) -> bool:
        """Whether ``placed`` is seen apart from ``other`` by its parts."""
        node, matrix = placed
        kind = type(node)
        if kind is tree.Use:
            child = node.shared.child
            return True if child is None else self.apart(
                (child, tree.compose(matrix, node.matrix)), other)
        if kind is not tree.Boolean:
            return False
        operands = [(o, matrix) for o in node.operands]
        if node.op == "U":
            return all(self.apart(o, other) for o in operands)
        if node.op == "I":
            return any(self.apart(o, other) for o in operands)
        if self.apart(operands[0], other):
            return True
        box_first, box_other = self.box(operands[0]), self.box(other)
        region = (tuple(map(max, box_first[0], box_other[0])),
                  tuple(map(min, box_first[1], box_other[1])))
        return self.covers(operands[1], region)

    def covers(self, placed, region) -> bool:
        """Whether ``placed``'s solid holds the box ``region`` (its cubes seen)."""
        node, matrix = placed
        kind = type(node)
        if kind is tree.Use:
            child = node.shared.child
            return child is not None and self.covers((child, tree.compose(matrix, node.matrix)),
                                                     region)
        if kind is tree.Boolean:
            if node.op == "U":
                return any(self.covers((o, matrix), region) for o in node.operands)
            if node.op == "I":
                return all(self.covers((o, matrix), region) for o in node.operands)
            return False
        if kind is not tree.Primitive or node.kind != "cu":
            return False
        placed_matrix = tree.compose(matrix, node.matrix)
        if any(sum(1 for axis in range(3) if placed_matrix[row + axis] != 0) != 1
               for row in (0, 4, 8)):
            return False  # turned: its box is more than the cube
        low, high = tree.placed_box(placed_matrix, (0.0, 0.0, 0.0), (1.0, 1.0, 1.0))
        return all(low[i] <= region[0][i] and region[1][i] <= high[i] for i in range(3))


def _reach(node, address, target, boxes: Boxes):
    """The part of ``node``'s solid whose way down leads to the node at
    ``address``, that node replaced by ``target(node)``."""
    if not address:
        return target(node)
    k, rest = address[0], address[1:]
    kind = type(node)
    if kind is tree.Use:
        return _wrap(node, _reach(node.shared.child, rest, target, boxes), "#part")
    inner = _reach(node.operands[k], rest, target, boxes)
    if node.op == "U":
        # the operands before it have what they share with it: those it may
        # share a volume with (not those it only touches)
        before = tuple(o for o in node.operands[:k] if boxes.share(o, node.operands[k]))
        if not before:
            return inner
        other = before[0] if len(before) == 1 else tree.Boolean("U", before, node.location)
        return tree.Boolean("D", (inner, other), node.location)
    if node.op == "D":
        return tree.Boolean("D", (inner, node.operands[1]), node.location)
    others = node.operands[:k] + node.operands[k + 1:]
    return tree.Boolean("I", (inner,) + others, node.location)


def _less_parts(node, parts, location, boxes: Boxes):
    """``node``'s solid less the solids its classed parts take."""
    if not parts:
        return node
    if type(node) is tree.Use and node.shared.child is not None and all(parts):
        # moved as the node is: made once per shared subtree (1,024 copies of a
        # house: the rest of each is one difference, not 1,024)
        return _wrap(node, _less_parts(node.shared.child, tuple(p[1:] for p in parts),
                                       location, boxes), "#part")
    taken = [_reach(node, p, lambda n: n, boxes) for p in parts]
    other = taken[0] if len(taken) == 1 else tree.Boolean("U", tuple(taken), location)
    return tree.Boolean("D", (node, other), location)


def element_tree(frame_tree: tree.FrameTree, element: Element, boxes: Boxes | None = None):
    """The CSG tree, in scene units, of the element's own solid (``boxes``:
    those of the frame's nodes, kept from one element to the next)."""
    boxes = Boxes() if boxes is None else boxes
    root = frame_tree.objects[element.object].root
    return _reach(root, element.address,
                  lambda node: _less_parts(node, element.parts, frame_tree.location, boxes), boxes)


def opening_tree(frame_tree: tree.FrameTree, opening: Opening):
    """The CSG tree of what the door or window took out: its solid where the
    first operand of the '$D' that subtracts it was (the wall's thickness deep)."""
    root = frame_tree.objects[opening.object].root
    cut = _node_at(root, opening.cut)
    cutter = _node_at(cut, opening.address[len(opening.cut):])
    block = tree.Boolean("I", (cutter, cut.operands[0]), cut.location)
    return _placed(root, opening.cut, block)


def _placed(node, address, replacement):
    """``replacement`` placed where the node at ``address`` is (only the
    transformations of the shared subtrees on the way count)."""
    if not address:
        return replacement
    if type(node) is tree.Use:
        return _wrap(node, _placed(node.shared.child, address[1:], replacement), "#place")
    return _placed(node.operands[address[0]], address[1:], replacement)


# --- spaces: rooms, not solids


def without_spaces(frame_tree: tree.FrameTree) -> tree.FrameTree:
    """The frame with every use of a ``space`` object taken out (its objects and
    shared subtrees rebuilt where they held one), the spaces in ``spaces``; a
    '>' object that was only a space is left out."""
    stripper = _Stripper(frame_tree.classes)
    objects = []
    for obj in frame_tree.objects:
        if obj.root is None:
            objects.append(obj)
            continue
        root = stripper.strip(obj.root, tree.IDENTITY)
        if root is not None or not stripper.has_space(obj.root):
            objects.append(obj if root is obj.root else tree.Object(obj.name, root, obj.where))
    return frame_tree.replace(objects=tuple(objects), spaces=tuple(stripper.spaces))


class _Stripper:
    """Takes the spaces out of a frame's trees, each shared subtree rebuilt once."""

    def __init__(self, declared):
        self.declared = declared
        self.holds: dict[str, bool] = {}
        self.rebuilt: dict[str, tree.Shared | None] = {}
        self.spaces: list[SpaceUse] = []

    def is_space(self, node) -> bool:
        if type(node) is not tree.Use:
            return False
        mark = self.declared.of(node.shared.location)
        return mark is not None and mark.role == "space"

    def has_space(self, node) -> bool:
        kind = type(node)
        if kind is tree.Use:
            key = node.shared.key
            if key not in self.holds:
                self.holds[key] = self.is_space(node) or (
                    node.shared.child is not None and self.has_space(node.shared.child))
            return self.holds[key]
        if kind is tree.Boolean:
            return any(self.has_space(o) for o in node.operands)
        if kind is tree.Smooth:
            return self.has_space(node.operand)
        return False

    def _note(self, node, placed) -> None:
        shared = node.shared
        self.spaces.append(SpaceUse(shared.name, self.declared.of(shared.location), placed,
                                    shared, _where(shared.location)))

    def strip(self, node, matrix):
        """``node`` without its spaces (None when nothing is left); ``matrix``
        places it in the scene."""
        if not self.has_space(node):
            return node
        kind = type(node)
        if kind is tree.Use:
            placed = tree.compose(matrix, node.matrix)
            shared = node.shared
            if self.is_space(node):
                self._note(node, placed)
                return None
            if shared.key not in self.rebuilt:
                child = self.strip(shared.child, placed)
                self.rebuilt[shared.key] = None if child is None else tree.Shared(
                    shared.name, child, tree.content_key(shared.name, child), shared.location)
            else:
                self.collect(shared.child, placed)
            new = self.rebuilt[shared.key]
            return None if new is None else tree.Use(node.matrix, node.path, new)
        if kind is tree.Smooth:
            operand = self.strip(node.operand, tree.compose(matrix, node.matrix))
            if operand is None:
                return None
            return tree.Smooth(node.angle, node.matrix, operand, node.tolerance,
                               tree.smooth_key(node.angle, node.tolerance, operand), node.location)
        return _boolean_of(node, [self.strip(o, matrix) for o in node.operands])

    def collect(self, node, matrix) -> None:
        """The spaces under a subtree already rebuilt (used again elsewhere)."""
        if not self.has_space(node):
            return
        kind = type(node)
        if kind is tree.Use:
            placed = tree.compose(matrix, node.matrix)
            if self.is_space(node):
                self._note(node, placed)
            elif node.shared.child is not None:
                self.collect(node.shared.child, placed)
        elif kind is tree.Smooth:
            self.collect(node.operand, tree.compose(matrix, node.matrix))
        elif kind is tree.Boolean:
            for o in node.operands:
                self.collect(o, matrix)


def _boolean_of(node: tree.Boolean, operands: list):
    """The boolean of what is left of its operands (None: empty), as the
    evaluator makes one (castor.csg.evaluate)."""
    if node.op == "D":
        if operands[0] is None:
            return None
        if operands[1] is None:
            return operands[0]
    elif node.op == "I" and any(o is None for o in operands):
        return None
    operands = [o for o in operands if o is not None]
    if not operands:
        return None
    if len(operands) == 1 and node.op != "D":
        return operands[0]
    return tree.Boolean(node.op, tuple(operands), node.location)

"""The evaluated CSG tree: the scene of one frame as plain, immutable, picklable data.

At each '>' (and each value of ``>[T = ...]``) the evaluator instantiates the
scene graph with the parameter values in force and gives one ``FrameTree``: its
objects, each the root of a tree of

- ``Primitive`` leaves: the kind, the evaluated shape arguments, the colour,
  the affine matrix from the primitive's unit space (the product of the
  transformations above it, up to the nearest shared subtree), the facet
  tolerance in the units of that subtree, the shape of the stretch above the
  subtree (the facet counts depend on it: castor.primitives.facets), and its
  path;
- ``Boolean`` nodes: the operator and the operands;
- ``Shared`` nodes: the subtree of a named object, made once for each set of
  parameter values and tolerance it reads and referenced from every place that
  uses it, with a canonical ``key`` computed from its content (never ``id()``),
  so that a facetizer in any process builds it once per key;
- ``Use`` nodes: one use of a shared subtree, with the matrix that places it
  and the path from the enclosing shared subtree down to it;
- ``Smooth`` nodes (``@s``, LANGUAGE.md §7.1): the operand's solid made the
  control mesh of a subdivision surface, in its own space, placed by a matrix.

Paths are relative to the nearest shared subtree above: a leaf's path holds
the boolean steps down to it (``U1.D2!cu``; the k-th operand of a boolean is
``U2``, ``I1``, ``D2``), a ``Use`` holds the steps down to the shared subtree
it places, and the subtree adds ``(name)``. ``leaves`` writes whole paths.

The nodes are plain classes (castor.records), not dataclasses: making these 7
frozen dataclasses cost about 6 ms of every start-up (issue 18). BLAKE2 and
struct are imported where a key is made: a scene without a named object or
``@s`` makes none.
"""

from __future__ import annotations

from typing import Iterator, Union

from castor.diagnostics import Location
from castor.records import Record

# A 3x4 affine matrix, row by row: (a, b, c, tx, d, e, f, ty, g, h, i, tz)
Matrix = tuple[float, ...]
IDENTITY: Matrix = (1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0)


class Primitive(Record):
    """One primitive placed in the frame, a leaf of the tree: ``kind`` names its
    declaration (a castor.primitives.PrimitiveKind, ``PRIMITIVES[kind]``)."""

    __slots__ = ("kind", "shape", "colour", "matrix", "tolerance", "metric", "path", "location")
    _compared = ("kind", "shape", "colour", "matrix", "tolerance", "metric", "path")

    def __init__(self, kind: str, shape: tuple[float, ...], colour: tuple[float, float, float],
                 matrix: Matrix, tolerance: float, metric: tuple[float, ...] | None, path: str,
                 location: Location):
        self.kind = kind  # "cu", "sp", ... (castor.primitives.PRIMITIVES)
        self.shape = shape  # the arguments after the colour
        self.colour = colour
        self.matrix = matrix
        self.tolerance = tolerance  # facet tolerance in the units its matrix maps into
        # how those units are stretched on the way to the scene's, up to a uniform
        # scale (folded into the tolerance) and a rotation: a 3x3 matrix row by row
        # (facets.stretch_above), None when not at all
        self.metric = metric
        self.path = path  # from the nearest shared subtree down: "U2!cy"
        self.location = location


class Boolean(Record):
    __slots__ = ("op", "operands", "location")
    _compared = ("op", "operands")

    def __init__(self, op: str, operands: tuple["TreeNode", ...], location: Location):
        self.op = op  # "U", "I" or "D"
        self.operands = operands
        self.location = location


class Shared(Record):
    """A named object's subtree, one object for each key however often it is used.

    Its key (``content_key``) is worked out when first asked (None given): the
    facetizer asks it, an analysis (``castor --check``, the language server)
    never does, and a subtree of 40,000 primitives takes a tenth of a second."""

    __slots__ = ("name", "child", "_key", "location")
    _compared = ("name", "child", "key")

    def __init__(self, name: str, child: "TreeNode | None", key: str | None,
                 location: Location):
        self.name = name
        self.child = child  # None: empty
        self._key = key  # a digest of the name and the content
        self.location = location

    @property
    def key(self) -> str:
        if self._key is None:
            self._key = content_key(self.name, self.child)
        return self._key

    def _fields(self) -> tuple[str, ...]:
        return ("name", "child", "key", "location")

    def __hash__(self) -> int:
        return hash(self.key)

    def __eq__(self, other) -> bool:
        return isinstance(other, Shared) and other.key == self.key


class Use(Record):
    __slots__ = ("matrix", "path", "shared")

    def __init__(self, matrix: Matrix, path: str, shared: Shared):
        self.matrix = matrix
        self.path = path  # the boolean steps from the enclosing shared subtree: "U2"
        self.shared = shared


class Smooth(Record):
    """``@s(angle)``: the operand (evaluated in its own space, the matrices
    above it in ``matrix``) smoothed with the facet tolerance in its units;
    ``key`` is a digest of all three, so that one smoothing serves every use."""

    __slots__ = ("angle", "matrix", "operand", "tolerance", "key", "location")
    _compared = ("angle", "matrix", "operand", "tolerance", "key")

    def __init__(self, angle: float, matrix: Matrix, operand: "TreeNode", tolerance: float,
                 key: str, location: Location):
        self.angle = angle  # degrees: an edge whose normals turn by more is a crease
        self.matrix = matrix
        self.operand = operand
        self.tolerance = tolerance
        self.key = key
        self.location = location


TreeNode = Union[Primitive, Boolean, Use, Smooth]


class Object(Record):
    """One object of a '>' command: a name (that of its named object, or
    ``objectK``) and its tree (None when it is empty)."""

    __slots__ = ("name", "root", "where")

    def __init__(self, name: str, root: TreeNode | None, where: str = ""):
        self.name = name
        self.root = root
        self.where = where  # FILE:LINE of its definition (a named object's) or of the '>' command


class FrameTree(Record):
    """The scene of one frame: what a facetizer, a ray tracer or a drawing needs."""

    __slots__ = ("number", "where", "location", "objects", "parameters", "classes", "spaces")

    def __init__(self, number: int, where: str, location: Location, objects: tuple[Object, ...],
                 parameters: tuple[tuple[str, float], ...] = (), classes=None,
                 spaces: tuple = ()):
        self.number = number
        self.where = where  # FILE:LINE of the '>' command
        self.location = location
        self.objects = objects
        self.parameters = parameters  # the values in force at the '>' (not PI)
        # what the scene's annotations declare (castor.language.classes.Declared),
        # None without any: LANGUAGE.md §11, read by castor.csg.elements
        self.classes = classes
        # the rooms (castor.csg.elements.SpaceUse) taken out of the objects: a
        # space is not a solid to build
        self.spaces = spaces

    def shared(self) -> dict[str, Shared]:
        """Every shared subtree of the frame, by key."""
        found: dict[str, Shared] = {}
        for obj in self.objects:
            if obj.root is not None:
                _collect_shared(obj.root, found)
        return found


def _collect_shared(node: TreeNode, found: dict[str, Shared]) -> None:
    stack = [node]
    while stack:
        node = stack.pop()
        if isinstance(node, Use):
            shared = node.shared
            if shared.key in found:
                continue
            found[shared.key] = shared
            if shared.child is not None:
                stack.append(shared.child)
        elif isinstance(node, Boolean):
            stack.extend(node.operands)
        elif isinstance(node, Smooth):
            stack.append(node.operand)


def leaves(node: TreeNode, matrix: Matrix = IDENTITY, prefix: str = "") -> Iterator[tuple[Primitive, Matrix, str]]:
    """Every primitive under ``node`` with its matrix to the scene and its full
    path from ``node``, shared subtrees expanded (as many times as they are used)."""
    from castor.csg.paths import join

    stack = [(node, matrix, prefix)]
    while stack:
        node, m, p = stack.pop()
        if isinstance(node, Primitive):
            yield node, compose(m, node.matrix), join((p, node.path))
        elif isinstance(node, Boolean):
            stack.extend((operand, m, p) for operand in reversed(node.operands))
        elif isinstance(node, Use) and node.shared.child is not None:
            stack.append((node.shared.child, compose(m, node.matrix),
                          join((p, node.path, f"({node.shared.name})"))))
        elif isinstance(node, Smooth):
            stack.append((node.operand, compose(m, node.matrix), p))


def compose(a: Matrix, b: Matrix) -> Matrix:
    """The matrix of applying ``b`` then ``a``."""
    if b is IDENTITY or b == IDENTITY:
        return a
    if a is IDENTITY or a == IDENTITY:
        return b
    a0, a1, a2, a3, a4, a5, a6, a7, a8, a9, a10, a11 = a
    b0, b1, b2, b3, b4, b5, b6, b7, b8, b9, b10, b11 = b
    return (a0 * b0 + a1 * b4 + a2 * b8, a0 * b1 + a1 * b5 + a2 * b9,
            a0 * b2 + a1 * b6 + a2 * b10, a0 * b3 + a1 * b7 + a2 * b11 + a3,
            a4 * b0 + a5 * b4 + a6 * b8, a4 * b1 + a5 * b5 + a6 * b9,
            a4 * b2 + a5 * b6 + a6 * b10, a4 * b3 + a5 * b7 + a6 * b11 + a7,
            a8 * b0 + a9 * b4 + a10 * b8, a8 * b1 + a9 * b5 + a10 * b9,
            a8 * b2 + a9 * b6 + a10 * b10, a8 * b3 + a9 * b7 + a10 * b11 + a11)


def placed_box(matrix: Matrix, low, high) -> tuple[tuple, tuple]:
    """The smallest box holding the box (``low``, ``high``) moved by the affine
    ``matrix``: per row, the translation plus each term's smaller or larger end."""
    if matrix is IDENTITY or matrix == IDENTITY:
        return tuple(low), tuple(high)
    lows, highs = [], []
    for row in range(0, 12, 4):
        smallest = largest = matrix[row + 3]
        for axis in range(3):
            h = matrix[row + axis]
            a, b = h * low[axis], h * high[axis]
            if a > b:
                a, b = b, a
            smallest += a
            largest += b
        lows.append(smallest)
        highs.append(largest)
    return tuple(lows), tuple(highs)


def _blake2b():
    """A 16-byte BLAKE2b: hashlib's own module, without hashlib's OpenSSL set-up
    (about 12 ms of a run whose scene names an object)."""
    try:
        from _blake2 import blake2b
    except ImportError:
        from hashlib import blake2b
    return blake2b(digest_size=16)


def smooth_key(angle: float, tolerance: float, operand: TreeNode) -> str:
    """The key of a smoothing: its angle, tolerance and operand's content."""
    import struct

    digest = _blake2b()
    digest.update(struct.pack("<2d", angle, tolerance))
    _feed(digest, operand)
    return digest.hexdigest()


def content_key(name: str, child: TreeNode | None) -> str:
    """The canonical key of a shared subtree: a digest of its name and content,
    the same in every process (shared subtrees below count by their own keys)."""
    digest = _blake2b()
    digest.update(name.encode())
    if child is not None:
        _feed(digest, child)
    return digest.hexdigest()


def _feed(digest, node: TreeNode) -> None:
    """Feed the content of the tree under ``node`` to ``digest``. The bytes are
    gathered and handed over in blocks (a digest of the whole is that of its
    parts fed in turn): a subtree of 40,000 primitives costs a loop, not 120,000
    calls of the digest."""
    import struct

    pack_matrix = struct.Struct("<12d").pack
    packs: dict[int, object] = {}  # the packing of n doubles, by n
    stack = [node]
    parts: list[bytes] = []
    add = parts.append
    while stack:
        node = stack.pop()
        kind = type(node)
        if kind is Primitive:
            count = len(node.shape) + 4
            pack = packs.get(count)
            if pack is None:
                pack = packs[count] = struct.Struct(f"<{count}d").pack
            add(b"P" + node.kind.encode() + node.path.encode() + b"\0")
            add(pack(*node.shape, *node.colour, node.tolerance))
            add(pack_matrix(*node.matrix))
            if node.metric is not None:
                add(b"M" + struct.pack("<9d", *node.metric))
        elif kind is Boolean:
            add(f"B{node.op}{len(node.operands)}".encode())
            stack.extend(reversed(node.operands))
        elif kind is Smooth:  # the operand by the smoothing's own key
            add(b"M" + node.key.encode())
            add(pack_matrix(*node.matrix))
        else:  # a Use: its place, and the shared subtree by its own key
            add(b"S" + node.path.encode() + b"\0" + node.shared.key.encode())
            add(pack_matrix(*node.matrix))
        if len(parts) >= 4096:
            digest.update(b"".join(parts))
            parts.clear()
    if parts:
        digest.update(b"".join(parts))


def dump(tree: FrameTree) -> str:
    """The tree as indented text, shared subtrees written once: for tests and
    for reading what a frame is made of."""
    lines: list[str] = [f"frame {tree.number} {tree.where}"]
    written: set[str] = set()

    def number(x: float) -> str:
        return repr(x) if x != int(x) or abs(x) >= 1e15 else str(int(x))

    def walk(node: TreeNode, depth: int, label: str) -> None:
        pad = "  " * depth
        if isinstance(node, Primitive):
            m = "" if node.matrix == IDENTITY else " @m(" + ", ".join(map(number, node.matrix)) + ")"
            shape = "" if not node.shape else ", " + ", ".join(map(number, node.shape))
            colour = ", ".join(map(number, node.colour))
            stretch = "" if node.metric is None else " s=(" + ", ".join(map(number, node.metric)) + ")"
            lines.append(f"{pad}{label}{node.path}{m} !{node.kind}({colour}{shape}) "
                         f"t={node.tolerance:g}{stretch}")
        elif isinstance(node, Boolean):
            lines.append(f"{pad}{label}${node.op}")
            for operand in node.operands:
                walk(operand, depth + 1, "")
        elif isinstance(node, Smooth):
            m = "" if node.matrix == IDENTITY else " @m(" + ", ".join(map(number, node.matrix)) + ")"
            lines.append(f"{pad}{label}@s({number(node.angle)}){m} t={node.tolerance:g}")
            walk(node.operand, depth + 1, "")
        else:
            shared = node.shared
            m = "" if node.matrix == IDENTITY else " @m(" + ", ".join(map(number, node.matrix)) + ")"
            head = f"{pad}{label}{node.path}({shared.name}){m} #{shared.key[:8]}"
            if shared.key in written:
                lines.append(head + " (as above)")
                return
            written.add(shared.key)
            lines.append(head)
            if shared.child is not None:
                walk(shared.child, depth + 1, "")

    for obj in tree.objects:
        lines.append(f"object {obj.name}")
        if obj.root is not None:
            walk(obj.root, 1, "")
    return "\n".join(lines) + "\n"

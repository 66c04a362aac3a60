"""Gestures that write text: Place and Move as the smallest edits of the
scene, Measure from the exact solids (CLI.md, "Editing on screen").

Each edit is a list of ``(file, TextEdit)``: comments and layout are left as
they are, numbers written short (castor.editing.text.short), no line is
added (a frame's header and messages name its line), and nothing else
changes. Place writes a new named object just before the '>' command of the
frame shown, on its line, and adds it to that command's list (or to a chosen
object's ``$U``, written before that object's definition); Move changes the literal numbers of the ``@t`` written directly in
front of the use moved, or writes ``@t(DX, DY, DZ)`` in front of it, never
an expression. A use whose text is evaluated several times in the frame (in
an object used twice) is moved by the use of that object instead, so that
only what was under the cursor moves; one inside a repetition is refused.
"""

from __future__ import annotations

import math
import re

from castor.csg import tree
from castor.editing.document import CommandError, Document
from castor.editing.places import Place, atom, container_text, segments, uses, walk
from castor.editing.text import TextEdit, insertion, number_at, replacement, short
from castor.language.scene import BooleanNode, NamedNode, PrimitiveNode, TransformedNode

Edits = list  # of (path, TextEdit)

# the name a placed object takes from its primitive, numbered to be unique
NAMES = {"cu": "bloc", "cy": "poteau", "co": "cone", "sp": "boule", "to": "tore",
         "pr": "prisme", "py": "pyramide", "we": "coin", "ex": "profil", "rv": "tour"}
DEFAULT_COLOUR = (0.8, 0.8, 0.8)
_OBJECT_NAME = re.compile(r"[a-z][A-Za-z0-9_]*\Z")


# --- Place

def place(document: Document, frame_number: int, kind: str, extra: tuple, at, size,
          colour=DEFAULT_COLOUR, name: str | None = None, into: str | None = None) -> Edits:
    """A new object: the primitive ``kind`` (with its ``extra`` arguments) filling
    the box from ``at`` to ``at + size``, written before the '>' of the frame
    and added to its list, or to the ``$U`` of the object ``into``."""
    from castor.diagnostics import CastorError, Location
    from castor.primitives import PRIMITIVES

    frame = document.frame(frame_number)
    declared = PRIMITIVES.get(kind)
    if declared is None:
        raise CommandError(f"unknown primitive '!{kind}' (known: "
                           + ", ".join("!" + k for k in PRIMITIVES) + ")")
    shape = tuple(float(v) for v in extra)
    wanted = len(declared.arguments)
    if len(shape) < wanted or (not declared.pairs and len(shape) != wanted) or \
            (declared.pairs and (len(shape) - wanted < 6 or (len(shape) - wanted) % 2)):
        raise CommandError(f"'!{kind}' takes {declared.form} (the colour given apart)")
    try:
        if declared.check is not None:
            declared.check(shape, Location("<place>", 1, 1), f"!{kind}")
    except CastorError as error:
        raise CommandError(error.message) from None
    low = [min(a, a + s) for a, s in zip(at, size)]
    extent = [abs(s) for s in size]
    if any(s == 0 for s in extent):
        raise CommandError("the box has a size of zero: give three sizes that are not 0")
    name = _new_name(document, kind, name)
    facetize = document.facetize(frame)
    offset = (0.0, 0.0, 0.0)
    if into is not None:
        offset = _into_offset(document, frame, into)
    unit_low, unit_high = declared.box(shape)
    scale = [e / (h - l) for e, l, h in zip(extent, unit_low, unit_high)]
    move = [lo - o - ul * k for lo, o, ul, k in zip(low, offset, unit_low, scale)]
    numbers = ", ".join(short(v) for v in (*colour, *shape))
    line = (f"{name} = @t({', '.join(short(v) for v in move)}) "
            f"@h({', '.join(short(v) for v in scale)}) !{kind}({numbers});")
    if into is None:
        before, listing = facetize, container_text(document, facetize)
    else:
        target = _container_named(document, frame, into)
        before, listing = document.definition(target), container_text(document, target.child)
    edits = [_before_statement(document, before.location, line)]
    last = listing.operands[-1]
    edits.append((listing.path, insertion(listing.text, last.end, f", {name}")))
    return edits


def _new_name(document: Document, kind: str, chosen: str | None) -> str:
    written = set()
    for path in {document.path, *(document.file_of(d.location) for d in document.statements)}:
        text = document.file_text(path) or ""
        written.update(re.findall(r"[A-Za-z_]\w*", text))
    if chosen is not None:
        if not isinstance(chosen, str) or not _OBJECT_NAME.match(chosen):
            raise CommandError(f"'{chosen}' is not an object name (a lowercase letter, then "
                               "letters, digits or '_')")
        if chosen in written or chosen in document.objects:
            raise CommandError(f"the name '{chosen}' is already used in the scene")
        return chosen
    base = NAMES.get(kind, kind)
    number = 1
    while f"{base}{number}" in written or f"{base}{number}" in document.objects:
        number += 1
    return f"{base}{number}"


def _before_statement(document: Document, location, line: str) -> tuple[str, TextEdit]:
    """``line`` written just before the statement at ``location``, on its line:
    no line moves, so every other frame (its '>' line, its messages) is the same."""
    path, text, start = document.offset_of(location)
    return path, insertion(text, start, line + " ")


def _named_in_frame(document: Document, frame, name: str):
    """The named node called ``name`` that the frame uses."""
    statement = document.facetize(frame)
    stack = list(statement.objects)
    seen = set()
    while stack:
        node = atom(stack.pop())
        if id(node) in seen:
            continue
        seen.add(id(node))
        if isinstance(node, NamedNode):
            if node.name == name:
                return node
            stack.append(node.child)
        elif isinstance(node, BooleanNode):
            stack.extend(node.operands)
    return None


def _container_named(document: Document, frame, name: str) -> NamedNode:
    node = _named_in_frame(document, frame, name)
    if node is None:
        raise CommandError(f"frame {frame.number} has no object '{name}' to place into")
    child = node.child
    if not isinstance(child, BooleanNode) or child.op != "U" or child.repeat is not None:
        raise CommandError(f"'{name}' is not a $U(...) of objects: a new object can only be "
                           f"added to a union (write '{name} = $U(...)' first)")
    return node


def _into_offset(document: Document, frame, name: str) -> tuple[float, float, float]:
    """Where the object ``name`` is placed in the frame: the box given in the
    scene is written in its own coordinates."""
    _container_named(document, frame, name)
    matrices: list = []
    for obj in frame.objects:
        if obj.root is not None:
            _shared_uses(obj.root, name, tree.IDENTITY, matrices, [])
    if len(matrices) != 1:
        raise CommandError(f"'{name}' is used {len(matrices)} times in frame {frame.number}: "
                           f"an object placed into it would appear as many times")
    m = matrices[0]
    if (m[0], m[1], m[2], m[4], m[5], m[6], m[8], m[9], m[10]) != (1, 0, 0, 0, 1, 0, 0, 0, 1):
        raise CommandError(f"'{name}' is turned or scaled where frame {frame.number} uses it: "
                           f"place the object in the frame's list instead")
    return m[3], m[7], m[11]


# --- Move

def move(document: Document, frame_number: int, source: str, by, path: str | None = None
         ) -> Edits:
    """Move the use at ``source`` (a primitive's or an object's ``FILE:LINE:COL``;
    ``path`` says which use when there are several) by ``by`` in the scene."""
    frame = document.frame(frame_number)
    if all(v == 0 for v in by):
        return []
    facetize = document.facetize(frame)
    places, index = _source_places(document, frame, facetize, source, path)
    index = _moved_place(document, frame, places, index)
    outer = _outer_linear(places[:index], dict(frame.parameters))
    local = _solve(outer, by)
    return _translate(document, places[index], local)


def _source_places(document: Document, frame, facetize, source: str, path: str | None):
    """The places down to the use at ``source`` along ``path`` (or the one path
    that has it), and the index of that use's place."""
    found: dict[tuple, tuple] = {}
    candidates = [path] if path is not None else _paths(frame)
    for full in candidates:
        steps = segments(full)
        if steps is None:
            raise CommandError(f"'{full}' is not a path (as snap gives it: (name).U2!cu)")
        for k, expr in enumerate(facetize.objects, 1):
            places = walk(expr, facetize, k, steps)
            if places is None:
                continue
            index = _index_of(document, places, source)
            if index is not None:
                key = (k, tuple(steps[:places[index].consumed]), index)
                found.setdefault(key, (places, index))
    if not found:
        where = f" along the path {path}" if path is not None else ""
        raise CommandError(f"no primitive or object use of frame {frame.number} is written at "
                           f"{source}{where}")
    if len(found) > 1:
        raise CommandError(f"what is written at {source} is used {len(found)} times in frame "
                           f"{frame.number}: give the path of the one to move (as snap gives it)")
    return next(iter(found.values()))


def _paths(frame) -> list[str]:
    paths = []
    for obj in frame.objects:
        if obj.root is not None:
            paths.extend(path for _, _, path in tree.leaves(obj.root))
    return list(dict.fromkeys(paths))


def _index_of(document: Document, places: list[Place], source: str) -> int | None:
    for index in range(len(places) - 1, -1, -1):
        node = places[index].node
        inner = atom(node)
        if isinstance(node, (TransformedNode, PrimitiveNode)) and \
                document.source(node.location) == source:
            return index
        if isinstance(inner, PrimitiveNode) and document.source(inner.location) == source:
            return index
        if isinstance(inner, NamedNode) and document.source(inner.location) == source:
            return index
    return None


def _moved_place(document: Document, frame, places: list[Place], index: int) -> int:
    """The place that takes the move: ``index``, or the use of the object around
    it when that object is used several times in the frame."""
    counts = uses(frame)
    while True:
        body = max((j for j in range(index + 1) if isinstance(places[j].container, NamedNode)
                    and places[j].index == 0), default=-1)
        for j in range(body + 1, index + 1):
            if places[j].repeat is not None:
                container = places[j].container
                raise CommandError(
                    f"{document.source(container.location)}: this is one of the copies a "
                    f"repetition makes; moving it would move every copy: move the object "
                    f"that holds the repetition, or change the repetition by hand")
        if body < 0 or counts[places[body].container.name] <= 1:
            return index
        index = body - 1


def _outer_linear(places: list[Place], env: dict) -> list[list[float]]:
    """The linear part of the transformations above a place, in the frame."""
    from castor.csg.evaluate import repeat_values
    from castor.diagnostics import CastorError
    from castor.language.expressions import evaluate
    from castor.transformations import step_matrix

    env.setdefault("PI", math.pi)
    matrix = tree.IDENTITY
    try:
        for place in places:
            if place.repeat is not None:
                repeat = place.container.repeat
                env[repeat.param] = repeat_values(repeat, env)[place.repeat - 1]
            if isinstance(place.node, TransformedNode):
                for step in place.node.steps:
                    if step.kind in ("f", "s"):
                        continue
                    values = [evaluate(arg, env) for arg in step.args]
                    matrix = tree.compose(matrix, step_matrix(step.kind, values, step.location,
                                                              "")[0])
    except CastorError as error:
        raise CommandError(error.message) from None
    return [list(matrix[0:3]), list(matrix[4:7]), list(matrix[8:11])]


def _solve(linear, by) -> tuple[float, float, float]:
    import numpy as np

    a = np.array(linear, dtype=np.float64)
    if abs(np.linalg.det(a)) < 1e-12:
        raise CommandError("the object is flattened where it is used: it cannot be moved")
    if np.allclose(a, np.eye(3), rtol=0, atol=0):
        return tuple(float(v) for v in by)
    return tuple(float(v) for v in np.linalg.solve(a, np.asarray(by, np.float64)))


def _translate(document: Document, place: Place, by) -> Edits:
    written = container_text(document, place.container)
    operand = written.operands[place.index - 1 if place.index else 0]
    literal = _literal_translation(operand)
    if literal is not None and isinstance(place.node, TransformedNode) and \
            place.node.steps[0].kind == "t":
        edits = []
        for (value, start, end), delta in zip(literal, by):
            new = short(value + delta)
            if delta != 0 and new != written.text[start:end]:
                edits.append((written.path, replacement(written.text, start, end, new)))
        return edits
    text = f"@t({', '.join(short(v) for v in by)}) "
    return [(written.path, insertion(written.text, operand.start, text))]


def _literal_translation(operand) -> list[tuple[float, int, int]] | None:
    """The three numbers of an ``@t`` written first in the operand, when each is
    a number as written (a sign allowed), with their spans; None otherwise."""
    ahead = operand.tokens
    if len(ahead) < 2 or ahead[0].text != "@t" or ahead[1].text != "(":
        return None
    found, k = [], 2
    for separator in (",", ",", ")"):
        number = number_at(ahead, k)
        if number is None:
            return None
        value, start, end, k = number
        if k >= len(ahead) or ahead[k].text != separator:
            return None
        found.append((value, start, end))
        k += 1
    return found


# --- Measure

def distance(first, second) -> dict:
    dx, dy, dz = (float(b) - float(a) for a, b in zip(first, second))
    return {"distance": math.sqrt(dx * dx + dy * dy + dz * dz), "dx": dx, "dy": dy, "dz": dz}


def object_figures(document: Document, frame_number: int, name: str) -> dict:
    """An object's volume and bounding box in the frame: one of the '>' objects, or
    a named object it uses (placed where it is used, when used once)."""
    from castor.mesh.facetize import Facetizer
    from castor.quantities import frame_figures

    frame = document.frame(frame_number)
    chosen = [obj for obj in frame.objects if obj.name == name and obj.root is not None]
    if not chosen:
        matrices: list = []
        roots: list = []
        for obj in frame.objects:
            if obj.root is not None:
                _shared_uses(obj.root, name, tree.IDENTITY, matrices, roots)
        if not roots:
            raise CommandError(f"frame {frame.number} has no object '{name}'")
        matrix = matrices[0] if len(matrices) == 1 else tree.IDENTITY
        chosen = [tree.Object(name, tree.Use(matrix, "", roots[0]))]
    single = tree.FrameTree(frame.number, frame.where, frame.location, tuple(chosen[:1]),
                            frame.parameters)
    figures = frame_figures(Facetizer().frame(single))[0]
    return {"name": name, "volume": figures.volume, "area": figures.area,
            "box": [list(corner) for corner in figures.bbox] if figures.bbox else None}


def _shared_uses(node, name: str, matrix, matrices: list, roots: list) -> None:
    if isinstance(node, tree.Use):
        placed = tree.compose(matrix, node.matrix)
        if node.shared.name == name:
            matrices.append(placed)
            roots.append(node.shared)
        elif node.shared.child is not None:
            _shared_uses(node.shared.child, name, placed, matrices, roots)
    elif isinstance(node, tree.Boolean):
        for operand in node.operands:
            _shared_uses(operand, name, matrix, matrices, roots)
    elif isinstance(node, tree.Smooth):
        _shared_uses(node.operand, name, tree.compose(matrix, node.matrix), matrices, roots)


def face_area(document: Document, frame_number: int, origin, direction) -> dict:
    """The area of the face a ray meets: a flat face of the evaluated solid (every
    polygon of the frame in its plane, joined to the one under the ray), exact;
    a curved face, its facets' (within the facet tolerance)."""
    import numpy as np

    from castor.editing.snap import face_at

    found = face_at(document.prepared(frame_number), origin, direction)
    if found is None:
        raise CommandError("the ray meets no face")
    point, number, plane = found
    source, path = document.prepared(frame_number).named(number)
    size = document.prepared(frame_number).solids.size
    for obj in document.mesh(frame_number).objects:
        polygons = _polygons(obj)
        if polygons is None:
            continue
        areas, normals, offsets, corners = polygons
        if plane is not None:
            on = (normals @ plane[0] > 1 - 1e-6) & (np.abs(offsets - plane[1]) < 1e-6 * size)
        else:
            on = np.array([str(obj.origins[k].steps) == path for k in obj.origin_of])
        under = [k for k in np.flatnonzero(on) if _holds(obj, k, point, normals[k], size)]
        if not under:
            continue
        if plane is None and obj.surface_of is not None:
            on &= obj.surface_of == obj.surface_of[under[0]]
        chosen = _joined(obj, np.flatnonzero(on), under[0])
        return {"area": float(areas[chosen].sum()), "exact": plane is not None,
                "source": source, "path": path}
    raise CommandError("the face under the ray was not found in the frame's polygons")


def _polygons(obj):
    """Each polygon's area, unit normal, offset along it, and first corner."""
    import numpy as np

    if obj.polygon_count == 0:
        return None
    start = obj.offsets[:-1]
    following = np.arange(1, len(obj.indices) + 1)
    following[obj.offsets[1:] - 1] = start
    a = obj.vertices[obj.indices]
    b = obj.vertices[obj.indices[following]]
    vector = np.add.reduceat(np.cross(a, b), start) / 2
    areas = np.linalg.norm(vector, axis=1)
    normals = vector / np.where(areas > 0, areas, 1)[:, None]
    corners = obj.vertices[obj.indices[start]]
    return areas, normals, np.einsum("ij,ij->i", normals, corners), corners


def _holds(obj, k: int, point, normal, size: float) -> bool:
    """Whether the convex polygon ``k`` holds the point (on its plane, within rounding)."""
    import numpy as np

    ring = obj.vertices[obj.indices[obj.offsets[k]:obj.offsets[k + 1]]]
    if abs((point - ring[0]) @ normal) > 1e-3 * size:
        return False
    sides = np.roll(ring, -1, axis=0) - ring
    return bool(np.all(np.cross(sides, point - ring) @ normal >= -1e-9 * size * size))


def _joined(obj, candidates, first: int) -> list[int]:
    """The polygons among ``candidates`` joined to ``first`` through shared corners."""
    corners = {k: set(obj.indices[obj.offsets[k]:obj.offsets[k + 1]].tolist())
               for k in candidates}
    by_vertex: dict[int, list[int]] = {}
    for k, ring in corners.items():
        for v in ring:
            by_vertex.setdefault(v, []).append(k)
    seen, stack = {first}, [first]
    while stack:
        for v in corners[stack.pop()]:
            for k in by_vertex[v]:
                if k not in seen:
                    seen.add(k)
                    stack.append(k)
    return sorted(seen)

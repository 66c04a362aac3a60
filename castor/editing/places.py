"""Where an object of a frame is written: from a path (LANGUAGE.md §8) to the
places of the text it passes through.

A *place* is an expression as written: an object of a '>' command, an
operand of a boolean, or the body of an object definition. The path of a
primitive in a frame, ``(maison).U2(murs).D1!cu``, goes down through a chain
of them; a gesture edits one. ``walk`` follows a path through the scene
graph; ``spans`` finds, by reading the text as written (castor.editing.text),
where each operand of a place's container starts and ends, so that a
translation is put in front of the right one and a name added at the end of
the right list; ``uses`` counts how often each named object is used in a
frame, since text inside an object used twice moves both.
"""

from __future__ import annotations

import re
from collections import Counter
from typing import NamedTuple

from castor.csg import tree
from castor.editing.document import CommandError, Document
from castor.editing.text import Token, tokens
from castor.language.scene import (BooleanNode, FrameCommand, NamedNode, PrimitiveNode,
                                   TransformedNode)

_SEGMENT = re.compile(r"\(([a-z]\w*)\)|\.?([UID])(\d+)|!([a-z]\w*)")


class Place(NamedTuple):
    node: object  # the expression written there: a TransformedNode or an atom
    container: object  # the FrameCommand, BooleanNode or NamedNode (a definition's body) it is in
    index: int  # its operand number (1-based) in the container; 0 for a body
    repeat: int | None  # for the body of a repetition, which of its values (1-based)
    consumed: int  # the path's segments passed to reach it


def atom(node):
    return node.child if isinstance(node, TransformedNode) else node


def segments(path: str) -> list[tuple] | None:
    """A path's steps: ("named", name), (op, k) or ("primitive", kind); None if malformed."""
    out, at = [], 0
    while at < len(path):
        match = _SEGMENT.match(path, at)
        if match is None:
            return None
        name, op, k, kind = match.groups()
        out.append(("named", name) if name else (op, int(k)) if op else ("primitive", kind))
        at = match.end()
    return out


def walk(expr, container, index: int, steps: list[tuple]) -> list[Place] | None:
    """The places from a frame's object down the path ``steps``, to its primitive
    (or, when the path ends at a named object, to the place that uses it)."""
    places = [Place(expr, container, index, None, 0)]
    node, k = atom(expr), 0
    while True:
        if k == len(steps):
            return places if isinstance(node, NamedNode) and steps and steps[-1][0] == "named" \
                else None
        step = steps[k]
        if isinstance(node, NamedNode):
            if step != ("named", node.name):
                return None
            k += 1
            if k == len(steps):
                return places
            places.append(Place(node.child, node, 0, None, k))
            node = atom(node.child)
        elif isinstance(node, BooleanNode):
            if step[0] != node.op:
                return None
            k += 1
            if node.repeat is not None:
                operand, repeat, position = node.operands[0], step[1], 1
            elif 1 <= step[1] <= len(node.operands):
                operand, repeat, position = node.operands[step[1] - 1], None, step[1]
            else:
                return None
            places.append(Place(operand, node, position, repeat, k))
            node = atom(operand)
        elif isinstance(node, PrimitiveNode):
            return places if step == ("primitive", node.kind) and k == len(steps) - 1 else None
        else:
            return None


def uses(frame: tree.FrameTree) -> Counter:
    """How many times each named object is used in the frame (its uses in the
    objects used, multiplied out)."""
    local: dict[str, Counter] = {}
    names: dict[str, str] = {}

    def scan(node) -> Counter:
        found: Counter = Counter()
        stack = [node]
        while stack:
            node = stack.pop()
            if isinstance(node, tree.Use):
                found[node.shared.key] += 1
                names[node.shared.key] = node.shared.name
                if node.shared.key not in local:
                    local[node.shared.key] = Counter()  # reserved, filled below
                    local[node.shared.key] = scan(node.shared.child) \
                        if node.shared.child is not None else Counter()
            elif isinstance(node, tree.Boolean):
                stack.extend(node.operands)
            elif isinstance(node, tree.Smooth):
                stack.append(node.operand)
        return found

    roots: Counter = Counter()
    for obj in frame.objects:
        if obj.root is not None:
            roots.update(scan(obj.root))
    order: list[str] = []
    seen: set[str] = set()

    def visit(key: str) -> None:
        stack = [(key, iter(local[key]))]
        seen.add(key)
        while stack:
            current, children = stack[-1]
            child = next(children, None)
            if child is None:
                order.append(current)
                stack.pop()
            elif child not in seen:
                seen.add(child)
                stack.append((child, iter(local[child])))

    for key in roots:
        if key not in seen:
            visit(key)
    times = Counter(roots)
    for key in reversed(order):  # each subtree after every one that uses it
        for child, count in local[key].items():
            times[child] += times[key] * count
    by_name: Counter = Counter()
    for key, count in times.items():
        by_name[names[key]] += count
    return by_name


class Operand(NamedTuple):
    start: int
    end: int
    tokens: list[Token]


class Written(NamedTuple):
    """A container's text: its file, the text, its operands and the token that
    closes their list (the ';' of a statement, the ')' of a boolean)."""

    path: str
    text: str
    operands: list[Operand]
    closing: Token


def container_text(document: Document, container) -> Written:
    """Where a container's operands are written; CommandError where macros
    write them (then the text does not show them one by one)."""
    location = container.location
    path, text, start = document.offset_of(location)
    ahead = tokens(text, start)
    first = next(ahead, None)
    if isinstance(container, FrameCommand):
        expected, opening, closing, count = ">", None, ";", len(container.objects)
    elif isinstance(container, BooleanNode):
        expected, opening, closing = f"${container.op}", "(", ")"
        count = 1 if container.repeat is not None else len(container.operands)
    else:
        expected, opening, closing, count = container.name, "=", ";", 1
    if first is None or first.text != expected:
        raise CommandError(f"{location}: the text there is not what the scene was made of "
                           f"(a macro?): '{expected}' expected")
    token = next(ahead, None)
    if token is not None and token.text == "[" and not isinstance(container, NamedNode):
        token = _skip_brackets(ahead)
    if opening is not None:
        if token is None or token.text != opening:
            raise CommandError(f"{location}: '{opening}' expected after '{expected}'")
        token = next(ahead, None)
    operands: list[Operand] = []
    current: list[Token] = []
    depth = 0
    while token is not None:
        if depth == 0 and token.text in (",", closing):
            if current:
                operands.append(Operand(current[0].start, current[-1].end, current))
            current = []
            if token.text == closing:
                break
        else:
            depth += token.text in "([" and token.kind == "mark"
            depth -= token.text in ")]" and token.kind == "mark"
            current.append(token)
        token = next(ahead, None)
    if token is None or len(operands) != count:
        raise CommandError(f"{location}: its operands are written with macros or "
                           f"directives; edit it by hand")
    return Written(path, text, operands, token)


def _skip_brackets(ahead) -> Token | None:
    depth = 1
    for token in ahead:
        if token.text == "[":
            depth += 1
        elif token.text == "]":
            depth -= 1
            if depth == 0:
                return next(ahead, None)
    return None

"""The oracle's scenes as Python structures (parameters, named objects, nested
transformations, booleans, repetitions, smooth solids, frames) and their
Castor text, which castor reads."""

from __future__ import annotations

import re
from dataclasses import dataclass, field


# --- the scene as a structure -----------------------------------------------

@dataclass(frozen=True)
class Param:
    """coefficient * NAME + constant, printed as an expression for castor."""
    name: str
    coefficient: float
    constant: float


@dataclass(frozen=True)
class Prim:
    kind: str  # cu pr py we ex
    colour: tuple
    args: tuple  # N for pr/py; x1, y1, ... for ex


@dataclass(frozen=True)
class Tf:
    steps: tuple  # (kind, args): t rx ry rz r h m
    child: object


@dataclass(frozen=True)
class Bool:
    op: str  # U I D
    children: tuple


@dataclass(frozen=True)
class Rep:
    op: str  # U I
    param: str
    count: int
    child: object  # uses param


@dataclass(frozen=True)
class Ref:
    name: str


@dataclass(frozen=True)
class Smooth:
    """``@s(angle) child`` (--smooth): over one primitive (perhaps transformed)
    the oracle makes the smooth solid itself (reference_subdivision.py);
    over anything else the frame is judged for its surface only."""
    angle: float
    child: object


@dataclass
class Scene:
    statements: list = field(default_factory=list)  # ("param", n, v) ("object", n, node) ("frame", [nodes])

    def frames(self) -> int:
        return sum(1 for s in self.statements if s[0] == "frame")


# --- printing for castor ----------------------------------------------------

def number(x: float) -> str:
    text = repr(float(x))
    return text if x >= 0 else f"({text})"


def expression(value) -> str:
    if isinstance(value, Param):
        return f"({number(value.coefficient)} * {value.name} + {number(value.constant)})"
    return number(value)


def text(node) -> str:
    if isinstance(node, Prim):
        return f"!{node.kind}({', '.join(number(c) for c in node.colour + node.args)})"
    if isinstance(node, Tf):
        steps = " ".join(f"@{k}({', '.join(expression(a) for a in args)})" for k, args in node.steps)
        return f"{steps} {text(node.child)}"
    if isinstance(node, Bool):
        return f"${node.op}({', '.join(text(c) for c in node.children)})"
    if isinstance(node, Rep):
        return f"${node.op}[{node.param} = 0, {node.count - 1}]({text(node.child)})"
    if isinstance(node, Smooth):
        return f"@s({number(node.angle)}) {text(node.child)}"
    return node.name


def scene_text(scene: Scene) -> str:
    lines = []
    for s in scene.statements:
        if s[0] == "param":
            lines.append(f"{s[1]} = {number(s[2])};")
        elif s[0] == "object":
            lines.append(f"{s[1]} = {text(s[2])};")
        else:
            lines.append(f"> {', '.join(text(n) for n in s[1])};")
    return "\n".join(lines) + "\n"


# --- reading it back ----------------------------------------------------------
#
# The corpus (tests/corpus/) keeps the scenes the oracle found as the text it
# printed; this reads that text (and only that form: the printer's output,
# with '//' comment lines) back into the structure the oracle evaluates.

_TOKEN = re.compile(r"\s*(?:(//[^\n]*)|([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)|([A-Za-z_]\w*)|(.))")


class _Reader:
    def __init__(self, text: str):
        self.tokens = [m.group(2) and float(m.group(2)) if m.group(2) else m.group(3) or m.group(4)
                       for m in _TOKEN.finditer(text) if not m.group(1) and m.group(0).strip()]
        self.at = 0

    def peek(self, ahead: int = 0):
        return self.tokens[self.at + ahead] if self.at + ahead < len(self.tokens) else None

    def take(self, want=None):
        token = self.peek()
        if want is not None and token != want:
            raise ValueError(f"expected {want!r}, found {token!r} (token {self.at})")
        self.at += 1
        return token

    def number(self) -> float:
        if self.peek() == "(":  # a negative number, as ``number`` writes it
            self.take("(")
            value = self.take()
            self.take(")")
        else:
            value = self.take()
        if not isinstance(value, float):
            raise ValueError(f"expected a number, found {value!r}")
        return value

    def expression(self):
        if self.peek() == "(" and self.peek(2) != ")":  # (c * NAME + k); not (-x)
            self.take("(")
            coefficient = self.number()
            self.take("*")
            name = self.take()
            self.take("+")
            constant = self.number()
            self.take(")")
            return Param(name, coefficient, constant)
        return self.number()

    def numbers(self, read) -> tuple:
        self.take("(")
        values = [read()]
        while self.peek() == ",":
            self.take(",")
            values.append(read())
        self.take(")")
        return tuple(values)

    def node(self):
        token = self.take()
        if token == "!":
            kind = self.take()
            values = self.numbers(self.number)
            return Prim(kind, values[:3], values[3:])
        if token == "@":
            kind = self.take()
            if kind == "s":
                return Smooth(self.numbers(self.number)[0], self.node())
            steps = [(kind, self.numbers(self.expression))]
            while self.peek() == "@" and self.peek(1) != "s":
                self.take("@")
                kind = self.take()
                steps.append((kind, self.numbers(self.expression)))
            return Tf(tuple(steps), self.node())
        if token == "$":
            op = self.take()
            if self.peek() == "[":
                self.take("[")
                param = self.take()
                self.take("=")
                self.number()
                self.take(",")
                count = int(self.number()) + 1
                self.take("]")
                self.take("(")
                child = self.node()
                self.take(")")
                return Rep(op, param, count, child)
            self.take("(")
            children = [self.node()]
            while self.peek() == ",":
                self.take(",")
                children.append(self.node())
            self.take(")")
            return Bool(op, tuple(children))
        if isinstance(token, str) and token[0].isalpha():
            return Ref(token)
        raise ValueError(f"unexpected {token!r} (token {self.at - 1})")

    def scene(self) -> Scene:
        statements = []
        while self.peek() is not None:
            if self.peek() == ">":
                self.take(">")
                nodes = [self.node()]
                while self.peek() == ",":
                    self.take(",")
                    nodes.append(self.node())
                statements.append(("frame", nodes))
            else:
                name = self.take()
                self.take("=")
                if isinstance(self.peek(), float) or self.peek() == "(":
                    statements.append(("param", name, self.number()))
                else:
                    statements.append(("object", name, self.node()))
            self.take(";")
        return Scene(statements)


def read_scene(text: str) -> Scene:
    """The structure of a scene the oracle printed (``scene_text``), comments skipped."""
    return _Reader(text).scene()

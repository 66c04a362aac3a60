"""The oracle's scenes as Python structures (parameters, named objects, nested
transformations, booleans, repetitions, smooth solids, frames) and their
Castor text, which castor reads."""

from __future__ import annotations

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

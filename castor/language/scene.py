"""The scene graph: expressions, nodes and statements, as plain frozen data.

The parser builds these bottom-up; an object reference shares the node of the
named object, so a scene is a DAG. Every node records the free parameters it
reads (``params``) so that the facetizer can cache a shared subgraph once per
set of parameter values, and its nesting ``depth`` so that deep graphs are
refused before they exhaust the stack. Nodes are never changed once made (they are not declared frozen only because
frozen dataclasses are slow to create, and a scene has many). Behaviour lives
elsewhere:
``expressions.py`` evaluates expressions, ``facetize.py`` turns nodes into
solids.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from castor.diagnostics import Location

EMPTY: frozenset[str] = frozenset()


# --- expressions -----------------------------------------------------------


@dataclass(eq=False, slots=True)
class Number:
    value: float
    location: Location
    params: frozenset[str] = EMPTY
    depth: int = 1


@dataclass(eq=False, slots=True)
class Param:
    name: str
    location: Location
    params: frozenset[str] = EMPTY
    depth: int = 1


@dataclass(eq=False, slots=True)
class Unary:
    op: str
    operand: "Expr"
    location: Location
    params: frozenset[str] = EMPTY
    depth: int = 1


@dataclass(eq=False, slots=True)
class Binary:
    op: str
    left: "Expr"
    right: "Expr"
    location: Location
    params: frozenset[str] = EMPTY
    depth: int = 1


@dataclass(eq=False, slots=True)
class Call:
    function: str
    args: tuple["Expr", ...]
    location: Location
    params: frozenset[str] = EMPTY
    depth: int = 1


Expr = Number | Param | Unary | Binary | Call


# --- scene graph nodes -----------------------------------------------------


@dataclass(eq=False, slots=True)
class Repeat:
    """``[I = A, B, S]``: the parameter I takes the values A, A+S, ... up to B."""

    param: str
    start: Expr
    stop: Expr
    step: Expr | None
    location: Location
    params: frozenset[str] = EMPTY


@dataclass(eq=False, slots=True)
class PrimitiveNode:
    """``!cu(R, G, B)`` and friends: a unit solid with a colour."""

    kind: str
    args: tuple[Expr, ...]
    location: Location
    params: frozenset[str] = EMPTY
    depth: int = 1


@dataclass(eq=False, slots=True)
class Step:
    """One transformation prefix such as ``@rz(90)``."""

    kind: str
    args: tuple[Expr, ...]
    location: Location


@dataclass(eq=False, slots=True)
class TransformedNode:
    """A run of transformation prefixes applied to one object, right to left.

    The run is kept flat (not one node per prefix) so that ten thousand nested
    transformations cost a loop, not ten thousand levels of recursion.
    """

    steps: tuple[Step, ...]
    child: "SceneNode"
    location: Location
    params: frozenset[str] = EMPTY
    depth: int = 1


@dataclass(eq=False, slots=True)
class BooleanNode:
    """``$U``, ``$I`` or ``$D`` of operands, or of a repeated body."""

    op: str  # 'U', 'I' or 'D'
    operands: tuple["SceneNode", ...]
    repeat: Repeat | None
    location: Location
    params: frozenset[str] = EMPTY
    depth: int = 1


@dataclass(eq=False, slots=True)
class NamedNode:
    """The node an object definition creates: it knows the name pointing at it."""

    name: str
    child: "SceneNode"
    location: Location
    params: frozenset[str] = EMPTY
    depth: int = 1


SceneNode = PrimitiveNode | TransformedNode | BooleanNode | NamedNode


# --- statements ------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class ParamDef:
    name: str
    expr: Expr
    location: Location


@dataclass(frozen=True, slots=True)
class ObjectDef:
    name: str
    node: SceneNode
    location: Location


@dataclass(frozen=True, slots=True)
class Facetize:
    objects: tuple[SceneNode, ...]
    repeat: Repeat | None
    location: Location


Statement = ParamDef | ObjectDef | Facetize


@dataclass
class Tables:
    """The two symbol tables of a scene (Python dicts are hash tables)."""

    parameters: dict[str, float] = field(default_factory=dict)
    objects: dict[str, NamedNode] = field(default_factory=dict)
    # names whose definition failed: their uses are reported once, quietly
    broken: set[str] = field(default_factory=set)

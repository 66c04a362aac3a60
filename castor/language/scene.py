"""The scene graph: expressions, nodes and statements, as plain frozen data.

The parser builds these bottom-up; an object reference shares the node of the
named object, so a scene is a DAG. Every node records the free parameters it
reads (``params``) so that the facetizer can cache a shared subgraph once per
set of parameter values, and its nesting ``depth`` so that deep graphs are
refused before they exhaust the stack. Nodes are never changed once made.
They are plain classes (castor.records), not dataclasses: making these 15
dataclasses cost about 7 ms of every start-up of castor (issue 18). Behaviour
lives elsewhere:
``expressions.py`` evaluates expressions, ``facetize.py`` turns nodes into
solids.
"""

from __future__ import annotations

from castor.diagnostics import Location
from castor.records import Identified, Record

EMPTY: frozenset[str] = frozenset()


# --- expressions -----------------------------------------------------------


class Number(Identified):
    """A number as written (or an expression without parameters, folded): it reads
    no parameter and nests one deep, for every number (a long statement makes
    hundreds of thousands: two fields, not four)."""

    __slots__ = ("value", "location")
    params: frozenset[str] = EMPTY
    depth = 1

    def __init__(self, value: float, location: Location):
        self.value = value
        self.location = location


class Param(Identified):
    __slots__ = ("name", "location", "params", "depth")

    def __init__(self, name: str, location: Location, params: frozenset[str] = EMPTY,
                 depth: int = 1):
        self.name = name
        self.location = location
        self.params = params
        self.depth = depth


class Unary(Identified):
    __slots__ = ("op", "operand", "location", "params", "depth")

    def __init__(self, op: str, operand: "Expr", location: Location, params: frozenset[str] = EMPTY,
                 depth: int = 1):
        self.op = op
        self.operand = operand
        self.location = location
        self.params = params
        self.depth = depth


class Binary(Identified):
    __slots__ = ("op", "left", "right", "location", "params", "depth")

    def __init__(self, op: str, left: "Expr", right: "Expr", location: Location,
                 params: frozenset[str] = EMPTY, depth: int = 1):
        self.op = op
        self.left = left
        self.right = right
        self.location = location
        self.params = params
        self.depth = depth


class Call(Identified):
    __slots__ = ("function", "args", "location", "params", "depth")

    def __init__(self, function: str, args: tuple["Expr", ...], location: Location,
                 params: frozenset[str] = EMPTY, depth: int = 1):
        self.function = function
        self.args = args
        self.location = location
        self.params = params
        self.depth = depth


Expr = Number | Param | Unary | Binary | Call


# --- scene graph nodes -----------------------------------------------------


class Repeat(Identified):
    """``[I = A, B, S]``: the parameter I takes the values A, A+S, ... up to B."""

    __slots__ = ("param", "start", "stop", "step", "location", "params")

    def __init__(self, param: str, start: Expr, stop: Expr, step: Expr | None, location: Location,
                 params: frozenset[str] = EMPTY):
        self.param = param
        self.start = start
        self.stop = stop
        self.step = step
        self.location = location
        self.params = params


class PrimitiveNode(Identified):
    """``!cu(R, G, B)`` and friends: a unit solid with a colour."""

    __slots__ = ("kind", "args", "location", "params", "depth")

    def __init__(self, kind: str, args: tuple[Expr, ...], location: Location,
                 params: frozenset[str] = EMPTY, depth: int = 1):
        self.kind = kind
        self.args = args
        self.location = location
        self.params = params
        self.depth = depth


class Step(Identified):
    """One transformation prefix such as ``@rz(90)``."""

    __slots__ = ("kind", "args", "location")

    def __init__(self, kind: str, args: tuple[Expr, ...], location: Location):
        self.kind = kind
        self.args = args
        self.location = location


class TransformedNode(Identified):
    """A run of transformation prefixes applied to one object, right to left.

    The run is kept flat (not one node per prefix) so that ten thousand nested
    transformations cost a loop, not ten thousand levels of recursion.
    """

    __slots__ = ("steps", "child", "location", "params", "depth")

    def __init__(self, steps: tuple[Step, ...], child: "SceneNode", location: Location,
                 params: frozenset[str] = EMPTY, depth: int = 1):
        self.steps = steps
        self.child = child
        self.location = location
        self.params = params
        self.depth = depth


class BooleanNode(Identified):
    """``$U``, ``$I`` or ``$D`` of operands, or of a repeated body."""

    __slots__ = ("op", "operands", "repeat", "location", "params", "depth")

    def __init__(self, op: str, operands: tuple["SceneNode", ...], repeat: Repeat | None,
                 location: Location, params: frozenset[str] = EMPTY, depth: int = 1):
        self.op = op  # 'U', 'I' or 'D'
        self.operands = operands
        self.repeat = repeat
        self.location = location
        self.params = params
        self.depth = depth


class NamedNode(Identified):
    """The node an object definition creates: it knows the name pointing at it."""

    __slots__ = ("name", "child", "location", "params", "depth")

    def __init__(self, name: str, child: "SceneNode", location: Location,
                 params: frozenset[str] = EMPTY, depth: int = 1):
        self.name = name
        self.child = child
        self.location = location
        self.params = params
        self.depth = depth


SceneNode = PrimitiveNode | TransformedNode | BooleanNode | NamedNode


class UndefinedReference(Identified):
    """Where a statement names an object that is not defined. The parser has
    reported it; the node stands in the graph only so that the rest of the
    statement is built and checked (its other faults reported with it), and
    the statement is dropped: no stage ever evaluates it."""

    __slots__ = ("name", "location", "params", "depth")

    def __init__(self, name: str, location: Location):
        self.name = name
        self.location = location
        self.params = EMPTY
        self.depth = 1


# --- statements ------------------------------------------------------------


class ParamDef(Record):
    __slots__ = ("name", "expr", "location")

    def __init__(self, name: str, expr: Expr, location: Location):
        self.name = name
        self.expr = expr
        self.location = location


class ObjectDef(Record):
    __slots__ = ("name", "node", "location")

    def __init__(self, name: str, node: SceneNode, location: Location):
        self.name = name
        self.node = node
        self.location = location


class FrameCommand(Record):
    """A '>' command (LANGUAGE.md §3): its objects, evaluated with the parameters
    in force, make one frame, or one for each value of its repetition; what a
    frame becomes (polygons, a picture, a drawing, a building model) the output
    says, not the command."""

    __slots__ = ("objects", "repeat", "location")

    def __init__(self, objects: tuple[SceneNode, ...], repeat: Repeat | None, location: Location):
        self.objects = objects
        self.repeat = repeat
        self.location = location


Statement = ParamDef | ObjectDef | FrameCommand


class Tables:
    """The two symbol tables of a scene (Python dicts are hash tables)."""

    __slots__ = ("parameters", "objects", "broken")

    def __init__(self, parameters: dict[str, float] | None = None,
                 objects: dict[str, NamedNode] | None = None, broken: set[str] | None = None):
        self.parameters = {} if parameters is None else parameters
        self.objects = {} if objects is None else objects
        # names whose definition failed: their uses are reported once, quietly
        self.broken = set() if broken is None else broken

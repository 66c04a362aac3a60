"""Instantiate the scene graph at one frame's parameter values: the evaluated CSG tree.

One walk of the DAG evaluates every expression, repetition, colour and
matrix with the parameters in force, checks every primitive, and gives a
``tree.FrameTree`` of plain data. A named object becomes one ``Shared`` subtree
for each set of values of the parameters it reads and facet tolerance, made
once and used from every place that refers to it: 400 references to one tree
are one subtree. Every error of the walk is collected with its location, so
that a frame with two faults reports both.
"""

from __future__ import annotations

import math
from contextlib import contextmanager
from typing import MutableMapping

from castor.csg import tree
from castor.csg.fineness import slow_message, slow_segments
from castor.csg.paths import ROOT, Trail
from castor.diagnostics import (CastorError, EvaluationError, GeometryError, LimitError, Location,
                               counted)
from castor.language.expressions import evaluate, format_number
from castor.language.scene import (BooleanNode, NamedNode, Number, PrimitiveNode, Repeat,
                                   SceneNode, TransformedNode)
from castor.settings import DEFAULT_TOLERANCE
from castor.primitives import PRIMITIVES
from castor.primitives.facets import linear_part, product, quantize, stretch_above
from castor.transformations import step_matrix

MAX_REPEAT = 1_000_000
# Beyond this, double precision leaves too few digits for exact booleans.
MAX_COORDINATE = 1e12
_MISSING = object()
_WITHIN = MAX_COORDINATE.__ge__  # abs(v) <= MAX_COORDINATE, as one call in C
# shared subtrees remembered across frames (late binding makes most frames alike)
_MEMO_LIMIT = 100_000


class FrameErrors(CastorError):
    """Every error found while evaluating one frame, in the order found."""

    def __init__(self, errors: list[CastorError]):
        super().__init__(errors[0].message, errors[0].location)
        self.errors = errors


def repeat_values(repeat: Repeat, env) -> list[float]:
    """The values A, A+S, ... not past B (LANGUAGE.md §6)."""
    start = evaluate(repeat.start, env)
    stop = evaluate(repeat.stop, env)
    step = evaluate(repeat.step, env) if repeat.step is not None else 1.0
    if step == 0:
        location = repeat.step.location if repeat.step is not None else repeat.location
        raise EvaluationError("the step of a repetition is zero; it would never end", location)
    span = (stop - start) / step
    if span < -1e-9:
        return []
    count = math.floor(span + 1e-9) + 1 if span < 1e18 else math.inf
    if count > MAX_REPEAT:
        raise LimitError(f"the repetition [{repeat.param} = {format_number(start)}, "
                         f"{format_number(stop)}, {format_number(step)}] gives "
                         f"{count if count < math.inf else 'too many'} values; "
                         f"at most {MAX_REPEAT} are allowed", repeat.location)
    return [start + i * step for i in range(count)]


@contextmanager
def restored(env, name: str):
    """A repetition's parameter gets its previous value (or none) back afterwards."""
    saved = env.get(name, _MISSING)
    try:
        yield
    finally:
        if saved is _MISSING:
            env.pop(name, None)
        else:
            env[name] = saved


class Evaluator:
    """Walks the scene graph into evaluated trees, frame after frame.

    Shared subtrees are remembered by (named node, values of the parameters it
    reads, tolerance, shape of the stretch above it), so a named object that
    reads nothing that changed is the same subtree, with the same key, in the
    next frame too.
    """

    def __init__(self):
        self.memo: dict[tuple, tuple[NamedNode, tree.Shared | None]] = {}
        self.errors: list[CastorError] = []
        self._seen_errors: set[tuple] = set()
        self.declared = None  # the scene's classes (castor.language.classes.Declared), if any
        # (message, location) of the primitives too finely faceted (castor.csg.fineness),
        # for the caller to say; each primitive's place once a run
        self.warnings: list[tuple[str, Location]] = []
        self._slow_said: set[Location] = set()
        self._chosen: float | None = None  # the frame's tolerance; None once an '@f' set one

    def frame(self, objects: tuple[SceneNode, ...], env: MutableMapping[str, float], number: int,
              where: str, location: Location) -> tree.FrameTree:
        """The evaluated tree of one '>' command; raises FrameErrors with every
        error found."""
        self.errors = []
        self._seen_errors = set()
        tolerance = env.get("TOLERANCE", DEFAULT_TOLERANCE)
        if not (tolerance > 0 and math.isfinite(tolerance)):
            raise EvaluationError(f"TOLERANCE must be a positive number, not "
                                  f"{format_number(tolerance)}", location)
        self._chosen = tolerance
        if len(self.memo) > _MEMO_LIMIT:
            self.memo.clear()
        made = []
        for k, node in enumerate(objects, 1):
            if type(node) is NamedNode:
                name = node.name
            else:
                name = f"object{k}"
            root = self._node(node, env, tree.IDENTITY, None, tolerance, ROOT, ROOT)
            made.append(tree.Object(name, root, f"{node.location.file}:{node.location.line}"))
        if self.errors:
            raise FrameErrors(self.errors)
        parameters = tuple((k, v) for k, v in env.items() if k != "PI")
        scene = tree.FrameTree(number, where, location, tuple(made), parameters, self.declared)
        if self.declared is not None and self.declared.has_spaces:
            from castor.csg.elements import without_spaces

            scene = without_spaces(scene)
        return scene

    def _fail(self, error: CastorError) -> None:
        key = (error.message, error.location)
        if key not in self._seen_errors:
            self._seen_errors.add(key)
            self.errors.append(error)

    def _values(self, args, env) -> list[float] | None:
        """The arguments' values; None, with every error recorded, if any fails.
        (Numbers, most arguments, are read in place: a long statement has hundreds
        of thousands; where one argument fails, all are evaluated again, one by one,
        for every error: evaluating has no effect but its value or its error.)"""
        try:
            return [arg.value if type(arg) is Number else evaluate(arg, env) for arg in args]
        except CastorError:
            pass
        values, failed = [], False
        for arg in args:
            try:
                values.append(evaluate(arg, env))
            except CastorError as error:
                self._fail(error)
                failed = True
        return None if failed else values

    # --- one node: its tree, or None when it is empty or failed. ``matrix``
    # places it in the nearest shared subtree (or the scene), whose units the
    # ``tolerance`` is in; ``stretch``, the shape of the stretch of those units
    # above (facets.stretch_above), or None.
    def _node(self, node: SceneNode, env, matrix: tree.Matrix, stretch, tolerance: float,
              trail: Trail, rel: Trail):
        kind = type(node)
        try:
            if kind is NamedNode:
                return self._named(node, env, matrix, stretch, tolerance, trail, rel)
            if kind is TransformedNode:
                return self._transformed(node, env, matrix, stretch, tolerance, trail, rel)
            if kind is BooleanNode:
                return self._boolean(node, env, matrix, stretch, tolerance, trail, rel)
            return self._primitive(node, env, matrix, stretch, tolerance, trail, rel)
        except FrameErrors as group:
            for error in group.errors:
                self._fail(error)
        except CastorError as error:
            self._fail(error)
        return None

    def _named(self, node: NamedNode, env, matrix, stretch, tolerance, trail, rel):
        linear = linear_part(matrix)
        if stretch is not None:
            linear = product(stretch, linear)
        largest, stretch = stretch_above(linear)
        # rounded so that near-equal scales share the subtree; under a
        # non-uniform stretch its primitives round once, with their own stretch
        local = quantize(tolerance / largest) if stretch is None else tolerance / largest
        key = (id(node), tuple(env.get(p, _MISSING) for p in sorted(node.params)), local, stretch)
        remembered = self.memo.get(key)
        if remembered is not None and remembered[0] is node:
            shared = remembered[1]
        else:
            before = len(self.errors)
            child = self._node(node.child, env, tree.IDENTITY, stretch, local,
                               trail.down(f"({node.name})"), ROOT)
            if len(self.errors) > before:
                shared = None
                child = None
            else:
                shared = tree.Shared(node.name, child, None, node.location)  # (its key when asked)
            if len(self.errors) == before:
                self.memo[key] = (node, shared)
        if shared is None or shared.child is None:
            return None
        return tree.Use(matrix, rel.steps(), shared)

    def _transformed(self, node: TransformedNode, env, matrix, stretch, tolerance, trail, rel):
        local = tree.IDENTITY
        failed = False
        for k, step in enumerate(node.steps):
            values = self._values(step.args, env)
            if values is None:
                failed = True
                continue
            if step.kind == "s":  # the steps after it and the child are its operand
                operand = TransformedNode(node.steps[k + 1:], node.child, node.location) if k + 1 < len(
                    node.steps) else node.child
                if failed:
                    return None
                self._check_reach(local, trail, node)
                return self._smooth(values[0], step.location, operand, env,
                                    tree.compose(matrix, local), stretch, tolerance, trail, rel)
            if step.kind == "f":
                if not (values[0] > 0):
                    raise GeometryError(f"the facet tolerance of '@f' must be positive, not "
                                        f"{format_number(values[0])}", step.location)
                # in scene units; inside a named object used at a scale, in its units
                tolerance = values[0]
                stretch = None
                self._chosen = None
                continue
            if step.kind == "t":  # the commonest step, without numpy
                x, y, z = values
                m = (1.0, 0.0, 0.0, x, 0.0, 1.0, 0.0, y, 0.0, 0.0, 1.0, z)
            else:
                m, _ = step_matrix(step.kind, values, step.location, trail)
            local = tree.compose(local, m)
        if failed:
            return None
        if local is not tree.IDENTITY:
            self._check_reach(local, trail, node)
            matrix = tree.compose(matrix, local)
        return self._node(node.child, env, matrix, stretch, tolerance, trail, rel)

    @staticmethod
    def _check_reach(local, trail, node: TransformedNode) -> None:
        if not all(map(_WITHIN, map(abs, local))):  # (a NaN is not within either)
            raise GeometryError(f"the transformations of {trail} reach beyond "
                                f"{MAX_COORDINATE:g}, the largest coordinate castor handles",
                                node.location)

    def _smooth(self, angle, location, operand, env, matrix, stretch, tolerance, trail, rel):
        """``@s(angle)``: a ``tree.Smooth`` of the operand evaluated in its own
        space (LANGUAGE.md §7.1); ``@s(0)`` keeps every edge and is no node."""
        if not 0 <= angle <= 180:
            raise GeometryError(f"the angle of '@s' must lie between 0 and 180 degrees, not "
                                f"{format_number(angle)}", location)
        if angle == 0:
            return self._node(operand, env, matrix, stretch, tolerance, trail, rel)
        # the operand in its own space, its tolerance scaled as a named object's is
        linear = linear_part(matrix)
        if stretch is not None:
            linear = product(stretch, linear)
        largest, shape = stretch_above(linear)
        local = quantize(tolerance / largest) if shape is None else tolerance / largest
        child = self._node(operand, env, tree.IDENTITY, shape, local, trail, rel)
        if child is None:
            return None
        return tree.Smooth(float(angle), matrix, child, local,
                           tree.smooth_key(float(angle), local, child), location)

    def _boolean(self, node: BooleanNode, env, matrix, stretch, tolerance, trail, rel):
        op = node.op
        operands = []
        if node.repeat is None:
            for k, child in enumerate(node.operands, 1):
                step = f"{op}{k}"
                operands.append(self._node(child, env, matrix, stretch, tolerance,
                                           trail.down(step), rel.down(step)))
        else:
            before, starts = len(self.errors), []
            with restored(env, node.repeat.param):
                for k, value in enumerate(repeat_values(node.repeat, env), 1):
                    env[node.repeat.param] = value
                    step = f"{op}{k}"
                    starts.append(len(self.errors))
                    operands.append(self._node(node.operands[0], env, matrix, stretch,
                                               tolerance, trail.down(step), rel.down(step)))
            if len(self.errors) > before + 1:
                self.errors[before:] = _merged(self.errors[before:], starts, before, trail, op)
        if op == "D":
            if not operands or operands[0] is None:
                return None
            if len(operands) < 2 or operands[1] is None:
                return operands[0]
        elif op == "I" and (not operands or any(o is None for o in operands)):
            return None
        operands = [o for o in operands if o is not None]
        if not operands:
            return None
        if len(operands) == 1 and op != "D":
            return operands[0]
        return tree.Boolean(op, tuple(operands), node.location)

    def _primitive(self, node: PrimitiveNode, env, matrix, stretch, tolerance, trail, rel):
        values = self._values(node.args, env)
        if values is None:
            return None
        colour = tuple(values[:3])
        if len(colour) != 3 or not (0.0 <= colour[0] <= 1.0 and 0.0 <= colour[1] <= 1.0
                                    and 0.0 <= colour[2] <= 1.0):
            _check_colour(colour, node, trail)
        shape = tuple(values[3:])
        kind = node.kind
        declared = PRIMITIVES[kind]
        if declared.check is not None:
            declared.check(shape, node.location, trail.down(f"!{kind}"))
        extent = _EXTENTS.get((kind, shape))
        if extent is None:
            if len(_EXTENTS) >= _EXTENTS_KEPT:
                _EXTENTS.clear()
            extent = _EXTENTS[kind, shape] = declared.extent(shape)
        _check_reach(matrix, extent, node, trail)
        if declared.curved:
            segments = slow_segments(declared, shape, matrix, stretch, tolerance, extent)
            if segments is not None and node.location not in self._slow_said:
                self._slow_said.add(node.location)
                self.warnings.append((slow_message(kind, segments, self._chosen), node.location))
        # the path: rel.down(f"!{kind}").steps(), a segment after which no dot comes
        return tree.Primitive(kind, shape, colour, matrix, tolerance, stretch,
                              f"{rel.steps()}!{kind}", node.location)


def _check_colour(colour, node: PrimitiveNode, trail: Trail) -> None:
    """Refuse a colour component outside 0..1."""
    here = trail.down(f"!{node.kind}")
    for name, c, arg in zip(("red", "green", "blue"), colour, node.args):
        if not 0.0 <= c <= 1.0:
            # a whole number up to 255 looks like a byte; 1.8 is a slip of its own
            hint = (f"; if it is a 0..255 value, write {format_number(c)}/255"
                    if 1 < c <= 255 and c == int(c) else "")
            raise GeometryError(f"colour component {name} = {format_number(c)} of {here} is "
                                f"outside 0..1{hint}", arg.location)


# the extent of each primitive's shape (PrimitiveKind.extent), by (kind, shape):
# a long statement places thousands of primitives of a few shapes
_EXTENTS: dict[tuple, float] = {}
_EXTENTS_KEPT = 4096


def _merged(errors: list[CastorError], starts: list[int], offset: int, trail: Trail,
            op: str) -> list[CastorError]:
    """The errors of a repetition's operands (those of operand k from
    ``starts[k - 1] - offset`` on), each error that several operands share said
    once, naming the first and how many (CLI.md: one message per cause)."""
    import copy
    import re

    groups: dict[tuple, tuple[CastorError, list[int]]] = {}
    k = 0
    for index, error in enumerate(errors, offset):
        while k < len(starts) and starts[k] <= index:
            k += 1
        own = re.compile(re.escape(str(trail.down(f"{op}{k}"))) + r"(?!\d)")
        key = (type(error), own.sub("\0", error.message), error.location)
        groups.setdefault(key, (error, []))[1].append(k)
    out = []
    for error, operands in groups.values():
        if len(operands) > 1:
            error = copy.copy(error)
            error.message += f" (the same in {counted('operand', operands)} of the repetition)"
        out.append(error)
    return out


def _check_reach(matrix: tree.Matrix, extent: float, node: PrimitiveNode, trail: Trail) -> None:
    """Refuse a primitive whose corners reach beyond MAX_COORDINATE (``extent``:
    the largest coordinate of its unit box, declared with the primitive)."""
    a, b, c, t, d, e, f, u, g, h, i, v = matrix
    if (abs(a) + abs(b) + abs(c)) * extent + abs(t) > MAX_COORDINATE or \
            (abs(d) + abs(e) + abs(f)) * extent + abs(u) > MAX_COORDINATE or \
            (abs(g) + abs(h) + abs(i)) * extent + abs(v) > MAX_COORDINATE:
        raise GeometryError(f"{trail.down(f'!{node.kind}')} reaches beyond {MAX_COORDINATE:g}, "
                            "the largest coordinate castor handles", node.location)

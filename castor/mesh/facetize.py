"""Evaluate the scene graph at a '>' command and turn it into polygons.

The facetizer walks the DAG with the parameter values in force, builds each
primitive's mesh (facet counts from the tolerance and the scale above it),
applies transformations, and hands booleans to the engine. Named nodes, the
only ones a scene can share, are cached once per set of values of the
parameters they read and per facet resolution, and reused by transformation.
"""

from __future__ import annotations

import math
import time
from contextlib import contextmanager
from dataclasses import dataclass
from typing import MutableMapping

import numpy as np

from castor.mesh import engine, memory, polygons, primitives
from castor.diagnostics import EvaluationError, GeometryError, LimitError, Location
from castor.language.expressions import evaluate, format_number
from castor.mesh.frame import Frame, FrameObject
from castor.csg.paths import ROOT, Path, Trail
from castor.language.scene import Boolean, Named, Node, Primitive, Repeat, Transformed
from castor.csg.transforms import step_matrix

MAX_REPEAT = 1_000_000
# Beyond this, double precision leaves too few digits for exact booleans.
MAX_COORDINATE = 1e12
DEFAULT_TOLERANCE = 0.01
_MISSING = object()
# A frame whose estimate is this many times --max-polygons is refused before
# it is built (operands of a union add up; their overlap would only remove).
ESTIMATE_SLACK = 4
# Cache entries are kept while the cached solids hold fewer triangles than this.
_CACHE_TRIANGLES = 4_000_000


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


@dataclass
class FrameStats:
    primitives: int = 0
    booleans: int = 0
    polygons: int = 0
    vertices: int = 0
    euler: int = 0
    seconds: float = 0.0


class Facetizer:
    def __init__(self, max_polygons: int = 20_000_000, check_only: bool = False,
                 merge_polygons: bool = True):
        self.max_polygons = max_polygons
        # False for formats that hold triangles only (STL, PLY, glTF): merging
        # triangles into polygons that the writer cuts up again is wasted work
        self.merge_polygons = merge_polygons
        # --check: evaluate every value and validate every primitive, build nothing
        self.check_only = check_only
        self.cache: dict[tuple, engine.Solid] = {}
        self.cache_triangles = 0
        # primitive shapes already built in the engine, by kind, size and facets
        self.shape_cache: dict[tuple, object] = {}
        self.counter = engine.Counter()
        self.primitive_count = 0
        self.stats = FrameStats()

    # --- a whole frame
    def frame(self, objects, env: MutableMapping[str, float], number: int, where: str,
              location: Location) -> Frame:
        started = time.perf_counter()
        self.counter.booleans = 0
        self.primitive_count = 0
        tolerance = env.get("TOLERANCE", DEFAULT_TOLERANCE)
        if not (tolerance > 0 and math.isfinite(tolerance)):
            raise EvaluationError(f"TOLERANCE must be a positive number, not "
                                  f"{format_number(tolerance)}", location)
        frame = Frame(number, where)
        if self.check_only:
            for node in objects:
                self.solid(node, env, 1.0, tolerance, ROOT)
            return frame
        estimate = sum(self.estimate(node, env, tolerance, {}) for node in objects)
        if estimate > ESTIMATE_SLACK * self.max_polygons:
            raise LimitError(f"the frame would need about {estimate:,} polygons, more than "
                             f"--max-polygons {self.max_polygons:,}; is an object used twice "
                             "at every level of a deep chain?", location)
        short = memory.too_big(estimate)
        if short is not None:
            raise LimitError(f"the frame would need about {short[0] / 2 ** 30:.1f} GB of memory, "
                             f"more than the {short[1] / 2 ** 30:.1f} GB available; simplify the "
                             "scene or raise TOLERANCE", location)
        total = 0
        merger = polygons.Merger()
        for node in objects:
            solid = self.solid(node, env, 1.0, tolerance, ROOT)
            pieces = []
            for batch in engine.batches(solid.parts):
                tri = engine.triangles(batch)
                if self.merge_polygons:
                    merged = merger.merge(tri.vertices, tri.triangles, tri.origin_ids, tri.face_ids)
                else:
                    merged = polygons.as_triangles(tri.triangles, tri.origin_ids)
                total += len(merged.offsets) - 1  # the limit counts polygons (CLI.md)
                self._check_count(total, location)
                pieces.append((tri.vertices, merged))
                del tri
            frame.objects.append(_frame_object(pieces, solid.origins))
        self.stats = FrameStats(self.primitive_count, self.counter.booleans)
        self.stats.seconds = time.perf_counter() - started
        return frame

    def frame_stats(self, frame: Frame) -> FrameStats:
        """The figures of --stats for the frame just made (counting edges costs)."""
        stats = self.stats
        for obj in frame.objects:
            stats.polygons += obj.polygon_count
            stats.vertices += len(obj.vertices)
            stats.euler += len(obj.vertices) - obj.edge_count() + obj.polygon_count
        return stats

    def estimate(self, node: Node, env, tolerance: float, seen: dict) -> int:
        """About how many triangles ``node`` gives, without building anything:
        operands add up, primitives count their facets. It catches a graph whose
        expansion explodes before any memory goes to it."""
        known = seen.get(id(node))
        if known is not None:
            return known
        kind = type(node)
        if kind is Named or kind is Transformed:
            count = self.estimate(node.child, env, tolerance, seen)
        elif kind is Boolean:
            if node.repeat is None:
                count = sum(self.estimate(o, env, tolerance, seen) for o in node.operands)
            else:
                try:
                    times = len(repeat_values(node.repeat, env))
                except (EvaluationError, LimitError):
                    times = 0
                try:
                    with _restored(env, node.repeat.param):
                        env[node.repeat.param] = evaluate(node.repeat.start, env) if times else 0.0
                        count = times * self.estimate(node.operands[0], env, tolerance, {})
                except EvaluationError:
                    count = 0
            if node.op == "D" and node.operands:
                count = max(count, 1)
        else:
            try:
                shape = tuple(evaluate(a, env) for a in node.args[3:])
                count = primitives.estimate_triangles(node.kind, shape, tolerance)
            except (EvaluationError, ValueError, IndexError, OverflowError):
                count = 12
        seen[id(node)] = count
        return count

    def _check_count(self, triangles: int, location: Location) -> None:
        if triangles > self.max_polygons:
            raise LimitError(f"the frame needs more than {self.max_polygons} polygons "
                             f"(--max-polygons); simplify the scene or raise the limit", location)

    # --- one node
    def solid(self, node: Node, env, scale: float, tolerance: float, path: Trail) -> engine.Solid:
        """The solid of ``node`` in its own coordinates; ``path`` is the way down to
        it, for messages."""
        kind = type(node)
        if kind is Named:
            return self._named(node, env, scale, tolerance, path)
        if kind is Transformed:
            return self._transformed(node, env, scale, tolerance, path)
        if kind is Boolean:
            return self._boolean(node, env, scale, tolerance, path)
        return self._primitive(node, env, scale, tolerance, path)

    def _named(self, node: Named, env, scale, tolerance, path) -> engine.Solid:
        here = path.down(f"({node.name})")
        local = _quantize(tolerance / scale)
        key = (node, tuple(env.get(p, _MISSING) for p in sorted(node.params)), local)
        cached = self.cache.get(key)
        if cached is not None:
            copy = engine.reinstanced(cached[0])
            if copy is not None:  # else the engine could not copy it exactly: evaluate again
                self.primitive_count += cached[1]
                return copy.prefixed(f"({node.name})")
        before = self.primitive_count
        solid = self.solid(node.child, env, scale, tolerance, here)
        count = solid.triangle_count()
        if self.cache_triangles + count > _CACHE_TRIANGLES:
            self.cache.clear()
            self.cache_triangles = 0
        self.cache[key] = (solid, self.primitive_count - before)
        self.cache_triangles += count
        return solid.prefixed(f"({node.name})")

    def _transformed(self, node: Transformed, env, scale, tolerance, path) -> engine.Solid:
        matrix = np.eye(4)
        moved = False
        for step in node.steps:
            values = [evaluate(a, env) for a in step.args]
            if step.kind == "f":
                if not (values[0] > 0):
                    raise GeometryError(f"the facet tolerance of '@f' must be positive, not "
                                        f"{format_number(values[0])}", step.location)
                tolerance = values[0]
                continue
            m, stretch = step_matrix(step.kind, values, step.location, path)
            matrix = matrix @ m
            scale *= stretch
            moved = True
        if not np.all(np.abs(matrix) <= MAX_COORDINATE):
            raise GeometryError(f"the transformations of {path} reach beyond "
                                f"{MAX_COORDINATE:g}, the largest coordinate castor handles",
                                node.location)
        solid = self.solid(node.child, env, scale, tolerance, path)
        if not moved or solid.empty:
            return solid
        solid = solid.transformed(matrix)
        box = solid.box()
        if not np.all(np.abs(box) <= MAX_COORDINATE):
            raise GeometryError(f"{path} reaches beyond {MAX_COORDINATE:g}, "
                                "the largest coordinate castor handles", node.location)
        return solid

    def _boolean(self, node: Boolean, env, scale, tolerance, path) -> engine.Solid:
        op = node.op
        operands: list[engine.Solid] = []
        if node.repeat is None:
            for k, child in enumerate(node.operands, 1):
                step = f"{op}{k}"
                operands.append(self.solid(child, env, scale, tolerance,
                                           path.down(step)).prefixed(step))
        else:
            with _restored(env, node.repeat.param):
                for k, value in enumerate(repeat_values(node.repeat, env), 1):
                    env[node.repeat.param] = value
                    step = f"{op}{k}"
                    operands.append(self.solid(node.operands[0], env, scale, tolerance,
                                               path.down(step)).prefixed(step))
        if self.check_only:
            return engine.EMPTY
        operand_triangles = sum(s.triangle_count() for s in operands)
        if operand_triangles > 2 * self.max_polygons:
            self._check_count(operand_triangles, node.location)
        if op == "U":
            result = engine.union(operands, self.counter)
        elif op == "I":
            result = engine.intersection(operands, self.counter)
        else:
            result = engine.difference(operands[0], operands[1], self.counter)
        result_triangles = result.triangle_count()
        if result_triangles > 2 * self.max_polygons:  # polygons are counted when merged
            self._check_count(result_triangles, node.location)
        return result

    def _primitive(self, node: Primitive, env, scale, tolerance, path) -> engine.Solid:
        here = path.down(f"!{node.kind}")
        values = [evaluate(a, env) for a in node.args]
        colour = tuple(values[:3])
        for name, c, arg in zip(("red", "green", "blue"), colour, node.args):
            if not 0.0 <= c <= 1.0:
                hint = f"; if it is a 0..255 value, write {format_number(c)}/255" if 1 < c <= 255 else ""
                raise GeometryError(f"colour component {name} = {format_number(c)} of {here} is "
                                    f"outside 0..1{hint}", arg.location)
        shape = tuple(values[3:])
        if self.check_only:
            primitives.validate(node.kind, shape, node.location, here)
            self.primitive_count += 1
            return engine.EMPTY
        local = _quantize(tolerance / scale)
        estimate = primitives.estimate_triangles(node.kind, shape, local)
        self._check_count(estimate, node.location)
        key = (node.kind, shape, local if node.kind in ("sp", "cy", "co", "to", "rv") else None)
        shape_in_engine = self.shape_cache.get(key)
        if shape_in_engine is None:
            mesh = primitives.build(node.kind, shape, local, node.location, here)
            try:
                shape_in_engine = engine.template(mesh)
            except engine.EngineError as exc:
                raise GeometryError(f"{here} gives no valid solid ({exc})", node.location) from None
            if len(self.shape_cache) > 4096:
                self.shape_cache.clear()
            self.shape_cache[key] = shape_in_engine
        self.primitive_count += 1
        return engine.instance(shape_in_engine, engine.Origin(Path(f"!{node.kind}"), colour))


@contextmanager
def _restored(env, name: str):
    """A repetition's parameter gets its previous value (or none) back afterwards."""
    saved = env.get(name, _MISSING)
    try:
        yield
    finally:
        if saved is _MISSING:
            env.pop(name, None)
        else:
            env[name] = saved


def _quantize(tolerance: float) -> float:
    """Round a tolerance down to a power of 2^(1/4), so near-equal scales share a cache entry."""
    if tolerance <= 0 or not math.isfinite(tolerance):
        return tolerance
    return 2.0 ** (math.floor(math.log2(tolerance) * 4) / 4)


def _frame_object(pieces, origin_table) -> FrameObject:
    """One object from its parts' polygons: vertices and origins compacted to
    those the polygons use."""
    if not pieces:
        return FrameObject(np.zeros((0, 3)), np.zeros(1, np.int64), np.zeros(0, np.int64),
                           np.zeros(0, np.int64), [])
    if len(pieces) == 1:
        vertices, merged = pieces[0]
        offsets, indices, origin_ids = merged.offsets, merged.indices, merged.origin_ids
    else:
        vertex_base = np.cumsum([0] + [len(v) for v, _ in pieces[:-1]])
        index_base = np.cumsum([0] + [len(m.indices) for _, m in pieces[:-1]])
        vertices = np.concatenate([v for v, _ in pieces])
        indices = np.concatenate([m.indices + b for (_, m), b in zip(pieces, vertex_base)])
        offsets = np.concatenate([np.zeros(1, np.int64)]
                                 + [m.offsets[1:] + b for (_, m), b in zip(pieces, index_base)])
        origin_ids = np.concatenate([m.origin_ids for _, m in pieces])
    used = np.zeros(len(vertices), bool)
    used[indices] = True
    if not used.all():  # vertices left inside merged polygons
        renumber = np.cumsum(used) - 1
        indices = renumber[indices]
        vertices = vertices[used]
    ids, origin_of = np.unique(origin_ids, return_inverse=True)
    origins = [origin_table[int(i)] for i in ids]
    return FrameObject(np.ascontiguousarray(vertices), offsets, indices.astype(np.int64),
                       origin_of.ravel().astype(np.int64), origins)

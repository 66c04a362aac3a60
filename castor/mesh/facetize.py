"""Facetize an evaluated CSG tree (castor.csg.tree) into closed polygon meshes:
the stage's entry point.

Each primitive's mesh is built once per kind, shape and facet counts (which
the primitive chooses from its transformation and the tolerance) and
instanced (instances); a shared subtree is built once per key and reused by
moving it, in this process (the key is its content, so every process
agrees). Booleans go to the engine (booleans); the triangles that come back,
with their origins and faces (provenance), are regularized (regularize) and
merged into convex polygons (merge). What is remembered between frames is
held by castor.mesh.caches.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

from castor.csg import tree
from castor.csg.paths import Path
from castor.diagnostics import GeometryError, LimitError
from castor.mesh import adapter, booleans, instances, memory, merge, primitives, provenance
from castor.mesh.caches import PROCESS
from castor.mesh.frame import (FaceSurfaces, Frame, Origin, compact, curved_origins,
                               polygon_surfaces)
from castor.mesh.regularize import regular_triangles
from castor.mesh.solid import EMPTY, Solid, instance
from castor.settings import DEFAULT_MAX_POLYGONS

# A frame whose estimate is this many times --max-polygons is refused before
# it is built (operands of a union add up; their overlap would only remove).
ESTIMATE_SLACK = 4


@dataclass
class FrameStats:
    primitives: int = 0
    booleans: int = 0
    seconds: float = 0.0


class Facetizer:
    """Turns evaluated trees into mesh frames; one per process, kept across frames."""

    def __init__(self, max_polygons: int = DEFAULT_MAX_POLYGONS, merge_polygons: bool = True):
        self.max_polygons = max_polygons
        # False for formats that hold triangles only (STL, PLY, glTF): merging
        # triangles into polygons that the writer cuts up again is wasted work
        self.merge_polygons = merge_polygons
        # shared solids and primitives' templates: the process's (caches.PROCESS)
        self.caches = PROCESS
        self.caches.new_facetizer()
        self.counter = booleans.Counter()
        self.primitive_count = 0
        self.stats = FrameStats()

    # --- a whole frame
    def frame(self, frame_tree: tree.FrameTree) -> Frame:
        started = time.perf_counter()
        self.counter.booleans = 0
        self.primitive_count = 0
        estimate, booleans = tree_figures(frame_tree)
        if estimate > ESTIMATE_SLACK * self.max_polygons:
            raise LimitError(f"the frame would need about {estimate:,} polygons, more than "
                             f"--max-polygons {self.max_polygons:,}; is an object used twice "
                             "at every level of a deep chain?", frame_tree.location)
        short = memory.too_big(estimate)
        if short is not None:
            raise LimitError(f"the frame would need about {short[0] / 2 ** 30:.1f} GB of memory, "
                             f"more than the {short[1] / 2 ** 30:.1f} GB available; simplify the "
                             "scene or raise TOLERANCE", frame_tree.location)
        total = 0
        self.caches.patterns.clear()  # patterns of this frame's parts only
        merger = merge.Merger(self.caches.patterns, self.caches.merged, self.caches.groups)
        frame = Frame(frame_tree.number, frame_tree.where)
        for obj in frame_tree.objects:
            solid = self.solid(obj.root) if obj.root is not None else EMPTY
            pieces = []
            curved = curved_origins(solid.origins)
            for batch in provenance.batches(solid.parts):
                tri = regular_triangles(provenance.triangles(batch, solid.origins), batch)
                if self.merge_polygons:
                    merged = merger.merge(tri.vertices, tri.triangles, tri.origin_ids, tri.face_ids)
                else:
                    merged = merge.as_triangles(tri.triangles, tri.origin_ids)
                total += len(merged.offsets) - 1  # the limit counts polygons (CLI.md)
                self._check_count(total, frame_tree)
                surfaces = polygon_surfaces(solid.origins, curved, merged.origin_ids,
                                            tri.face_ids[merged.source])
                pieces.append((tri.vertices, merged, surfaces))
                del tri
            frame.objects.append(compact(pieces, solid.origins, obj.name))
        # the frame's booleans, each shared subtree counted once: the same
        # figure whichever process makes the frame, whatever it had cached
        self.stats = FrameStats(self.primitive_count, booleans, time.perf_counter() - started)
        return frame

    def _check_count(self, triangles: int, where) -> None:
        if triangles > self.max_polygons:
            raise LimitError(f"the frame needs more than {self.max_polygons} polygons "
                             f"(--max-polygons); simplify the scene or raise the limit",
                             where.location)

    # --- one node
    def solid(self, node: tree.TreeNode) -> Solid:
        kind = type(node)
        if kind is tree.Primitive:
            return self._primitive(node)
        if kind is tree.Boolean:
            return self._boolean(node)
        if kind is tree.Smooth:
            return self._smooth(node)
        return self._use(node)

    def _smooth(self, node: tree.Smooth) -> Solid:
        """A smooth solid, made once per key (castor.mesh.smooth) and moved."""
        from castor.mesh import smooth  # here: a scene without '@s' needs none of it

        solid = self._once(node.key, lambda: smooth.smoothed(self.solid(node.operand), node,
                                                              self.max_polygons))
        if node.matrix != tree.IDENTITY and not solid.empty:
            solid = solid.transformed(node.matrix)
        return solid

    def _use(self, use: tree.Use) -> Solid:
        shared = use.shared
        # the engine's own solid, as it was computed: never a copy rebuilt from
        # its mesh, which the engine may rebuild differently
        solid = self._once(shared.key, lambda: self.solid(shared.child))
        solid = solid.prefixed(f"({shared.name})")
        if use.path:
            solid = solid.prefixed(use.path)
        if use.matrix != tree.IDENTITY and not solid.empty:
            solid = solid.transformed(use.matrix)
        return solid

    def _once(self, key, make) -> Solid:
        """The solid cached under ``key``, or ``make()``'s, cached with the
        primitives it counted (a cached solid counts them again, as made)."""
        cached = self.caches.solids.get(key)
        if cached is not None:
            self.primitive_count += cached[1]
            return cached[0]
        before = self.primitive_count
        solid = make()
        self.caches.solids.put(key, (solid, self.primitive_count - before),
                               solid.triangle_count())
        return solid

    def _boolean(self, node: tree.Boolean) -> Solid:
        operands = [self.solid(o) for o in node.operands]
        operand_triangles = sum(s.triangle_count() for s in operands)
        if operand_triangles > 2 * self.max_polygons:
            self._check_count(operand_triangles, node)
        if node.op == "U":
            result = booleans.union(operands, self.counter)
        elif node.op == "I":
            result = booleans.intersection(operands, self.counter)
        else:
            result = booleans.difference(operands[0], operands[1], self.counter)
        result_triangles = result.triangle_count()
        if result_triangles > 2 * self.max_polygons:  # polygons are counted when merged
            self._check_count(result_triangles, node)
        return result

    def _primitive(self, leaf: tree.Primitive) -> Solid:
        facets = primitives.facet_counts(leaf)
        key = (leaf.kind, leaf.shape, facets)
        cached = self.caches.templates.get(key)
        if cached is None:
            estimate = primitives.estimate_triangles(leaf.kind, leaf.shape, facets)
            self._check_count(estimate, leaf)
            mesh = primitives.build(leaf.kind, leaf.shape, facets)
            try:
                template = instances.template(mesh)
            except adapter.EngineError as exc:
                raise GeometryError(f"{leaf.path} gives no valid solid ({exc})",
                                    leaf.location) from None
            # which faces are facets of a curved surface, for the outputs' creases
            surfaces = (FaceSurfaces(mesh.surfaces) if (mesh.surfaces >= 0).any() else None)
            self.caches.templates.put(key, (template, estimate, surfaces))
        else:
            # (the cache is the process's: checked against this facetizer's limit)
            template, estimate, surfaces = cached
            if estimate > self.max_polygons:
                self._check_count(estimate, leaf)
        self.primitive_count += 1
        origin = Origin(Path(leaf.path), leaf.colour, leaf.kind, surfaces)
        return instance(template, origin, None if leaf.matrix == tree.IDENTITY else leaf.matrix)


def tree_figures(frame_tree: tree.FrameTree) -> tuple[int, int]:
    """About how many triangles the frame gives, and its boolean operations,
    without building anything: operands add up, primitives count their facets,
    a shared subtree counts its triangles once per use and its booleans once.
    The estimate catches a graph whose expansion explodes before any memory
    goes to it."""
    known: dict[str, int] = {}
    booleans = 0

    def count(node) -> int:
        nonlocal booleans
        kind = type(node)
        if kind is tree.Primitive:
            return primitives.estimate_triangles(node.kind, node.shape,
                                                 primitives.facet_counts(node))
        if kind is tree.Boolean:
            booleans += 1
            total = sum(count(o) for o in node.operands)
            return max(total, 1) if node.op == "D" else total
        if kind is tree.Smooth:  # at least one level: four times the operand
            return 4 * count(node.operand)
        shared = node.shared
        if shared.key not in known:
            known[shared.key] = count(shared.child) if shared.child is not None else 0
        return known[shared.key]

    triangles = sum(count(o.root) for o in frame_tree.objects if o.root is not None)
    return triangles, booleans

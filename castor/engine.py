"""The boolean engine, manifold3d, behind one small adapter.

A ``Solid`` is a manifold plus the table of its origins: manifold3d gives
every input mesh an ID and records, for each output triangle, which input it
came from; castor maps that ID to the primitive's path and colour. That is how
colours and paths survive any depth of booleans without guessing by geometry.
Everything that touches manifold3d is in this file.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import manifold3d
import numpy as np

from .paths import Path
from .primitives import Mesh

_Add = manifold3d.OpType.Add
_Intersect = manifold3d.OpType.Intersect


class Origin(NamedTuple):
    """Where a polygon comes from: the path of its primitive and its colour."""

    steps: Path
    colour: tuple[float, float, float]

    @property
    def path(self) -> str:
        return str(self.steps)


@dataclass(frozen=True, slots=True)
class Solid:
    manifold: manifold3d.Manifold
    origins: dict[int, Origin]

    @property
    def empty(self) -> bool:
        return self.manifold.is_empty()

    def triangle_count(self) -> int:
        return self.manifold.num_tri()

    def box(self) -> np.ndarray:
        """(min xyz, max xyz) as a (2, 3) array."""
        return np.array(self.manifold.bounding_box(), dtype=np.float64).reshape(2, 3)

    def prefixed(self, prefix: str) -> "Solid":
        """The same solid with ``prefix`` put in front of every path."""
        return Solid(self.manifold, {i: Origin(o.steps.under(prefix), o.colour)
                                     for i, o in self.origins.items()})

    def transformed(self, matrix: np.ndarray) -> "Solid":
        return Solid(self.manifold.transform(np.ascontiguousarray(matrix[:3, :])), self.origins)


EMPTY = Solid(manifold3d.Manifold(), {})


class EngineError(Exception):
    """manifold3d refused a mesh (not an oriented 2-manifold)."""


def template(mesh: Mesh) -> manifold3d.Manifold:
    """A primitive's mesh in the engine, built once and instanced many times."""
    gl = manifold3d.Mesh64(
        vert_properties=mesh.vertices,
        tri_verts=mesh.triangles.astype(np.uint64),
        face_id=mesh.faces.astype(np.uint64),
    )
    manifold = manifold3d.Manifold(gl)
    if manifold.status() != manifold3d.Error.NoError:
        raise EngineError(str(manifold.status()))
    return manifold


def instance(shape: manifold3d.Manifold, origin: Origin) -> Solid:
    """One use of a primitive: the engine gives it a new ID that every output
    triangle coming from it will carry (as_original is cheap: no rebuilding)."""
    manifold = shape.as_original()
    return Solid(manifold, {manifold.original_id(): origin})


def reinstanced(solid: Solid) -> Solid:
    """A copy of ``solid`` whose origins have new IDs.

    A cached subgraph used twice in one scene must not share IDs with its other
    uses, or the two uses could not be told apart in the output.
    """
    if solid.empty:
        return solid
    gl = solid.manifold.to_mesh64()
    old_ids = np.asarray(gl.run_original_id, dtype=np.int64)
    unique = np.unique(old_ids)
    first = manifold3d.Manifold.reserve_ids(len(unique))
    new_ids = first + np.searchsorted(unique, old_ids)
    def array(values, dtype):
        return np.array(values, dtype=dtype)  # an owned, writable copy: the engine wants one

    copy = manifold3d.Mesh64(
        vert_properties=np.array(np.asarray(gl.vert_properties)[:, :3], dtype=np.float64),
        tri_verts=array(gl.tri_verts, np.uint64),
        run_index=array(gl.run_index, np.uint64),
        run_original_id=array(new_ids, np.uint32),
        face_id=array(gl.face_id, np.uint64),
        merge_from_vert=array(gl.merge_from_vert, np.uint64),
        merge_to_vert=array(gl.merge_to_vert, np.uint64),
    )
    manifold = manifold3d.Manifold(copy)
    mapping = dict(zip(unique.tolist(), range(first, first + len(unique))))
    return Solid(manifold, {mapping[i]: o for i, o in solid.origins.items() if i in mapping})


def _merged_origins(solids) -> dict[int, Origin]:
    origins: dict[int, Origin] = {}
    for s in solids:
        origins.update(s.origins)
    return origins


def _overlap_groups(boxes: np.ndarray) -> list[list[int]]:
    """Groups of operands whose boxes meet (touching counts), by union-find."""
    n = len(boxes)
    parent = list(range(n))

    def find(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    lo, hi = boxes[:, 0, :], boxes[:, 1, :]
    order = np.argsort(lo[:, 0], kind="stable")
    # sweep along x: only operands whose x-intervals meet can overlap
    active: list[int] = []
    for i in order.tolist():
        active = [j for j in active if hi[j, 0] >= lo[i, 0]]
        if active:
            a = np.array(active)
            meet = np.all((lo[a] <= hi[i]) & (lo[i] <= hi[a]), axis=1)
            for j in a[meet].tolist():
                parent[find(j)] = find(i)
        active.append(i)
    groups: dict[int, list[int]] = {}
    for i in range(n):
        groups.setdefault(find(i), []).append(i)
    return list(groups.values())


class Counter:
    """Counts the calls made to the engine, for --stats."""

    def __init__(self):
        self.booleans = 0


def union(solids: list[Solid], counter: Counter) -> Solid:
    """Regularized union; operands whose boxes do not meet are only put together."""
    solids = [s for s in solids if not s.empty]
    if not solids:
        return EMPTY
    if len(solids) == 1:
        return solids[0]
    boxes = np.stack([s.box() for s in solids])
    parts = []
    for group in _overlap_groups(boxes):
        if len(group) == 1:
            parts.append(solids[group[0]].manifold)
        else:
            counter.booleans += 1
            parts.append(manifold3d.Manifold.batch_boolean([solids[i].manifold for i in group], _Add))
    manifold = parts[0] if len(parts) == 1 else manifold3d.Manifold.compose(parts)
    return Solid(manifold, _merged_origins(solids))


def intersection(solids: list[Solid], counter: Counter) -> Solid:
    """Regularized intersection; empty at once if the boxes have no common interior."""
    if not solids or any(s.empty for s in solids):
        return EMPTY
    if len(solids) == 1:
        return solids[0]
    boxes = np.stack([s.box() for s in solids])
    lo, hi = boxes[:, 0, :].max(axis=0), boxes[:, 1, :].min(axis=0)
    if np.any(lo >= hi):
        return EMPTY
    counter.booleans += 1
    manifold = manifold3d.Manifold.batch_boolean([s.manifold for s in solids], _Intersect)
    return Solid(manifold, _merged_origins(solids))


def difference(a: Solid, b: Solid, counter: Counter) -> Solid:
    """Regularized a - b; a itself if the boxes have no common interior."""
    if a.empty or b.empty:
        return a
    box_a, box_b = a.box(), b.box()
    if np.any(np.maximum(box_a[0], box_b[0]) >= np.minimum(box_a[1], box_b[1])):
        return a
    counter.booleans += 1
    return Solid(a.manifold - b.manifold, _merged_origins((a, b)))


class Triangles(NamedTuple):
    vertices: np.ndarray  # (V, 3) float64
    triangles: np.ndarray  # (T, 3) int64
    origin_ids: np.ndarray  # (T,) int64
    face_ids: np.ndarray  # (T,) int64, unique to one flat face of one primitive


def triangles(solid: Solid) -> Triangles:
    """The solid's triangles in double precision, with each one's origin and face."""
    if solid.empty:
        return Triangles(np.zeros((0, 3)), np.zeros((0, 3), np.int64),
                         np.zeros(0, np.int64), np.zeros(0, np.int64))
    gl = solid.manifold.to_mesh64()
    vertices = np.asarray(gl.vert_properties, dtype=np.float64)[:, :3]
    tris = np.asarray(gl.tri_verts, dtype=np.int64)
    # identify vertices that manifold3d split only for properties
    merge_from = np.asarray(gl.merge_from_vert, dtype=np.int64)
    if len(merge_from):
        remap = np.arange(len(vertices))
        remap[merge_from] = np.asarray(gl.merge_to_vert, dtype=np.int64)
        tris = remap[tris]
    run_index = np.asarray(gl.run_index, dtype=np.int64) // 3
    run_ids = np.asarray(gl.run_original_id, dtype=np.int64)
    origin_ids = np.repeat(run_ids, np.diff(run_index))
    # one key for each flat face of each primitive: the origin in the high bits
    face_ids = (origin_ids << 32) | (np.asarray(gl.face_id, dtype=np.int64) & 0xFFFFFFFF)
    return Triangles(vertices, tris, origin_ids, face_ids)

"""The boolean engine, manifold3d, behind one small adapter: the only module
that imports it.

Everything castor asks of the engine is a function here: a mesh in (a
primitive's template), a mesh out (arrays, with the runs that say which
template and placement each triangle comes from), the booleans, moving,
composing and splitting solids. The rest of castor holds the engine's solids
as opaque handles (``Manifold``, or ``Composed``: solids that do not meet, made
one by the engine only when asked) and asks them only for their counts, box,
volume and area (``num_tri()``, ``bounding_box()``, ``volume()``, …).
"""

from __future__ import annotations

from typing import NamedTuple

import manifold3d
import numpy as np

Manifold = manifold3d.Manifold

_Intersect = manifold3d.OpType.Intersect


class EngineError(Exception):
    """manifold3d refused a mesh (not an oriented 2-manifold)."""


class Composed:
    """Solids that do not meet, as the one solid the engine's ``compose`` makes
    of them, made each time it is asked for and never kept.

    A union of thousands of parts is composed into fewer (castor.mesh.booleans,
    MAX_PARTS); the engine's composition copies every triangle (with its sort
    and its tree of boxes, some 300 bytes a triangle), and all of a frame's
    compositions held at once, beside the parts they were made of, were most of
    the memory of 4,096 houses. Held as its parts instead, a composition is made
    when its triangles are read (provenance, a batch at a time) or a boolean
    needs it, and let go after: the same solid, triangle for triangle, in the
    same order. Its counts and box are its parts' (the engine's composition
    adds none and moves none: checked on every composition of 1,024 houses)."""

    __slots__ = ("parts", "_counts", "_box")

    def __init__(self, parts: list):
        self.parts = tuple(parts)
        self._counts: tuple[int, int] | None = None
        self._box: tuple | None = None

    def manifold(self) -> Manifold:
        """The engine's composition, made now. Made at once, not left to the
        engine's lazy tree: a composition of compositions left lazy is flattened
        by the engine into one of all their parts, which orders the triangles
        otherwise."""
        made = manifold3d.Manifold.compose([engine(part) for part in self.parts])
        made.num_tri()  # (any question of the engine's makes it)
        return made

    def num_tri(self) -> int:
        return self._tallied()[0]

    def num_vert(self) -> int:
        return self._tallied()[1]

    def is_empty(self) -> bool:
        return self.num_tri() == 0

    def bounding_box(self) -> tuple:
        if self._box is None:
            boxes = np.array([part.bounding_box() for part in self.parts],
                             dtype=np.float64).reshape(-1, 2, 3)
            self._box = (*boxes[:, 0].min(axis=0).tolist(), *boxes[:, 1].max(axis=0).tolist())
        return self._box

    def _tallied(self) -> tuple[int, int]:
        if self._counts is None:
            self._counts = (sum(part.num_tri() for part in self.parts),
                            sum(part.num_vert() for part in self.parts))
        return self._counts

    def __getattr__(self, name: str):
        # any other question (volume, surface_area, status…): of the composition
        return getattr(self.manifold(), name)


def engine(solid) -> Manifold:
    """The engine's own solid of ``solid`` (a Composed made now)."""
    return solid.manifold() if type(solid) is Composed else solid


# --- into the engine


def from_mesh(vertices: np.ndarray, triangles: np.ndarray, faces: np.ndarray) -> Manifold:
    """The engine's solid of a closed, oriented triangle mesh whose triangles
    carry face numbers (kept through every boolean); EngineError if refused."""
    gl = manifold3d.Mesh64(
        vert_properties=vertices,
        tri_verts=triangles.astype(np.uint64),
        face_id=faces.astype(np.uint64),
    )
    manifold = manifold3d.Manifold(gl)
    if manifold.status() != manifold3d.Error.NoError:
        raise EngineError(str(manifold.status()))
    return manifold


def from_runs(vertices: np.ndarray, triangles: np.ndarray, faces: np.ndarray,
              starts: np.ndarray) -> tuple[Manifold, np.ndarray]:
    """The engine's solid of a closed, oriented triangle mesh castor made itself
    (a smooth solid's refined facets), its triangles in runs beginning at
    ``starts``, each run under an engine ID of its own (returned, one per run)
    so that its triangles keep their origin through any boolean; EngineError
    if refused."""
    first = manifold3d.Manifold.reserve_ids(len(starts))
    ids = np.arange(first, first + len(starts), dtype=np.int64)
    gl = manifold3d.Mesh64(
        vert_properties=np.ascontiguousarray(vertices, dtype=np.float64),
        tri_verts=np.ascontiguousarray(triangles, dtype=np.uint64),
        run_index=(np.r_[starts, len(triangles)] * 3).astype(np.uint64),
        run_original_id=ids.astype(np.uint32),
        face_id=faces.astype(np.uint64))
    manifold = manifold3d.Manifold(gl)
    if manifold.status() != manifold3d.Error.NoError:
        raise EngineError(str(manifold.status()))
    return manifold, ids


def as_original(manifold: Manifold) -> tuple[Manifold, int]:
    """A copy of ``manifold`` under an engine ID of its own, and that ID."""
    copy = engine(manifold).as_original()
    return copy, copy.original_id()


def reserve_ids(count: int) -> int:
    """The first of ``count`` new engine IDs, never given to anything else."""
    return int(manifold3d.Manifold.reserve_ids(count))


def with_run_ids(manifold: Manifold, run_ids: np.ndarray) -> Manifold | None:
    """The same solid, triangle for triangle, whose runs carry the engine IDs
    ``run_ids`` (one per run of ``to_arrays(manifold)``); each run keeps its
    transformation and face numbers. (The engine keeps a mesh's runs when it
    is given them: a round trip through its mesh.) None if the engine would
    not keep the mesh as it is."""
    manifold = engine(manifold)
    gl = manifold.to_mesh64()
    merge_from = np.array(gl.merge_from_vert, dtype=np.uint64)
    copy = manifold3d.Manifold(manifold3d.Mesh64(
        vert_properties=np.array(gl.vert_properties, dtype=np.float64),
        tri_verts=np.array(gl.tri_verts, dtype=np.uint64),
        merge_from_vert=merge_from if len(merge_from) else None,
        merge_to_vert=np.array(gl.merge_to_vert, dtype=np.uint64) if len(merge_from) else None,
        run_index=np.array(gl.run_index, dtype=np.uint64),
        run_original_id=np.array(run_ids, dtype=np.uint32),
        run_transform=np.array(gl.run_transform, dtype=np.float64),
        run_flags=np.array(gl.run_flags, dtype=np.uint8),
        face_id=np.array(gl.face_id, dtype=np.uint64)))
    if (copy.status() != manifold3d.Error.NoError or copy.num_tri() != manifold.num_tri()
            or copy.num_vert() != manifold.num_vert()
            or abs(copy.volume() - manifold.volume()) > 1e-12 * max(1.0, abs(manifold.volume()))
            or not np.array_equal(_corner_rows(gl), _corner_rows(copy.to_mesh64()))):
        # the engine tidies a mesh it is given (it was seen to collapse an
        # edge of a result and lose volume, and to move vertices): then
        # there is no such copy
        return None
    return copy


def _corner_rows(gl) -> np.ndarray:
    """A mesh's triangles as rows of their corners' coordinates (corners in
    order within a row, rows sorted): equal for the same triangles in any
    order and numbering. (Which way each turns is left to the volume.)"""
    corners = np.asarray(gl.vert_properties, dtype=np.float64)[:, :3][
        np.asarray(gl.tri_verts, dtype=np.int64)]  # (T, 3, 3)
    rows = np.sort(corners.view([("", np.float64)] * 3).reshape(len(corners), 3), axis=1)
    rows = rows.view(np.float64).reshape(len(corners), 9)
    return rows[np.lexsort(rows.T[::-1])]


# --- out of the engine


class EngineMesh(NamedTuple):
    """A solid's triangles in double precision, as the engine gives them."""

    vertices: np.ndarray  # (V, 3) float64
    triangles: np.ndarray  # (T, 3) int64
    face_ids: np.ndarray  # (T,) int64: the template's face number of each triangle
    run_index: np.ndarray  # (R + 1,) the first triangle of each run
    run_ids: np.ndarray  # (R,) the engine ID of each run's template
    placements: np.ndarray  # (R, 3, 4) the transformation that placed each run
    merge_from: np.ndarray  # vertices the engine split only for properties…
    merge_to: np.ndarray  # …and the vertex each is one with


def to_arrays(manifold: Manifold) -> EngineMesh:
    """The engine's mesh of ``manifold`` as numpy arrays."""
    gl = engine(manifold).to_mesh64()
    return EngineMesh(
        np.asarray(gl.vert_properties, dtype=np.float64)[:, :3],
        np.asarray(gl.tri_verts, dtype=np.int64),
        np.asarray(gl.face_id, dtype=np.int64) & 0xFFFFFFFF,
        np.asarray(gl.run_index, dtype=np.int64) // 3,
        np.asarray(gl.run_original_id, dtype=np.int64),
        # the engine's transformations are (R, 4, 3), the columns of our 3x4 rows
        np.asarray(gl.run_transform, dtype=np.float64).transpose(0, 2, 1),
        np.asarray(gl.merge_from_vert, dtype=np.int64),
        np.asarray(gl.merge_to_vert, dtype=np.int64),
    )


# --- the engine's operations


def empty() -> Manifold:
    return manifold3d.Manifold()


def add(a: Manifold, b: Manifold) -> Manifold:
    """a + b, the engine's union of two solids."""
    return engine(a) + engine(b)


def subtract(a: Manifold, b: Manifold) -> Manifold:
    """a - b, the engine's difference."""
    return engine(a) - engine(b)


def intersect(a: Manifold, b: Manifold) -> Manifold:
    """a ^ b, the engine's intersection of two solids."""
    return engine(a) ^ engine(b)


def intersect_all(manifolds: list) -> Manifold:
    """The engine's intersection of all at once."""
    return manifold3d.Manifold.batch_boolean([engine(m) for m in manifolds], _Intersect)


def compose(manifolds: list) -> Manifold:
    """Solids that do not meet as one, without a boolean."""
    return manifold3d.Manifold.compose([engine(m) for m in manifolds])


def decompose(manifold: Manifold) -> list:
    """The solid's connected shells, each a solid."""
    return engine(manifold).decompose()


def transform(manifold: Manifold, rows: np.ndarray) -> Manifold:
    """Moved by an affine map (3x4 rows, contiguous)."""
    return engine(manifold).transform(rows)


def triangulate(outline: np.ndarray) -> np.ndarray:
    """Triangles (T, 3) of a simple polygon (N, 2), counter-clockwise."""
    return np.asarray(manifold3d.triangulate([outline]), dtype=np.int64)

"""A solid as castor holds it between booleans: parts whose boxes do not
meet, each the engine's or a placed copy of a template not yet in it, and the
origins of its triangles (castor.mesh.provenance).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from castor.mesh import adapter, keys
from castor.mesh.frame import Origin
from castor.mesh.instances import Placed, Template, fill_boxes, in_engine
from castor.mesh.provenance import NO_ORIGINS, Origins


@dataclass(frozen=True, slots=True)
class Solid:
    """A solid as parts whose bounding boxes do not meet, and its origins.

    A union of operands that do not meet never goes to the engine and is
    never composed into one mesh: it stays a list of parts, so that a forest
    of copies of one tree, or a union of 100,000 operands, costs no more
    than its parts. The engine sees one part, or the composition of all,
    only when a boolean needs it.
    """

    parts: tuple  # never empty: manifolds, and primitives not yet in the engine (Placed)
    origins: Origins
    # each part's content key (castor.mesh.keys), None where not known; None: none known
    keys: tuple | None = None

    def key(self, i: int) -> bytes | None:
        """The content key of part ``i`` (castor.mesh.keys), or None."""
        part = self.parts[i]
        if type(part) is Placed:
            return keys.placed(part.id, part.matrix)
        return None if self.keys is None else self.keys[i]

    def whole_key(self) -> bytes | None:
        """The key of ``whole()``: of its parts, in order."""
        if len(self.parts) == 1:
            return self.key(0)
        return keys.derived(b"W", [self.key(i) for i in range(len(self.parts))])

    @property
    def empty(self) -> bool:
        return not self.parts

    def triangle_count(self) -> int:
        return sum(part.num_tri() for part in self.parts)  # at most booleans.MAX_PARTS calls

    def part_boxes(self) -> np.ndarray:
        """(parts, 2, 3): each part's (min xyz, max xyz)."""
        fill_boxes(self.parts)
        return np.array([part.bounding_box() for part in self.parts],
                        dtype=np.float64).reshape(-1, 2, 3)

    def box(self) -> np.ndarray:
        """(min xyz, max xyz) as a (2, 3) array."""
        if len(self.parts) == 1:
            return np.array(self.parts[0].bounding_box(), dtype=np.float64).reshape(2, 3)
        boxes = self.part_boxes()
        return np.array([boxes[:, 0].min(axis=0), boxes[:, 1].max(axis=0)])

    def whole(self) -> adapter.Manifold:
        """All parts as one manifold, for a boolean that needs them together
        (of a solid whose parts are all in the engine: see ``in_engine``)."""
        if len(self.parts) == 1:
            return self.parts[0]
        return adapter.compose(list(self.parts))

    def in_engine(self, which=None) -> "Solid":
        """The same solid with its parts (or those numbered in ``which``) in the engine."""
        if not any(type(p) is Placed for p in self.parts):
            return self
        parts = list(self.parts)
        known = [self.key(i) for i in range(len(parts))]
        for i in range(len(parts)) if which is None else which:
            parts[i] = in_engine(parts[i])
        return Solid(tuple(parts), self.origins, tuple(known))

    def prefixed(self, prefix: str) -> "Solid":
        """The same solid with ``prefix`` put in front of every path."""
        return Solid(self.parts, self.origins.prefixed(prefix), self.keys)

    def transformed(self, matrix) -> "Solid":
        """Moved by an affine map: a 3x4 or 4x4 matrix, or its 12 numbers row by row."""
        rows = np.asarray(matrix, dtype=np.float64).reshape(-1, 4)[:3]
        full = np.eye(4)
        full[:3] = rows
        m = np.ascontiguousarray(rows)
        moved = None
        if self.keys is not None:
            moved = tuple(None if type(part) is Placed else keys.derived(b"T", [key], m.tobytes())
                          for part, key in zip(self.parts, self.keys))
        return Solid(tuple(part.moved(full) if type(part) is Placed else adapter.transform(part, m)
                           for part in self.parts), self.origins.transformed(m), moved)


def of_parts(manifolds, origins: Origins, known=None) -> Solid:
    """The solid of the engine's results (those not empty) and their origins;
    ``known``: their content keys, in order (castor.mesh.keys), if known."""
    if known is None:
        return Solid(tuple(m for m in manifolds if not m.is_empty()), origins)
    kept = [(m, key) for m, key in zip(manifolds, known) if not m.is_empty()]
    return Solid(tuple(m for m, _ in kept), origins, tuple(key for _, key in kept))


EMPTY = Solid((), NO_ORIGINS)


_IDENTITY = np.eye(4)[:3]


def instance(shape: Template, origin: Origin, matrix=None) -> Solid:
    """One use of a primitive, placed by ``matrix`` (its 12 numbers row by row, or
    None); it enters the engine only if a boolean needs it."""
    rows = (_IDENTITY.copy() if matrix is None
            else np.array(matrix, dtype=np.float64).reshape(3, 4))
    return Solid((Placed(shape, rows),), Origins.one(shape.id, rows, origin))  # neither changes it

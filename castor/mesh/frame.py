"""What one '>' command produces: the polygons of each object, ready to write."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np

from castor.csg.paths import Path


class Origin(NamedTuple):
    """Where a polygon comes from: the path of its primitive and its colour."""

    steps: Path
    colour: tuple[float, float, float]

    @property
    def path(self) -> str:
        return str(self.steps)


@dataclass
class FrameObject:
    """One object of a '>' command: a closed surface of convex polygons."""

    vertices: np.ndarray  # (V, 3) float64, every vertex used
    offsets: np.ndarray  # (P + 1,) start of each polygon in indices
    indices: np.ndarray  # vertex numbers, counter-clockwise seen from outside
    origin_of: np.ndarray  # (P,) index into origins
    origins: list[Origin]
    name: str = ""  # the '>' command's object: its name, or objectK
    where: str = ""  # FILE:LINE of its definition, or of the '>' command

    @property
    def polygon_count(self) -> int:
        return len(self.offsets) - 1

    def edge_count(self) -> int:
        start = self.indices
        following = np.arange(1, len(start) + 1)
        following[self.offsets[1:] - 1] = self.offsets[:-1]
        a, b = start, start[following]
        return len(np.unique(np.minimum(a, b) * (len(self.vertices) + 1) + np.maximum(a, b)))


@dataclass
class Frame:
    number: int
    where: str  # FILE:LINE of the '>' command
    objects: list[FrameObject] = field(default_factory=list)
    parameters: dict[str, float] = field(default_factory=dict)  # in force at the '>'

    @property
    def polygon_count(self) -> int:
        return sum(o.polygon_count for o in self.objects)


def compact(pieces, origin_table, name: str = "") -> FrameObject:
    """One object from its parts' polygons: vertices and origins compacted to
    those the polygons use."""
    if not pieces:
        return FrameObject(np.zeros((0, 3)), np.zeros(1, np.int64), np.zeros(0, np.int64),
                           np.zeros(0, np.int64), [], name)
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
                       origin_of.ravel().astype(np.int64), origins, name)

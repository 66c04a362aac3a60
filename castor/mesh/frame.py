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
    name: str | None = None  # the '>' command's object ('maison'), for the formats' names

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

    @property
    def polygon_count(self) -> int:
        return sum(o.polygon_count for o in self.objects)

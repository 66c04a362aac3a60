"""castor's polygon stream read back (OUTPUT.md), as any other program reads it."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np


@dataclass
class Polygon:
    path: str
    colour: tuple[float, float, float]
    points: np.ndarray  # (n, 3)


@dataclass
class Frame:
    number: int
    where: str
    polygons: list[Polygon] = field(default_factory=list)

    def volume(self) -> float:
        return sum(_fan_volume(p.points) for p in self.polygons)

    def box(self) -> np.ndarray:
        pts = np.concatenate([p.points for p in self.polygons])
        return np.array([pts.min(axis=0), pts.max(axis=0)])

    def area(self, colour=None, path_part=None) -> float:
        total = 0.0
        for p in self.polygons:
            if colour is not None and p.colour != tuple(colour):
                continue
            if path_part is not None and path_part not in p.path:
                continue
            total += np.linalg.norm(newell(p.points)) / 2
        return total

    def colours(self) -> set:
        return {p.colour for p in self.polygons}

    def paths(self) -> set:
        return {p.path for p in self.polygons}


def parse_stream(text: str) -> list[Frame]:
    lines = text.splitlines()
    assert lines and lines[0] == "castor-polygons 1", "missing header"
    frames: list[Frame] = []
    current = None
    for line in lines[1:]:
        fields = line.split(" ")
        if fields[0] == "frame":
            assert current is None, "frame inside a frame"
            current = Frame(int(fields[1]), fields[2])
        elif fields[0] == "poly":
            path = fields[1]
            colour = tuple(float(x) for x in fields[2:5])
            n = int(fields[5])
            coords = [float(x) for x in fields[6:]]
            assert len(coords) == 3 * n, f"vertex count mismatch in {line[:80]}"
            current.polygons.append(Polygon(path, colour, np.array(coords).reshape(n, 3)))
        elif fields[0] == "endframe":
            assert int(fields[1]) == current.number
            assert int(fields[2]) == len(current.polygons), "endframe count mismatch"
            frames.append(current)
            current = None
        else:
            raise AssertionError(f"unknown record: {line[:80]}")
    assert current is None, "frame not ended"
    return frames


def newell(points: np.ndarray) -> np.ndarray:
    """Twice the polygon's vector area (Newell), taken about its centre: about
    the origin, the rounding of coordinates of 2 swamps the normal of a
    triangle 2e-4 long and 1e-10 high, and a planar one read as tilted."""
    points = points - points.mean(axis=0)
    nxt = np.roll(points, -1, axis=0)
    return np.cross(points, nxt).sum(axis=0)


def _fan_volume(points: np.ndarray) -> float:
    a = points[0]
    total = 0.0
    for i in range(1, len(points) - 1):
        total += float(np.dot(a, np.cross(points[i], points[i + 1]))) / 6
    return total

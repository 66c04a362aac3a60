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
        """The signed volume enclosed: each polygon a fan of triangles from its
        first corner, all the frame's triangles at once (a forest of 400 trees
        took a minute one triangle at a time)."""
        corners, starts = self.arrays()
        fans = np.maximum(np.diff(starts) - 2, 0)
        first = np.repeat(starts[:-1], fans)
        k = np.arange(int(fans.sum())) - np.repeat(np.cumsum(fans) - fans, fans)
        a, b, c = corners[first], corners[first + k + 1], corners[first + k + 2]
        each = (np.einsum("ij,ij->i", a, np.cross(b, c)) / 6).tolist()
        # summed as one polygon at a time would be, in the same order
        total, at = 0, 0
        for count in fans.tolist():
            polygon = 0.0
            for value in each[at:at + count]:
                polygon += value
            total += polygon
            at += count
        return total

    def arrays(self):
        """All the corners (C, 3), and where each polygon's start (P + 1,)."""
        sizes = [len(p.points) for p in self.polygons]
        if not sizes:
            return np.zeros((0, 3)), np.zeros(1, np.int64)
        corners = np.concatenate([np.asarray(p.points, dtype=np.float64).reshape(-1, 3)
                                  for p in self.polygons])
        return corners, np.concatenate([[0], np.cumsum(sizes)]).astype(np.int64)

    def box(self) -> np.ndarray:
        pts = np.concatenate([p.points for p in self.polygons])
        return np.array([pts.min(axis=0), pts.max(axis=0)])

    def area(self, colour=None, path_part=None) -> float:
        """The polygons' area (of those of a colour, or whose path holds
        ``path_part``): each polygon's Newell normal about its centre, as
        ``newell`` takes it, all polygons at once."""
        corners, starts = self.arrays()
        sizes = np.diff(starts)
        if not len(sizes):
            return 0.0
        polygon = np.repeat(np.arange(len(sizes)), sizes)
        centre = np.add.reduceat(corners, starts[:-1], axis=0) / sizes[:, None]
        about = corners - centre[polygon]
        following = np.arange(len(corners)) + 1
        following[starts[1:] - 1] = starts[:-1]
        normal = np.zeros((len(sizes), 3))
        np.add.at(normal, polygon, np.cross(about, about[following]))
        halves = (np.linalg.norm(normal, axis=1) / 2).tolist()
        total = 0.0
        for p, half in zip(self.polygons, halves):
            if colour is not None and p.colour != tuple(colour):
                continue
            if path_part is not None and path_part not in p.path:
                continue
            total += half
        return total

    def colours(self) -> set:
        return {p.colour for p in self.polygons}

    def paths(self) -> set:
        return {p.path for p in self.polygons}


def parse_stream(text: str) -> list[Frame]:
    """The frames of a polygon stream, checked as it is read: records in
    order, vertex counts, each frame's polygon count. A frame's coordinates
    are read in one go (a forest of 400 trees is 28 MB of them)."""
    lines = text.splitlines()
    assert lines and lines[0] == "castor-polygons 1", "missing header"
    frames: list[Frame] = []
    current = None
    heads: list = []
    coordinates: list[str] = []
    for line in lines[1:]:
        fields = line.split(" ", 6)
        if fields[0] == "frame":
            assert current is None, "frame inside a frame"
            current = Frame(int(fields[1]), line.split(" ")[2])
            heads, coordinates = [], []
        elif fields[0] == "poly":
            assert current is not None, "poly outside a frame"
            n = int(fields[5])
            values = fields[6] if len(fields) > 6 else ""
            count = values.count(" ") + 1 if values else 0
            assert count == 3 * n, f"vertex count mismatch in {line[:80]}"
            heads.append((fields[1], tuple(float(x) for x in fields[2:5]), n))
            coordinates.append(values)
        elif fields[0] == "endframe":
            assert int(fields[1]) == current.number
            assert int(fields[2]) == len(heads), "endframe count mismatch"
            points = np.fromstring(" ".join(coordinates), sep=" ").reshape(-1, 3)
            at = 0
            for path, colour, n in heads:
                current.polygons.append(Polygon(path, colour, points[at:at + n]))
                at += n
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

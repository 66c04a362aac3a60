"""Read castor's polygon stream back and check the geometry a test needs.

Kept independent of castor's own modules, so that the tests judge the output
as any other program reading the stream would.
"""

from __future__ import annotations

import subprocess
import sys
import tempfile
from collections import Counter
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
            total += np.linalg.norm(_newell(p.points)) / 2
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


def _newell(points: np.ndarray) -> np.ndarray:
    nxt = np.roll(points, -1, axis=0)
    return np.cross(points, nxt).sum(axis=0)


def _fan_volume(points: np.ndarray) -> float:
    a = points[0]
    total = 0.0
    for i in range(1, len(points) - 1):
        total += float(np.dot(a, np.cross(points[i], points[i + 1]))) / 6
    return total


def check_closed(frame: Frame) -> None:
    """Every directed edge is matched by exactly one opposite edge (by exact position)."""
    edges = Counter()
    for p in frame.polygons:
        pts = [tuple(v) for v in p.points.tolist()]
        for i in range(len(pts)):
            edges[(pts[i], pts[(i + 1) % len(pts)])] += 1
    for (a, b), count in edges.items():
        assert count == 1, f"edge {a}->{b} used {count} times"
        assert edges.get((b, a)) == 1, f"edge {a}->{b} has no opposite edge"


def check_convex_planar(frame: Frame, slack: float = 1e-7) -> None:
    for p in frame.polygons:
        pts = p.points
        assert len(pts) >= 3
        normal = _newell(pts)
        length = np.linalg.norm(normal)
        assert length > 0, f"degenerate polygon {p.path}"
        normal /= length
        size = np.ptp(pts, axis=0).max()
        distance = (pts - pts.mean(axis=0)) @ normal
        assert np.abs(distance).max() <= slack * max(size, 1.0), f"non-planar polygon {p.path}"
        edges = np.roll(pts, -1, axis=0) - pts
        turns = np.cross(edges, np.roll(edges, -1, axis=0)) @ normal
        scale = np.linalg.norm(edges, axis=1) * np.linalg.norm(np.roll(edges, -1, axis=0), axis=1)
        assert np.all(turns >= -slack * scale), f"non-convex polygon {p.path}"


def check_solid(frame: Frame) -> None:
    check_closed(frame)
    check_convex_planar(frame)
    if frame.polygons:
        assert frame.volume() > 0, "surface is not outward oriented"


def run(*args, stdin: str | None = None, cwd=None, check_status=None):
    """Run castor; returns (status, stdout, stderr)."""
    # run outside the source tree, so that the installed package is what runs
    result = subprocess.run([sys.executable, "-m", "castor", *args], input=stdin,
                            capture_output=True, text=True, cwd=cwd or tempfile.gettempdir(),
                            timeout=600)
    assert "Traceback" not in result.stderr, result.stderr
    if check_status is not None:
        assert result.returncode == check_status, result.stderr
    return result.returncode, result.stdout, result.stderr


def frames_of(scene: str, *args) -> list[Frame]:
    """Facetize a scene given as text; fails on any error message."""
    status, out, err = run("--no-cpp", *args, stdin=scene)
    assert status == 0, err
    return parse_stream(out)

"""A quantity take-off: the figures of a frame's objects, for --stats and --summary.

Pure functions from a mesh frame (castor/mesh/frame.py) to numbers an architect
uses to price a facade or check a floor area: volume, surface area, bounding
box, shells (separate solids), polygons, and the area of each colour. Volumes
and areas are those of the written polygons, in scene units.
"""

from __future__ import annotations

import json
from typing import NamedTuple

import numpy as np

from castor.mesh.frame import Frame, FrameObject
from castor.mesh.arrays import components


class Figures(NamedTuple):
    name: str
    volume: float
    area: float
    bbox: tuple[tuple[float, float, float], tuple[float, float, float]] | None
    shells: int
    polygons: int
    vertices: int
    colours: list[tuple[tuple[float, float, float], float]]  # (rgb, area), largest first


def _triangle_figures(obj: FrameObject, centre: np.ndarray) -> tuple[np.ndarray, ...]:
    """Six times the signed volume of each fan triangle's tetrahedron from
    ``centre``, its area, and its polygon's origin: made a piece of polygons at
    a time, so that no (T, 3, 3) array of corners is held (72 bytes a triangle,
    and as much again for each temporary); each figure is the same number."""
    from castor.formats._mesh import CHUNK
    from castor.mesh.arrays import fan_triangles

    count = int(np.maximum(np.diff(obj.offsets) - 2, 0).sum())
    volumes, areas, origins = np.empty(count), np.empty(count), np.empty(count, np.int64)
    done = 0
    for first in range(0, obj.polygon_count, CHUNK):
        last = min(first + CHUNK, obj.polygon_count)
        start, end = obj.offsets[first], obj.offsets[last]
        tris, polygon = fan_triangles(obj.offsets[first:last + 1] - start, obj.indices[start:end])
        corners = obj.vertices[tris]
        a, b, c = corners[:, 0] - centre, corners[:, 1] - centre, corners[:, 2] - centre
        part = slice(done, done + len(tris))
        volumes[part] = np.einsum("ij,ij->i", a, np.cross(b, c))
        areas[part] = np.linalg.norm(np.cross(b - a, c - a), axis=1) / 2
        origins[part] = obj.origin_of[first + polygon]
        done += len(tris)
    return volumes, areas, origins


def shell_count(obj: FrameObject) -> int:
    """How many separate closed surfaces the object has (polygons joined by shared
    vertices), by label propagation with pointer jumping: no Python loop over
    vertices."""
    used = np.unique(obj.indices)
    if len(used) == 0:
        return 0
    following = np.arange(1, len(obj.indices) + 1)
    following[obj.offsets[1:] - 1] = obj.offsets[:-1]
    a, b = obj.indices, obj.indices[following]
    label = components(len(obj.vertices), a, b)
    return len(np.unique(label[used]))


def object_figures(obj: FrameObject, name: str) -> Figures:
    """The figures of one object."""
    if obj.polygon_count == 0:
        return Figures(name, 0.0, 0.0, None, 0, 0, 0, [])
    centre = (obj.vertices.min(axis=0) + obj.vertices.max(axis=0)) / 2
    volumes, areas, origin_of_triangle = _triangle_figures(obj, centre)
    volume = float(volumes.sum() / 6)
    origin_area = np.bincount(origin_of_triangle, weights=areas, minlength=len(obj.origins))
    by_colour: dict[tuple, float] = {}
    for origin, area in zip(obj.origins, origin_area.tolist()):
        key = tuple(float(x) for x in origin.colour)
        by_colour[key] = by_colour.get(key, 0.0) + area
    colours = sorted(by_colour.items(), key=lambda item: -item[1])
    low, high = obj.vertices.min(axis=0).tolist(), obj.vertices.max(axis=0).tolist()
    return Figures(name, volume, float(areas.sum()), (tuple(low), tuple(high)),
                   shell_count(obj), obj.polygon_count, len(obj.vertices), colours)


def frame_figures(frame: Frame) -> list[Figures]:
    """The figures of each object of the frame, named as the mesh formats name them."""
    from castor.formats._mesh import object_names

    return [object_figures(obj, name) for obj, name in zip(frame.objects, object_names(frame))]


def _g(x: float) -> str:
    """A figure as a person reads it: 6 significant digits, no '-0'."""
    text = f"{x:.6g}"
    return "0" if text in ("-0", "0") else text


def stats_line(frame: Frame, primitives: int, booleans: int, seconds: float) -> str:
    """The --stats line of a frame (CLI.md)."""
    figures = frame_figures(frame)
    boxes = [f.bbox for f in figures if f.bbox is not None]
    if boxes:
        low = np.min([b[0] for b in boxes], axis=0)
        high = np.max([b[1] for b in boxes], axis=0)
        box = f"box {' '.join(map(_g, low))} to {' '.join(map(_g, high))}"
    else:
        box = "no box (empty)"
    return (f"castor: frame {frame.number} {frame.where}: {_count(primitives, 'primitive')}, "
            f"{_count(booleans, 'boolean operation')}, "
            f"{_count(sum(f.polygons for f in figures), 'polygon')}, "
            f"{_count(sum(f.vertices for f in figures), 'vertex', 'vertices')}, "
            f"volume {_g(sum(f.volume for f in figures))}, "
            f"area {_g(sum(f.area for f in figures))}, {box}, {seconds:.3f} s")


def _count(n: int, one: str, many: str | None = None) -> str:
    return f"{n} {one if n == 1 else (many or one + 's')}"


def _number(x: float) -> float | int:
    """JSON numbers without noise: 12 significant digits, whole numbers as integers."""
    x = float(f"{x:.12g}") + 0.0
    return int(x) if x.is_integer() and abs(x) < 1e15 else x


def summary_record(frame: Frame) -> dict:
    """One frame of the --summary document (OUTPUT.md, "Quantities")."""
    objects = []
    for f in frame_figures(frame):
        objects.append({
            "name": f.name,
            "volume": _number(f.volume),
            "area": _number(f.area),
            "bbox": [[_number(x) for x in corner] for corner in f.bbox] if f.bbox else None,
            "shells": f.shells,
            "polygons": f.polygons,
            "colours": [{"rgb": [_number(c) for c in rgb], "area": _number(area)}
                        for rgb, area in f.colours],
        })
    return {"number": frame.number, "where": frame.where, "objects": objects}


class Summary:
    """Collects each frame's record; ``text`` is the --summary document."""

    def __init__(self):
        self.frames: list[dict] = []

    def add(self, frame: Frame) -> None:
        self.frames.append(summary_record(frame))

    def text(self) -> str:
        frames = sorted(self.frames, key=lambda record: record["number"])
        # one line per object: readable, and still easy for grep
        parts = []
        for record in frames:
            head = json.dumps({k: v for k, v in record.items() if k != "objects"})[:-1]
            objects = ",\n   ".join(json.dumps(o) for o in record["objects"])
            parts.append(f' {head}, "objects": [\n   {objects}]}}' if objects
                         else f' {head}, "objects": []}}')
        return '{"frames": [\n' + ",\n".join(parts) + "]}\n"

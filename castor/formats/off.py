"""Geomview OFF with a colour for each face (integers 0..255, as MeshLab writes them).

OpenSCAD reads an OFF file straight into CGAL's exact polyhedra, whose booleans
stop with an assertion at a face whose vertices are not exactly on one plane
(a rotated quad, by a rounding) or that has a corner of 180 degrees (a vertex in
the middle of a straight edge, where a neighbouring polygon ends). So a polygon
is written whole only where it is exactly planar, lying in a plane x, y or z =
constant, and has no straight corner; any other is written as triangles with
true corners. Polygons of more than four vertices are cut into convex quads,
because some readers (trimesh's OFF loader) take nothing larger.
"""

from __future__ import annotations

from typing import Iterator

import numpy as np

from castor.formats import WriteInfo
from castor.mesh.frame import Frame
from castor.formats._mesh import (CHUNK, byte_colours, pieces, split_large, straight_corners,
                                  triangle_counts, triangles, vertex_bases)
from castor.formats.cps import StreamError, StreamFrame, number_strings


def _axis_aligned(vertices: np.ndarray, offsets: np.ndarray, indices: np.ndarray) -> np.ndarray:
    """(P,) which polygons lie in a plane x, y or z = constant: exactly planar."""
    if len(indices) == 0:
        return np.zeros(len(offsets) - 1, bool)
    p = vertices[indices]
    starts = offsets[:-1]
    low = np.minimum.reduceat(p, starts, axis=0)
    high = np.maximum.reduceat(p, starts, axis=0)
    return np.any(low == high, axis=1)


def _whole(vertices: np.ndarray, offsets: np.ndarray, indices: np.ndarray) -> np.ndarray:
    """(P,) which polygons are written whole (perhaps cut into quads), not as triangles."""
    return (np.diff(offsets) == 3) | (_axis_aligned(vertices, offsets, indices)
                                     & ~straight_corners(vertices, offsets, indices))


def face_count(vertices: np.ndarray, offsets: np.ndarray, indices: np.ndarray) -> int:
    """How many faces ``faces`` makes of these polygons, without making them."""
    sizes = np.diff(offsets)
    whole = _whole(vertices, offsets, indices)
    # a polygon of n > 4 vertices becomes a fan of (n - 1) // 2 quads (the last
    # perhaps a triangle); one cut into triangles, as many as it takes
    counts = np.where(sizes > 4, (sizes - 1) // 2, 1)
    if not whole.all():
        counts = np.where(whole, counts, triangle_counts(vertices, offsets, indices))
    return int(counts.sum())


def faces(vertices: np.ndarray, offsets: np.ndarray, indices: np.ndarray,
          colours: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The faces OFF readers take: (offsets, indices, colours) of convex faces of at
    most four vertices, each exactly planar, none with a straight corner."""
    whole = _whole(vertices, offsets, indices)
    if not whole.all():
        tris, polygon = triangles(vertices, offsets, indices)
        cut = ~whole[polygon]
        parts = [(p, indices[offsets[p]:offsets[p + 1]]) for p in np.flatnonzero(whole)]
        parts += list(zip(polygon[cut].tolist(), tris[cut]))
        parts.sort(key=lambda part: part[0])
        owner = np.array([p for p, _ in parts], np.int64)
        new_sizes = np.array([len(f) for _, f in parts], np.int64)
        offsets = np.zeros(len(parts) + 1, np.int64)
        np.cumsum(new_sizes, out=offsets[1:])
        indices = np.concatenate([f for _, f in parts]) if parts else np.zeros(0, np.int64)
        colours = colours[owner]
    return split_large(offsets, indices, colours)


def export_chunks(frame: Frame, path: str | None = None, size: int | None = None) -> Iterator[bytes]:
    """The file a piece at a time: the counts, the vertices, then the faces."""
    bases = vertex_bases(frame)
    count = sum(face_count(p.vertices, p.offsets, p.indices) for p in pieces(frame, size))
    yield f"OFF\n{bases[-1]} {count} 0\n".encode("ascii")
    step = size or CHUNK
    for obj in frame.objects:
        for first in range(0, len(obj.vertices), step):
            numbers = number_strings(obj.vertices[first:first + step])
            yield ("\n".join(" ".join(numbers[i:i + 3]) for i in range(0, len(numbers), 3))
                   + "\n").encode("ascii")
    for piece in pieces(frame, size):
        offsets, indices, colours = faces(piece.vertices, piece.offsets, piece.indices,
                                          piece.colours())
        sizes = np.diff(offsets).tolist()
        if not sizes:
            continue
        bounds = offsets.tolist()
        words = (indices + bases[piece.number]).astype(str).tolist()
        rgb = [f"{r} {g} {b}" for r, g, b in byte_colours(colours).tolist()]
        yield ("\n".join(f"{sizes[p]} {' '.join(words[bounds[p]:bounds[p + 1]])} {rgb[p]}"
                         for p in range(len(sizes))) + "\n").encode("ascii")


def export(frame: Frame, path: str | None = None) -> bytes:
    return b"".join(export_chunks(frame, path))


def load(text: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """An OFF file read back: (points polygon after polygon, offsets, colours 0..1),
    each face's colour as written (0..255 integers or 0..1 numbers), grey if none.
    Raises ValueError on a malformed file."""
    words = []
    for line in text.splitlines():
        line = line.split("#", 1)[0].split()
        if line:
            words.append(line)
    if not words or words[0][0] not in ("OFF", "COFF"):
        raise ValueError("not an OFF file (it does not begin with OFF)")
    counts = words[0][1:] or words[1]
    start = 1 if words[0][1:] else 2
    n_vertices, n_faces = int(counts[0]), int(counts[1])
    vertices = np.array([w[:3] for w in words[start:start + n_vertices]], dtype=np.float64)
    points, offsets, colours = [], [0], []
    for face in words[start + n_vertices:start + n_vertices + n_faces]:
        size = int(face[0])
        points.append(vertices[np.array(face[1:1 + size], dtype=np.int64)])
        offsets.append(offsets[-1] + size)
        rgb = np.array(face[1 + size:4 + size], dtype=np.float64)
        if len(rgb) < 3:
            rgb = np.full(3, 0.8)
        elif any("." not in w for w in face[1 + size:4 + size]) and rgb.max() > 1:
            rgb = rgb / 255.0
        colours.append(rgb)
    return (np.concatenate(points) if points else np.zeros((0, 3)),
            np.array(offsets, np.int64), np.array(colours, dtype=np.float64).reshape(-1, 3))


def read(path: str) -> Iterator[StreamFrame]:
    """An OFF file as one frame, read beside its writer: trimesh drops OFF colours."""
    try:
        with open(path, encoding="utf-8", errors="replace") as handle:
            points, offsets, colours = load(handle.read())
    except (OSError, ValueError, IndexError) as exc:
        raise StreamError(f"{path}: cannot read this OFF file ({exc})") from None
    yield StreamFrame(1, path, points, offsets, colours)


def write(frame: Frame, info: WriteInfo) -> Iterator[bytes]:
    """The registry's writer (castor.formats): the frame a piece at a time."""
    return export_chunks(frame, info.path)

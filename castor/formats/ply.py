"""Binary PLY: triangles, with colours on the vertices and on the faces.

Blender reads only vertex colours and MeshLab shows either, so each vertex
carries the colour of its faces: a vertex where faces of two colours meet is
written once per colour. Faces keep their own colour too. Every face is a
triangle, the form every PLY reader takes (trimesh's binary reader refuses
faces of mixed lengths).
"""

from __future__ import annotations

from typing import Iterator

import numpy as np

from castor.formats import WriteInfo
from castor.mesh.frame import Frame
from castor.formats._mesh import (CHUNK, Piece, byte_colours, pieces, triangles,
                                  vertex_bases)
from castor.formats._trimesh import read_with_trimesh

_VERTEX = np.dtype([("xyz", "<f8", 3), ("rgb", "u1", 3)])
_FACE = np.dtype([("count", "u1"), ("indices", "<i4", 3), ("rgb", "u1", 3)])


def _coloured_corners(piece: Piece, base: int) -> tuple[np.ndarray, np.ndarray]:
    """(T, 3) a key for each corner of the piece's triangles: its vertex in the
    frame's combined list and its colour, as vertex * 2**24 + 0xRRGGBB (in the
    order of (vertex, red, green, blue)); and (T, 3) the triangles' colours."""
    tris, polygon = triangles(piece.vertices, piece.offsets, piece.indices)
    face_colour = byte_colours(piece.colours())[polygon] if len(tris) else np.zeros((0, 3), np.uint8)
    rgb = face_colour.astype(np.int64) @ np.array([1 << 16, 1 << 8, 1], np.int64)
    return ((tris + base) << 24) | rgb[:, None], face_colour


def export_chunks(frame: Frame, path: str | None = None, size: int | None = None) -> Iterator[bytes]:
    """The file a piece at a time: one vertex per (vertex, colour) pair, numbered
    in the order of the pair, so the pairs are gathered (not the triangles) first."""
    bases = vertex_bases(frame)
    seen, face_count = [], 0
    for piece in pieces(frame, size):
        keys, _ = _coloured_corners(piece, bases[piece.number])
        seen.append(np.unique(keys))
        face_count += len(keys)
    unique = np.unique(np.concatenate(seen)) if seen else np.zeros(0, np.int64)
    del seen
    header = "\n".join([
        "ply", "format binary_little_endian 1.0", "comment castor: one frame",
        f"element vertex {len(unique)}",
        "property double x", "property double y", "property double z",
        "property uchar red", "property uchar green", "property uchar blue",
        f"element face {face_count}",
        "property list uchar int vertex_indices",
        "property uchar red", "property uchar green", "property uchar blue",
        "end_header"]) + "\n"
    yield header.encode("ascii")
    step = size or CHUNK
    # the objects' vertices are consecutive in the combined list, so are their pairs
    bounds = np.searchsorted(unique, np.array(bases, np.int64) << 24).tolist()
    for number, obj in enumerate(frame.objects):
        for first in range(bounds[number], bounds[number + 1], step):
            keys = unique[first:min(first + step, bounds[number + 1])]
            vertex = np.zeros(len(keys), dtype=_VERTEX)
            vertex["xyz"] = obj.vertices[(keys >> 24) - bases[number]]
            vertex["rgb"] = np.stack([(keys >> 16) & 255, (keys >> 8) & 255, keys & 255], axis=1)
            yield vertex.tobytes()
    for piece in pieces(frame, size):
        keys, face_colour = _coloured_corners(piece, bases[piece.number])
        faces = np.zeros(len(keys), dtype=_FACE)
        faces["count"] = 3
        faces["indices"] = np.searchsorted(unique, keys)
        faces["rgb"] = face_colour
        yield faces.tobytes()


def export(frame: Frame, path: str | None = None) -> bytes:
    return b"".join(export_chunks(frame, path))


def read(path: str):
    """A PLY file as one frame, coloured by its vertices."""
    return read_with_trimesh(path)


def write(frame: Frame, info: WriteInfo) -> Iterator[bytes]:
    """The registry's writer (castor.formats): the frame a piece at a time."""
    return export_chunks(frame, info.path)

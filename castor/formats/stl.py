"""STL, binary (default) or ASCII: triangles only, no colour.

Both are written a piece of the frame at a time (``export_chunks``,
``export_ascii_chunks``); binary STL gives its triangle count first, so the
triangles are counted (not made) in a pass before.
"""

from __future__ import annotations

from typing import Iterator

import numpy as np

from castor.formats import WriteInfo
from castor.mesh.frame import Frame
from castor.formats._mesh import Piece, pieces, triangle_counts, triangles
from castor.formats._trimesh import read_with_trimesh

_RECORD = np.dtype([("normal", "<f4", 3), ("corners", "<f4", (3, 3)), ("attribute", "<u2")])


def _triangles(piece: Piece) -> tuple[np.ndarray, np.ndarray]:
    """(T, 3, 3) the corners of the piece's triangles and (T, 3) their unit normals."""
    tris, _ = triangles(piece.vertices, piece.offsets, piece.indices)
    corners = piece.vertices[tris]  # (T, 3, 3)
    normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    lengths = np.linalg.norm(normals, axis=1, keepdims=True)
    normals = np.divide(normals, lengths, out=np.zeros_like(normals), where=lengths > 0)
    return corners, normals


def export_chunks(frame: Frame, path: str | None = None, size: int | None = None) -> Iterator[bytes]:
    count = sum(int(triangle_counts(p.vertices, p.offsets, p.indices).sum())
                for p in pieces(frame, size))
    yield b"castor binary STL".ljust(80, b" ") + np.uint32(count).tobytes()
    for piece in pieces(frame, size):
        corners, normals = _triangles(piece)
        data = np.zeros(len(corners), dtype=_RECORD)
        data["normal"] = normals
        data["corners"] = corners
        yield data.tobytes()


def export(frame: Frame, path: str | None = None) -> bytes:
    return b"".join(export_chunks(frame, path))


def export_ascii_chunks(frame: Frame, path: str | None = None,
                        size: int | None = None) -> Iterator[bytes]:
    yield b"solid castor\n"
    for piece in pieces(frame, size):
        corners, normals = _triangles(piece)
        out = []
        for n, c in zip(normals.tolist(), corners.tolist()):
            out.append(f"  facet normal {n[0]!r} {n[1]!r} {n[2]!r}\n    outer loop")
            for v in c:
                out.append(f"      vertex {v[0]!r} {v[1]!r} {v[2]!r}")
            out.append("    endloop\n  endfacet")
        if out:
            yield ("\n".join(out) + "\n").encode("ascii")
    yield b"endsolid castor\n"


def export_ascii(frame: Frame, path: str | None = None) -> bytes:
    return b"".join(export_ascii_chunks(frame, path))


def read(path: str):
    """An STL file, binary or ASCII, as one frame (grey: STL has no colour)."""
    return read_with_trimesh(path)


def write(frame: Frame, info: WriteInfo) -> Iterator[bytes]:
    """The registry's writer for binary STL (castor.formats): a piece at a time."""
    return export_chunks(frame, info.path)


def write_ascii(frame: Frame, info: WriteInfo) -> Iterator[bytes]:
    """The registry's writer for ASCII STL (castor.formats): a piece at a time."""
    return export_ascii_chunks(frame, info.path)

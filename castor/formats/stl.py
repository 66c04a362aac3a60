"""STL, binary (default) or ASCII: triangles only, no colour."""

from __future__ import annotations

import numpy as np

from castor.mesh.frame import Frame
from castor.formats._mesh import combine, triangles


def _triangles(frame: Frame) -> tuple[np.ndarray, np.ndarray]:
    mesh = combine(frame)
    tris, _ = triangles(mesh.vertices, mesh.offsets, mesh.indices)
    corners = mesh.vertices[tris]  # (T, 3, 3)
    normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    lengths = np.linalg.norm(normals, axis=1, keepdims=True)
    normals = np.divide(normals, lengths, out=np.zeros_like(normals), where=lengths > 0)
    return corners, normals


def export(frame: Frame, path: str | None = None) -> bytes:
    corners, normals = _triangles(frame)
    record = np.dtype([("normal", "<f4", 3), ("corners", "<f4", (3, 3)), ("attribute", "<u2")])
    data = np.zeros(len(corners), dtype=record)
    data["normal"] = normals
    data["corners"] = corners
    header = b"castor binary STL".ljust(80, b" ")
    return header + np.uint32(len(corners)).tobytes() + data.tobytes()


def export_ascii(frame: Frame, path: str | None = None) -> bytes:
    corners, normals = _triangles(frame)
    out = ["solid castor"]
    for n, c in zip(normals.tolist(), corners.tolist()):
        out.append(f"  facet normal {n[0]!r} {n[1]!r} {n[2]!r}\n    outer loop")
        for v in c:
            out.append(f"      vertex {v[0]!r} {v[1]!r} {v[2]!r}")
        out.append("    endloop\n  endfacet")
    out.append("endsolid castor")
    return ("\n".join(out) + "\n").encode("ascii")

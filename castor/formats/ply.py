"""Binary PLY: double-precision vertices, triangles with a colour each.

Each convex polygon is written as a fan of triangles: every face then has the
same length, which is the form every PLY reader takes (trimesh's binary reader
refuses faces of mixed lengths).
"""

from __future__ import annotations

import numpy as np

from castor.mesh.frame import Frame
from castor.mesh.polygons import fan_triangles
from castor.formats._mesh import byte_colours, combine


def write(frame: Frame, stream) -> None:
    mesh = combine(frame)
    tris, polygon = fan_triangles(mesh.offsets, mesh.indices)
    header = "\n".join([
        "ply", "format binary_little_endian 1.0", "comment castor: one frame",
        f"element vertex {len(mesh.vertices)}",
        "property double x", "property double y", "property double z",
        f"element face {len(tris)}",
        "property list uchar int vertex_indices",
        "property uchar red", "property uchar green", "property uchar blue",
        "end_header"]) + "\n"
    record = np.dtype([("count", "u1"), ("indices", "<i4", 3), ("colour", "u1", 3)])
    faces = np.zeros(len(tris), dtype=record)
    faces["count"] = 3
    faces["indices"] = tris
    faces["colour"] = byte_colours(mesh.colours)[polygon] if len(tris) else np.zeros((0, 3))
    stream.write(header.encode("ascii"))
    stream.write(np.ascontiguousarray(mesh.vertices, dtype="<f8").tobytes())
    stream.write(faces.tobytes())

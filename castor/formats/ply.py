"""Binary PLY: triangles, with colours on the vertices and on the faces.

Blender reads only vertex colours and MeshLab shows either, so each vertex
carries the colour of its faces: a vertex where faces of two colours meet is
written once per colour. Faces keep their own colour too. Every face is a
triangle, the form every PLY reader takes (trimesh's binary reader refuses
faces of mixed lengths).
"""

from __future__ import annotations

import numpy as np

from castor.mesh.frame import Frame
from castor.formats._mesh import byte_colours, combine, triangles


def export(frame: Frame, path: str | None = None) -> bytes:
    mesh = combine(frame)
    tris, polygon = triangles(mesh.vertices, mesh.offsets, mesh.indices)
    face_colour = byte_colours(mesh.colours)[polygon] if len(tris) else np.zeros((0, 3), np.uint8)
    # one vertex per (vertex, colour) pair
    palette, colour_id = np.unique(face_colour, axis=0, return_inverse=True)
    colour_id = colour_id.ravel()
    keys = tris * max(len(palette), 1) + colour_id[:, None]
    unique, corner = np.unique(keys.ravel(), return_inverse=True)
    vertex_of, colour_of = np.divmod(unique, max(len(palette), 1))
    header = "\n".join([
        "ply", "format binary_little_endian 1.0", "comment castor: one frame",
        f"element vertex {len(unique)}",
        "property double x", "property double y", "property double z",
        "property uchar red", "property uchar green", "property uchar blue",
        f"element face {len(tris)}",
        "property list uchar int vertex_indices",
        "property uchar red", "property uchar green", "property uchar blue",
        "end_header"]) + "\n"
    vertex = np.zeros(len(unique), dtype=np.dtype([("xyz", "<f8", 3), ("rgb", "u1", 3)]))
    vertex["xyz"] = mesh.vertices[vertex_of] if len(unique) else np.zeros((0, 3))
    vertex["rgb"] = palette[colour_of] if len(unique) else np.zeros((0, 3))
    faces = np.zeros(len(tris), dtype=np.dtype([("count", "u1"), ("indices", "<i4", 3),
                                                ("rgb", "u1", 3)]))
    faces["count"] = 3
    faces["indices"] = corner.reshape(-1, 3)
    faces["rgb"] = face_colour
    return header.encode("ascii") + vertex.tobytes() + faces.tobytes()

"""Binary glTF 2.0: one mesh per object, one primitive (and material) per colour.

Positions are single precision, as glTF requires; the primitives of an object
share its vertex list, so the surface stays closed. Normals are left out:
viewers then shade flat, which is right for polygons.
"""

from __future__ import annotations

import json
import struct

import numpy as np

from castor.mesh.frame import Frame
from castor.mesh.polygons import fan_triangles


def _linear(c: float) -> float:
    # glTF colours are linear; castor's are as displayed (sRGB)
    return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4


def write(frame: Frame, stream) -> None:
    blobs: list[bytes] = []
    offset = 0
    buffer_views, accessors, meshes, nodes, materials = [], [], [], [], []
    material_of: dict[tuple, int] = {}

    def add_view(data: bytes, target: int) -> int:
        nonlocal offset
        buffer_views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(data),
                             "target": target})
        padded = data + b"\0" * (-len(data) % 4)
        blobs.append(padded)
        offset += len(padded)
        return len(buffer_views) - 1

    for number, obj in enumerate(frame.objects):
        if obj.polygon_count == 0:
            continue
        positions = np.ascontiguousarray(obj.vertices, dtype="<f4")
        view = add_view(positions.tobytes(), 34962)
        accessors.append({"bufferView": view, "componentType": 5126, "count": len(positions),
                          "type": "VEC3", "min": positions.min(axis=0).tolist(),
                          "max": positions.max(axis=0).tolist()})
        position_accessor = len(accessors) - 1
        tris, polygon = fan_triangles(obj.offsets, obj.indices)
        origin = obj.origin_of[polygon]
        colours = np.array([o.colour for o in obj.origins], dtype=np.float64)
        unique, colour_of_origin = np.unique(colours, axis=0, return_inverse=True)
        colour_of_tri = colour_of_origin.ravel()[origin]
        primitives = []
        for c, colour in enumerate(unique):
            key = tuple(colour.tolist())
            if key not in material_of:
                materials.append({"name": "c_" + "_".join(f"{x:g}" for x in key),
                                  "pbrMetallicRoughness": {
                                      "baseColorFactor": [_linear(x) for x in key] + [1.0],
                                      "metallicFactor": 0.0, "roughnessFactor": 0.9},
                                  "doubleSided": False})
                material_of[key] = len(materials) - 1
            indices = np.ascontiguousarray(tris[colour_of_tri == c].ravel(), dtype="<u4")
            view = add_view(indices.tobytes(), 34963)
            accessors.append({"bufferView": view, "componentType": 5125, "count": len(indices),
                              "type": "SCALAR"})
            primitives.append({"attributes": {"POSITION": position_accessor},
                               "indices": len(accessors) - 1, "material": material_of[key],
                               "mode": 4})
        meshes.append({"name": f"object{number + 1}", "primitives": primitives})
        nodes.append({"mesh": len(meshes) - 1, "name": f"object{number + 1}"})

    document = {
        "asset": {"version": "2.0", "generator": "castor"},
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes)))}],
        "nodes": nodes, "meshes": meshes, "materials": materials,
        "accessors": accessors, "bufferViews": buffer_views,
        "buffers": [{"byteLength": offset}],
    }
    if not nodes:
        for key in ("nodes", "meshes", "materials", "accessors", "bufferViews", "buffers"):
            document.pop(key)
        document["scenes"] = [{"nodes": []}]
    text = json.dumps(document, separators=(",", ":")).encode("utf-8")
    text += b" " * (-len(text) % 4)
    binary = b"".join(blobs)
    chunks = struct.pack("<II", len(text), 0x4E4F534A) + text
    if binary:
        chunks += struct.pack("<II", len(binary), 0x004E4942) + binary
    stream.write(struct.pack("<III", 0x46546C67, 2, 12 + len(chunks)) + chunks)

"""Binary glTF 2.0: one named node and mesh per object, one primitive (and
material) per colour.

+Y up, as the glTF standard says: scene z becomes glTF y (and scene y becomes
-z), so that Blender and every viewer show a house standing. Positions are
single precision, as glTF requires; the primitives of an object share its
vertex list, so the surface stays closed. Normals are left out: viewers then
shade flat, which is right for polygons.
"""

from __future__ import annotations

import json
import struct

import numpy as np

from castor.mesh.frame import Frame
from castor.formats._mesh import materials as frame_materials, object_names, triangles, y_up


def _linear(c: float) -> float:
    # glTF colours are linear; castor's are as displayed (sRGB)
    return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4


def export(frame: Frame, path: str | None = None) -> bytes:
    blobs: list[bytes] = []
    offset = 0
    buffer_views, accessors, meshes, nodes, materials = [], [], [], [], []
    material_index: dict[int, int] = {}  # frame material -> glTF material

    def add_view(data: bytes, target: int) -> int:
        nonlocal offset
        buffer_views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(data),
                             "target": target})
        padded = data + b"\0" * (-len(data) % 4)
        blobs.append(padded)
        offset += len(padded)
        return len(buffer_views) - 1

    table, material_of = frame_materials(frame)
    for obj, name, material in zip(frame.objects, object_names(frame), material_of):
        if obj.polygon_count == 0:
            continue
        positions = np.ascontiguousarray(y_up(obj.vertices), dtype="<f4")
        view = add_view(positions.tobytes(), 34962)
        accessors.append({"bufferView": view, "componentType": 5126, "count": len(positions),
                          "type": "VEC3", "min": positions.min(axis=0).tolist(),
                          "max": positions.max(axis=0).tolist()})
        position_accessor = len(accessors) - 1
        tris, polygon = triangles(obj.vertices, obj.offsets, obj.indices)
        material_of_tri = material[polygon]
        primitives = []
        for m in np.unique(material_of_tri).tolist():
            if m not in material_index:
                colour = table[m].colour
                materials.append({"name": table[m].name,
                                  "pbrMetallicRoughness": {
                                      "baseColorFactor": [_linear(x) for x in colour] + [1.0],
                                      "metallicFactor": 0.0, "roughnessFactor": 0.9},
                                  "doubleSided": False})
                material_index[m] = len(materials) - 1
            indices = np.ascontiguousarray(tris[material_of_tri == m].ravel(), dtype="<u4")
            view = add_view(indices.tobytes(), 34963)
            accessors.append({"bufferView": view, "componentType": 5125, "count": len(indices),
                              "type": "SCALAR"})
            primitives.append({"attributes": {"POSITION": position_accessor},
                               "indices": len(accessors) - 1, "material": material_index[m],
                               "mode": 4})
        meshes.append({"name": name, "primitives": primitives})
        nodes.append({"mesh": len(meshes) - 1, "name": name})

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
        document["scenes"] = [{}]  # an empty list of nodes is not valid glTF
    text = json.dumps(document, separators=(",", ":")).encode("utf-8")
    text += b" " * (-len(text) % 4)
    binary = b"".join(blobs)
    chunks = struct.pack("<II", len(text), 0x4E4F534A) + text
    if binary:
        chunks += struct.pack("<II", len(binary), 0x004E4942) + binary
    return struct.pack("<III", 0x46546C67, 2, 12 + len(chunks)) + chunks

"""Binary glTF 2.0: one named node and mesh per object, one primitive (and
material) per colour.

+Y up, as the glTF standard says: scene z becomes glTF y (and scene y becomes
-z), so that Blender and every viewer show a house standing. Positions are
single precision, as glTF requires; the primitives of an object share its
vertex list, so the surface stays closed. Normals are left out: viewers then
shade flat, which is right for polygons.
"""

from __future__ import annotations

import struct
from typing import Iterator

import numpy as np

from castor.formats import WriteInfo
from castor.mesh.frame import Frame, FrameObject
from castor.formats._mesh import object_names, object_pieces, triangle_counts, triangles, y_up
from castor.formats._mesh import materials as frame_materials
from castor.formats._trimesh import read_with_trimesh


def _linear(c: float) -> float:
    # glTF colours are linear; castor's are as displayed (sRGB)
    return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4


def _indices_by_material(obj: FrameObject, material: np.ndarray,
                         size: int | None) -> dict[int, np.ndarray]:
    """For each material of the object's triangles (in order), the vertex numbers
    of its triangles, in triangle order: counted first, then filled a piece of
    polygons at a time, so that no array of every triangle is held beside them."""
    parts = list(object_pieces(obj, size))
    counts = np.concatenate([triangle_counts(obj.vertices, offsets, indices)
                             for _, offsets, indices in parts])
    per_material = np.bincount(material, weights=counts, minlength=1).astype(np.int64)
    by_material = {m: np.empty(3 * int(n), "<u4") for m, n in enumerate(per_material.tolist()) if n}
    filled = dict.fromkeys(by_material, 0)
    for first, offsets, indices in parts:
        tris, polygon = triangles(obj.vertices, offsets, indices)
        material_of_tri = material[first + polygon]
        for m in np.unique(material_of_tri).tolist():
            chosen = tris[material_of_tri == m].ravel()
            by_material[m][filled[m]:filled[m] + len(chosen)] = chosen
            filled[m] += len(chosen)
    return by_material


def export(frame: Frame, path: str | None = None) -> bytes:
    return b"".join(export_chunks(frame, path))


def export_chunks(frame: Frame, path: str | None = None, size: int | None = None) -> Iterator[bytes]:
    """The file in pieces: its header and JSON chunk, then each buffer view.
    Every buffer view is made (the JSON gives their lengths and bounds first),
    but the file is never joined into one ``bytes``."""
    blobs: list[np.ndarray] = []  # each view's numbers, written as bytes one at a time
    offset = 0
    buffer_views, accessors, meshes, nodes, materials = [], [], [], [], []
    material_index: dict[int, int] = {}  # frame material -> glTF material

    def add_view(data: np.ndarray, target: int) -> int:
        nonlocal offset
        buffer_views.append({"buffer": 0, "byteOffset": offset, "byteLength": data.nbytes,
                             "target": target})
        blobs.append(data)
        offset += data.nbytes + (-data.nbytes % 4)
        return len(buffer_views) - 1

    table, material_of = frame_materials(frame)
    for obj, name, material in zip(frame.objects, object_names(frame), material_of):
        if obj.polygon_count == 0:
            continue
        positions = np.ascontiguousarray(y_up(obj.vertices), dtype="<f4")
        view = add_view(positions, 34962)
        accessors.append({"bufferView": view, "componentType": 5126, "count": len(positions),
                          "type": "VEC3", "min": positions.min(axis=0).tolist(),
                          "max": positions.max(axis=0).tolist()})
        position_accessor = len(accessors) - 1
        by_material = _indices_by_material(obj, material, size)
        primitives = []
        for m, indices in by_material.items():
            if m not in material_index:
                colour = table[m].colour
                materials.append({"name": table[m].name,
                                  "pbrMetallicRoughness": {
                                      "baseColorFactor": [_linear(x) for x in colour] + [1.0],
                                      "metallicFactor": 0.0, "roughnessFactor": 0.9},
                                  "doubleSided": False})
                material_index[m] = len(materials) - 1
            view = add_view(indices, 34963)
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
    import json  # here: the registry imports this module at every start-up

    text = json.dumps(document, separators=(",", ":")).encode("utf-8")
    text += b" " * (-len(text) % 4)
    length = 12 + 8 + len(text) + (8 + offset if offset else 0)
    yield struct.pack("<III", 0x46546C67, 2, length) + struct.pack("<II", len(text), 0x4E4F534A) + text
    if offset:
        yield struct.pack("<II", offset, 0x004E4942)
        for data in blobs:
            yield data.tobytes() + b"\0" * (-data.nbytes % 4)


def read(path: str):
    """A glTF file (.glb, or .gltf with its buffers) as one frame, z up again."""
    return read_with_trimesh(path, up="y")


def write(frame: Frame, info: WriteInfo) -> Iterator[bytes]:
    """The registry's writer (castor.formats): the frame a piece at a time."""
    return export_chunks(frame, info.path)

"""Wavefront OBJ: one object per '>' object, named after it, a material per colour.

+Y up, as Blender and most OBJ readers assume: scene z becomes OBJ y (and
scene y becomes -z), so a house imports standing. The materials go to a
companion .mtl file beside the .obj (``companions``), named after what they
colour (``toit``, ``fenetre``).
"""

from __future__ import annotations

import os
from typing import Iterator

import numpy as np

from castor.formats import WriteInfo
from castor.mesh.frame import Frame
from castor.formats._mesh import CHUNK, materials, object_names, y_up
from castor.formats.cps import number_strings
from castor.formats._trimesh import read_with_trimesh


def export_chunks(frame: Frame, path: str | None = None, size: int | None = None) -> Iterator[bytes]:
    """The file a piece at a time: each object's vertices, then its faces by material."""
    step = size or CHUNK
    table, material_of = materials(frame)
    head = ["# castor: one frame, +Y up, polygons counter-clockwise seen from outside"]
    if path is not None:
        head.append(f"mtllib {_mtl_name(path)}")
    yield ("\n".join(head) + "\n").encode("utf-8")
    base = 1
    for obj, name, material in zip(frame.objects, object_names(frame), material_of):
        yield f"o {name}\n".encode("utf-8")
        for first in range(0, len(obj.vertices), step):
            numbers = number_strings(y_up(obj.vertices[first:first + step]))
            yield ("\n".join("v " + " ".join(numbers[i:i + 3]) for i in range(0, len(numbers), 3))
                   + "\n").encode("utf-8")
        order = np.argsort(material, kind="stable")
        sizes = np.diff(obj.offsets)
        current = None
        for first in range(0, len(order), step):
            chosen = order[first:first + step]
            # the chosen polygons' vertex numbers, polygon after polygon
            counts = sizes[chosen]
            starts = np.repeat(obj.offsets[:-1][chosen] - np.cumsum(counts) + counts, counts)
            words = (obj.indices[starts + np.arange(len(starts))] + base).astype(str).tolist()
            bounds = np.concatenate([[0], np.cumsum(counts)]).tolist()
            lines = []
            for k, m in enumerate(material[chosen].tolist()):
                if m != current:
                    current = m
                    lines.append(f"usemtl {table[current].name}")
                lines.append("f " + " ".join(words[bounds[k]:bounds[k + 1]]))
            yield ("\n".join(lines) + "\n").encode("utf-8")
        base += len(obj.vertices)


def export(frame: Frame, path: str | None = None) -> bytes:
    return b"".join(export_chunks(frame, path))


def _mtl_name(path: str) -> str:
    return os.path.splitext(os.path.basename(path))[0] + ".mtl"


def companions(frame: Frame, info: WriteInfo) -> dict[str, bytes]:
    """The .mtl file that goes beside the file (``info.path``)."""
    path = info.path
    table, _ = materials(frame)
    lines = []
    for material in table:
        rgb = " ".join(number_strings(np.array(material.colour)))
        lines += [f"newmtl {material.name}", f"Ka {rgb}", f"Kd {rgb}", "Ks 0 0 0", "d 1",
                  "illum 1", ""]
    return {os.path.join(os.path.dirname(path), _mtl_name(path)): "\n".join(lines).encode("utf-8")}


def read(path: str):
    """An OBJ file (its .mtl beside it) as one frame, z up again."""
    return read_with_trimesh(path, up="y")


def write(frame: Frame, info: WriteInfo) -> Iterator[bytes]:
    """The registry's writer (castor.formats): the frame a piece at a time."""
    return export_chunks(frame, info.path)

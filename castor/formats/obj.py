"""Wavefront OBJ: one object per '>' object, named after it, a material per colour.

+Y up, as Blender and most OBJ readers assume: scene z becomes OBJ y (and
scene y becomes -z), so a house imports standing. The materials go to a
companion .mtl file beside the .obj (``companions``), named after what they
colour (``toit``, ``fenetre``).
"""

from __future__ import annotations

import os

import numpy as np

from castor.mesh.frame import Frame
from castor.formats._mesh import materials, object_names, y_up
from castor.formats.cps import number_strings


def export(frame: Frame, path: str | None = None) -> bytes:
    table, material_of = materials(frame)
    lines = ["# castor: one frame, +Y up, polygons counter-clockwise seen from outside"]
    if path is not None:
        lines.append(f"mtllib {_mtl_name(path)}")
    base = 1
    for obj, name, material in zip(frame.objects, object_names(frame), material_of):
        lines.append(f"o {name}")
        numbers = number_strings(y_up(obj.vertices))
        lines.extend("v " + " ".join(numbers[i:i + 3]) for i in range(0, len(numbers), 3))
        words = (obj.indices + base).astype(str).tolist()
        bounds = obj.offsets.tolist()
        order = np.argsort(material, kind="stable").tolist()
        current = None
        for p in order:
            if material[p] != current:
                current = material[p]
                lines.append(f"usemtl {table[current].name}")
            lines.append("f " + " ".join(words[bounds[p]:bounds[p + 1]]))
        base += len(obj.vertices)
    return ("\n".join(lines) + "\n").encode("utf-8")


def _mtl_name(path: str) -> str:
    return os.path.splitext(os.path.basename(path))[0] + ".mtl"


def companions(frame: Frame, path: str) -> dict[str, bytes]:
    """The .mtl file that goes beside ``path``."""
    table, _ = materials(frame)
    lines = []
    for material in table:
        rgb = " ".join(number_strings(np.array(material.colour)))
        lines += [f"newmtl {material.name}", f"Ka {rgb}", f"Kd {rgb}", "Ks 0 0 0", "d 1",
                  "illum 1", ""]
    return {os.path.join(os.path.dirname(path), _mtl_name(path)): "\n".join(lines).encode("utf-8")}

"""Wavefront OBJ: one group per object, one material per colour.

The materials go to a companion .mtl file beside the .obj (``companions``);
written to standard output, the OBJ names its materials by colour
(``c_0.9_0.9_0.85``) so that a reader without the .mtl still sees the colours.
"""

from __future__ import annotations

import os

import numpy as np

from castor.mesh.frame import Frame
from castor.formats._mesh import combine
from castor.formats.cps import number_strings


def _material_names(colours: np.ndarray) -> tuple[list[str], np.ndarray, np.ndarray]:
    unique, inverse = np.unique(colours, axis=0, return_inverse=True)
    names = ["c_" + "_".join(number_strings(c)) for c in unique]
    return names, unique, inverse.ravel()


def write(frame: Frame, stream, path: str | None = None) -> None:
    mesh = combine(frame)
    names, unique, inverse = _material_names(mesh.colours)
    lines = ["# castor: one frame, polygons counter-clockwise seen from outside"]
    if path is not None:
        lines.append(f"mtllib {os.path.splitext(os.path.basename(path))[0]}.mtl")
    numbers = number_strings(mesh.vertices)
    lines.extend("v " + " ".join(numbers[i:i + 3]) for i in range(0, len(numbers), 3))
    offsets = mesh.offsets.tolist()
    indices = (mesh.indices + 1).tolist()
    objects = mesh.objects.tolist()
    current_object, current_material = None, None
    for p in range(len(offsets) - 1):
        if objects[p] != current_object:
            current_object = objects[p]
            lines.append(f"o object{current_object + 1}")
            current_material = None
        if inverse[p] != current_material:
            current_material = inverse[p]
            lines.append(f"usemtl {names[current_material]}")
        lines.append("f " + " ".join(map(str, indices[offsets[p]:offsets[p + 1]])))
    stream.write("\n".join(lines) + "\n")


def companions(frame: Frame, path: str) -> dict[str, bytes]:
    """The .mtl file that goes beside ``path``."""
    mesh = combine(frame)
    names, unique, _ = _material_names(mesh.colours)
    lines = []
    for name, colour in zip(names, unique):
        rgb = " ".join(number_strings(colour))
        lines += [f"newmtl {name}", f"Ka {rgb}", f"Kd {rgb}", "Ks 0 0 0", "d 1", "illum 1", ""]
    return {os.path.splitext(path)[0] + ".mtl": "\n".join(lines).encode("utf-8")}

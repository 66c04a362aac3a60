"""Geomview OFF with a colour for each face (integers 0..255, as MeshLab writes them).

Polygons of more than four vertices are cut into convex quads, because some
readers (trimesh's OFF loader) take nothing larger.
"""

from __future__ import annotations

from castor.mesh.frame import Frame
from castor.formats._mesh import byte_colours, combine, split_large
from castor.formats.cps import number_strings


def write(frame: Frame, stream) -> None:
    mesh = combine(frame)
    offsets, indices, colours = split_large(mesh.offsets, mesh.indices, mesh.colours)
    numbers = number_strings(mesh.vertices)
    lines = ["OFF", f"{len(mesh.vertices)} {len(offsets) - 1} 0"]
    lines.extend(" ".join(numbers[i:i + 3]) for i in range(0, len(numbers), 3))
    offsets = offsets.tolist()
    indices = indices.tolist()
    colours = byte_colours(colours).tolist()
    for p in range(len(offsets) - 1):
        face = indices[offsets[p]:offsets[p + 1]]
        r, g, b = colours[p]
        lines.append(f"{len(face)} {' '.join(map(str, face))} {r} {g} {b}")
    stream.write("\n".join(lines) + "\n")

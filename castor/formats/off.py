"""Geomview OFF with a colour for each face (integers 0..255, as MeshLab writes them).

Polygons with a straight corner (a vertex in the middle of a straight edge,
where a neighbouring polygon ends) are written as triangles with true corners:
OpenSCAD reads an OFF file straight into CGAL's exact polyhedra, whose booleans
stop with an assertion at a face corner of 180 degrees. Polygons of more than
four vertices are cut into convex quads, because some readers (trimesh's OFF
loader) take nothing larger.
"""

from __future__ import annotations

import numpy as np

from castor.mesh.frame import Frame
from castor.formats._mesh import byte_colours, combine, split_large, straight_corners, triangles
from castor.formats.cps import number_strings


def faces(vertices: np.ndarray, offsets: np.ndarray, indices: np.ndarray,
          colours: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The faces OFF readers take: (offsets, indices, colours) of convex faces of at
    most four vertices and no straight corner."""
    straight = straight_corners(vertices, offsets, indices)
    if straight.any():
        tris, polygon = triangles(vertices, offsets, indices)
        # triangles of the straight-cornered polygons, every other polygon whole
        cut = straight[polygon]
        parts = [(p, indices[offsets[p]:offsets[p + 1]]) for p in np.flatnonzero(~straight)]
        parts += list(zip(polygon[cut].tolist(), tris[cut]))
        parts.sort(key=lambda part: part[0])
        owner = np.array([p for p, _ in parts], np.int64)
        new_sizes = np.array([len(f) for _, f in parts], np.int64)
        offsets = np.zeros(len(parts) + 1, np.int64)
        np.cumsum(new_sizes, out=offsets[1:])
        indices = np.concatenate([f for _, f in parts]) if parts else np.zeros(0, np.int64)
        colours = colours[owner]
    return split_large(offsets, indices, colours)


def export(frame: Frame, path: str | None = None) -> bytes:
    mesh = combine(frame)
    offsets, indices, colours = faces(mesh.vertices, mesh.offsets, mesh.indices, mesh.colours)
    numbers = number_strings(mesh.vertices)
    lines = ["OFF", f"{len(mesh.vertices)} {len(offsets) - 1} 0"]
    lines.extend(" ".join(numbers[i:i + 3]) for i in range(0, len(numbers), 3))
    sizes = np.diff(offsets).tolist()
    bounds = offsets.tolist()
    words = indices.astype(str).tolist()
    rgb = [f"{r} {g} {b}" for r, g, b in byte_colours(colours).tolist()]
    lines.extend(f"{sizes[p]} {' '.join(words[bounds[p]:bounds[p + 1]])} {rgb[p]}"
                 for p in range(len(sizes)))
    return ("\n".join(lines) + "\n").encode("ascii")

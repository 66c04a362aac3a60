"""``!we``: the wedge, the right triangle (0, 0), (1, 0), (0, 1) of the xz plane
swept along y from 0 to 1: half the unit cube below the plane x + z = 1 (a
ramp, a lean-to roof, a step's nosing). Five flat faces; a ray meets it as
five half-spaces."""

from __future__ import annotations

from castor.primitives import rays
from castor.primitives.base import FLAT, Mesh, PrimitiveKind

# outward normals and offsets: z >= 0, x >= 0, y >= 0, y <= 1, x + z <= 1
_PLANES = (((0, 0, -1), (-1, 0, 0), (0, -1, 0), (0, 1, 0), (1, 0, 1)), (0, 0, 0, 1, 1))
_UNIT = ((0.0, 0.0, 0.0), (1.0, 1.0, 1.0))


def mesh(shape: tuple, facets: tuple) -> Mesh:
    import numpy as np

    vertices = np.array([[0, 0, 0], [1, 0, 0], [0, 0, 1],  # the triangle at y = 0
                         [0, 1, 0], [1, 1, 0], [0, 1, 1]], dtype=np.float64)  # at y = 1
    # faces, counter-clockwise from outside, numbered as the planes above
    triangles = np.array([[0, 3, 4], [0, 4, 1],  # the floor, z = 0
                          [0, 2, 5], [0, 5, 3],  # the back, x = 0
                          [0, 1, 2],  # the end y = 0
                          [3, 5, 4],  # the end y = 1
                          [1, 4, 5], [1, 5, 2]], dtype=np.int64)  # the slope
    faces = np.array([0, 0, 1, 1, 2, 3, 4, 4], dtype=np.int64)
    return Mesh(vertices, triangles, faces, np.full(5, FLAT, np.int64))


def spans(shape, o, d):
    return rays.halfspaces(*_PLANES, o, d)


PRIMITIVE = PrimitiveKind(
    place=75, name="we", title="wedge",
    solid="the triangle (0, 0), (1, 0), (0, 1) of the xz plane swept along y from 0 to 1",
    arguments=(), pair_names=None, curved=False, check=None, box=lambda shape: _UNIT,
    mesh=mesh, triangles=lambda shape, facets: 8, spans=spans,
    normal=rays.halfspace_normal(_PLANES[0]))

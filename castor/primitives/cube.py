"""``!cu``: the unit cube [0,1]^3, six flat faces; a ray meets it as six half-spaces."""

from __future__ import annotations

from castor.primitives import rays
from castor.primitives.base import Mesh, PrimitiveKind
from castor.primitives.facets import quads

# outward normals and offsets (numbers, not arrays: reading a scene imports no numpy)
_PLANES = (((-1, 0, 0), (1, 0, 0), (0, -1, 0), (0, 1, 0), (0, 0, -1), (0, 0, 1)),
           (0, 1, 0, 1, 0, 1))
_UNIT = ((0.0, 0.0, 0.0), (1.0, 1.0, 1.0))


def mesh(shape: tuple, facets: tuple) -> Mesh:
    import numpy as np

    vertices = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0],
                         [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], dtype=np.float64)
    corners = np.array([[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4],
                        [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]])
    return quads(vertices, corners, 0)


def spans(shape, o, d):
    return rays.halfspaces(*_PLANES, o, d)


PRIMITIVE = PrimitiveKind(
    place=10, name="cu", title="cube", solid="the unit cube [0,1]^3", arguments=(), pair_names=None,
    curved=False, check=None, box=lambda shape: _UNIT, mesh=mesh,
    triangles=lambda shape, facets: 12, spans=spans,
    normal=rays.halfspace_normal(_PLANES[0]))

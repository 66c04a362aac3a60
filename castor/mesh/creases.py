"""Is the edge between two faces a crease? One answer for every output.

An edge is a crease unless the faces on its two sides lie in one plane, or
are facets of one curved surface of one primitive instance (the side of a
cylinder, a band of ``!rv``: ``castor.primitives`` says which faces of a
primitive's mesh those are, and the polygons of a frame carry it,
``castor.mesh.frame``). Drawings (hidden lines), pictures (``--edges``, where
a pixel's surface is the exact face the ray met) and castor-view decide with
``creases`` alike; a 16-sided prism shows its 16 edges, a cylinder of 16
facets only its outline, whatever the angle between them.

castor-view reads files that carry each polygon's path (ending in ``!kind``)
but not its surface: ``guessed_same_surface`` takes two neighbouring polygons
of one path of a kind whose faces are all flat (cube, wedge, prism, pyramid,
extrusion) as different faces, and two of one path of a curved kind as
facets of one surface when they turn by at most ``SMOOTH_TURN`` (a circle
has at least 8 segments, so neighbouring facets of one surface never turn by
more than 45°). Polygons without a path (a mesh file) are taken as one
curved primitive.
"""

from __future__ import annotations

import math

import numpy as np

# 1 - cos of the largest turn between two faces counted as one plane (about 0.08°):
# above single-precision rounding of unit normals (pictures), below any real crease
COPLANAR = 1e-6

SMOOTH_TURN = math.radians(45.5)


def creases(cosine: np.ndarray, same_surface: np.ndarray) -> np.ndarray:
    """For edges whose two faces' unit normals have ``cosine``, and which lie
    (or not) between facets of one curved surface, whether each is a crease."""
    return (cosine < 1 - COPLANAR) & ~same_surface


def same_surface(origin_a, origin_b, surface_a, surface_b) -> np.ndarray:
    """Whether two polygons are facets of one curved surface of one primitive
    use: the same origin, the same surface number, not FLAT (-1)."""
    return (origin_a == origin_b) & (surface_a == surface_b) & (surface_a >= 0)


def guessed_same_surface(same_origin, curved, cosine) -> np.ndarray:
    """For polygons whose surfaces are not known (only their path's kind,
    ``curved``: a kind with curved faces, or no kind known): whether two
    neighbours are facets of one curved surface."""
    return same_origin & curved & (cosine >= math.cos(SMOOTH_TURN))


def curved_kinds(kinds) -> np.ndarray:
    """For each kind (a primitive's name, or "" when none is known), whether
    its primitive may have curved faces."""
    from castor.primitives import PRIMITIVES

    return np.array([PRIMITIVES[k].curved if k in PRIMITIVES else True for k in kinds], bool)

"""``!sp``: the sphere of radius 1 centred at the origin, one curved surface:
quads between rings of latitude, fans at the poles; a ray meets it as a quadric."""

from __future__ import annotations

import math

from castor.primitives import rays
from castor.primitives.base import Mesh, PrimitiveKind
from castor.primitives.facets import (joined, largest_stretch, plane_stretch, quads, quantize,
                                     ring, sphere_segments)

INF = math.inf


def sphere(around: int, rings: int) -> Mesh:
    import numpy as np

    polar = np.pi * np.arange(1, rings) / rings
    blocks = [np.array([[0.0, 0.0, 1.0]])]
    for angle in polar:
        z = math.cos(angle)
        blocks.append(ring(around, math.sin(angle), z))
    blocks.append(np.array([[0.0, 0.0, -1.0]]))
    vertices = np.concatenate(blocks)
    if rings % 2 == 0:  # the equator lies exactly in z = 0
        vertices[1 + (rings // 2 - 1) * around: 1 + (rings // 2) * around, 2] = 0.0
    south = len(vertices) - 1
    j = np.arange(around)
    k = (j + 1) % around
    top = np.column_stack([np.zeros(around, np.int64), 1 + j, 1 + k])
    bottom_ring = 1 + (rings - 2) * around
    bottom = np.column_stack([np.full(around, south), bottom_ring + k, bottom_ring + j])
    upper = 1 + np.arange(rings - 2)[:, None] * around  # first index of each upper ring
    corners = np.stack([upper + j, upper + around + j, upper + around + k, upper + k], axis=-1)
    corners = corners.reshape(-1, 4)
    side = quads(vertices, corners, 2 * around)
    return joined(vertices, [top, bottom, side.triangles],
                  [np.arange(around), around + np.arange(around), side.faces],
                  np.zeros(len(side.surfaces), np.int64))


def facets(shape, linear, tolerance) -> tuple[int, int]:
    """(around, rings): the rings of latitude as many as the largest stretch
    needs (a meridian of an ellipsoid is stretched by up to that), the
    segments around as many as the largest circle of latitude, the equator
    stretched in its xy plane, needs (facets.sphere_segments: the bound)."""
    largest = largest_stretch(linear)
    flat = plane_stretch(linear)
    return sphere_segments(quantize(tolerance / largest), quantize(tolerance / flat),
                           flat / largest)


def spans(shape, o, d):
    import numpy as np

    a = np.einsum("ij,ij->i", d, d)
    b = 2 * np.einsum("ij,ij->i", o, d)
    c = np.einsum("ij,ij->i", o, o) - 1
    t1, t2 = rays.roots(a, b, c)
    ok = np.isfinite(t1) & np.isfinite(t2)
    return rays.single(np.where(ok, t1, INF), np.where(ok, t2, -INF), 0, 0)


def normal(shape, p, face):
    return p


PRIMITIVE = PrimitiveKind(
    place=20, name="sp", title="sphere", solid="the sphere of radius 1 centred at the origin",
    arguments=(), pair_names=None, curved=True, check=None,
    box=lambda shape: ((-1.0,) * 3, (1.0,) * 3),
    mesh=lambda shape, facets: sphere(*facets),
    triangles=lambda shape, facets: 2 * math.prod(facets),
    spans=spans, normal=normal, facets=facets)

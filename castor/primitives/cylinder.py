"""``!cy``: the cylinder of radius 1 about the z axis from z = 0 to z = 1: two
flat caps and one curved side; a ray meets it as a quadric in a slab."""

from __future__ import annotations

import math

from castor.primitives import rays
from castor.primitives.base import PrimitiveKind
from castor.primitives.facets import circle_segments, column, plane_stretch, quantize

INF = math.inf
ROUND = ((-1.0, -1.0, 0.0), (1.0, 1.0, 1.0))  # the box of a unit disc swept or coned up


def spans(shape, o, d):
    import numpy as np

    a = d[:, 0] ** 2 + d[:, 1] ** 2
    b = 2 * (o[:, 0] * d[:, 0] + o[:, 1] * d[:, 1])
    c = o[:, 0] ** 2 + o[:, 1] ** 2 - 1
    t1, t2 = rays.roots(a, b, c)
    vertical = a == 0
    t1 = np.where(vertical, np.where(c <= 0, -INF, INF), t1)
    t2 = np.where(vertical, np.where(c <= 0, INF, -INF), t2)
    ok = ~(np.isnan(t1) | np.isnan(t2))
    t1, t2 = np.where(ok, t1, INF), np.where(ok, t2, -INF)
    s0, s1, f0, f1 = rays.slab(o, d)
    enter = np.maximum(t1, s0)
    leave = np.minimum(t2, s1)
    return rays.single(enter, leave, np.where(s0 > t1, f0 + 1, 0),
                       np.where(s1 < t2, f1 + 1, 0))


def facets(shape, linear, tolerance) -> tuple[int]:
    """(segments,): those of its circles, as stretched in their xy plane. A
    point of the side and the facet beside it differ across, in the plane of
    the circle through the point, so a stretch along the axis changes no gap."""
    return (circle_segments(1.0, quantize(tolerance / plane_stretch(linear))),)


PRIMITIVE = PrimitiveKind(
    place=30, name="cy", title="cylinder", solid="radius 1 about the z axis, from z = 0 to z = 1",
    arguments=(), pair_names=None, curved=True, check=None, box=lambda shape: ROUND,
    mesh=lambda shape, facets: column(facets[0], surface=0),
    triangles=lambda shape, facets: 4 * facets[0],
    spans=spans, normal=rays.round_normal(False), facets=facets)

"""``!co``: the cone with a base of radius 1 in z = 0 and its apex at (0, 0, 1):
a flat base and one curved side; a ray meets it as a quadric in a slab."""

from __future__ import annotations

import math

from castor.primitives import rays
from castor.primitives.base import PrimitiveKind
from castor.primitives.cylinder import ROUND, facets
from castor.primitives.facets import spire

INF = math.inf


def spans(shape, o, d):
    import numpy as np

    w0, dw = 1 - o[:, 2], -d[:, 2]
    a = d[:, 0] ** 2 + d[:, 1] ** 2 - dw ** 2
    b = 2 * (o[:, 0] * d[:, 0] + o[:, 1] * d[:, 1] - w0 * dw)
    c = o[:, 0] ** 2 + o[:, 1] ** 2 - w0 ** 2
    a = np.where(np.abs(a) < 1e-14, 1e-14, a)
    t1, t2 = rays.roots(a, b, c)
    real = np.isfinite(t1) & np.isfinite(t2)
    s0, s1, f0, f1 = rays.slab(o, d)
    # inside the double cone: [t1, t2] (a > 0) or outside it (a < 0); the slab
    # keeps one nappe, so at most one piece survives
    pieces = []
    positive = a > 0
    pieces.append((np.where(positive, t1, -INF), np.where(positive, t2, t1)))
    pieces.append((np.where(positive, INF, t2), np.where(positive, -INF, INF)))
    none = ~real
    best_in, best_out = np.full(len(o), INF), np.full(len(o), -INF)
    face_in, face_out = np.zeros(len(o), np.int64), np.zeros(len(o), np.int64)
    for lo, hi in pieces:
        lo = np.where(none, INF, lo)
        hi = np.where(none, -INF, hi)
        enter, leave = np.maximum(lo, s0), np.minimum(hi, s1)
        found = (enter <= leave) & (leave - enter >= best_out - best_in)
        best_in = np.where(found, enter, best_in)
        best_out = np.where(found, leave, best_out)
        face_in = np.where(found, np.where(s0 > lo, f0 + 1, 0), face_in)
        face_out = np.where(found, np.where(s1 < hi, f1 + 1, 0), face_out)
    # a ray with no real root along a > 0 misses; along a < 0 it lies inside the
    # double cone all along (within the slab only on the lower nappe)
    inside_all = none & (a < 0)
    best_in = np.where(inside_all, s0, best_in)
    best_out = np.where(inside_all, s1, best_out)
    face_in = np.where(inside_all, f0 + 1, face_in)
    face_out = np.where(inside_all, f1 + 1, face_out)
    return rays.single(best_in, best_out, face_in, face_out)


PRIMITIVE = PrimitiveKind(
    place=40, name="co", title="cone", solid="base of radius 1 in z = 0, apex (0, 0, 1)",
    arguments=(), pair_names=None, curved=True, check=None, box=lambda shape: ROUND,
    mesh=lambda shape, facets: spire(facets[0], surface=0),
    triangles=lambda shape, facets: 4 * facets[0],
    # as a cylinder's: each circle of the side shrinks towards the apex, in its xy plane
    spans=spans, normal=rays.round_normal(True), facets=facets)

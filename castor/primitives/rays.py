"""What the primitives' ray spans share (castor.pictures.trace).

For rays ``o + t d`` in a primitive's own space (``d`` need not be a unit
vector: the parameter ``t`` is the scene ray's own, so that the spans of all
primitives can be combined), a primitive's ``spans(shape, o, d)`` gives the
spans as two (n, 2K) arrays: ``t`` (entry, exit, entry, exit, ...; sorted;
``inf`` where a ray has fewer than K spans) and ``face`` (which face of the
primitive each crossing lies on); its ``normal(shape, p, face)`` the
(unnormalised) outward normal at points ``p`` on the given faces.

Here: one span from an entry and an exit; the intersection of half-spaces
(the cube, prisms, pyramids, convex extrusions); the roots of a quadratic;
the slab 0 <= z <= 1; spans from sorted crossings (even-odd).

numpy is imported in the functions that use it, here and in every primitive's
module: reading and checking a scene (the parser, the evaluator, ``--check``)
reads the primitives' declarations and needs none of it (issue 18).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

if TYPE_CHECKING:  # numpy is imported where it is used: see rays.py
    import numpy as np

INF = math.inf


def empty_like(n: int, k: int = 1):
    import numpy as np

    return np.full((n, 2 * k), INF), np.zeros((n, 2 * k), np.int64)


def single(enter, leave, face_in, face_out):
    """One span per ray (enter <= leave), or none."""
    import numpy as np

    ok = enter <= leave
    t = np.empty((len(enter), 2))
    t[:, 0] = np.where(ok, enter, INF)
    t[:, 1] = np.where(ok, leave, INF)
    face = np.empty((len(enter), 2), np.int64)
    face[:, 0] = face_in
    face[:, 1] = face_out
    return t, face


def halfspaces(normals: np.ndarray, offsets: np.ndarray, o: np.ndarray, d: np.ndarray):
    """The span of each ray inside the intersection of the half-spaces; the
    face of a crossing is the number of its plane."""
    import numpy as np

    normals, offsets = np.asarray(normals, np.float64), np.asarray(offsets, np.float64)
    nd = d @ normals.T  # (n, P)
    no = o @ normals.T
    with np.errstate(divide="ignore", invalid="ignore"):
        t = (offsets - no) / nd
    entering = nd < 0
    leaving = nd > 0
    parallel_out = (nd == 0) & (no > offsets)
    t_in = np.where(entering, t, -INF)
    t_out = np.where(leaving, t, INF)
    face_in = np.argmax(t_in, axis=1)
    face_out = np.argmin(t_out, axis=1)
    rows = np.arange(len(o))
    enter = t_in[rows, face_in]
    leave = t_out[rows, face_out]
    enter = np.where(np.any(parallel_out, axis=1), INF, enter)
    return single(enter, leave, face_in, face_out)


def halfspace_normal(normals):
    """The outward normal on each face of the intersection of half-spaces:
    ``normals`` (numbers or an array) by face number."""
    def normal(shape, p, face):
        import numpy as np

        return np.asarray(normals, np.float64)[face]
    return normal


_planes: dict[tuple, tuple] = {}


def prism_planes(n: int, pyramid: bool):
    import numpy as np

    key = (n, pyramid)
    if key not in _planes:
        angles = (2 * np.arange(n) + 1) * np.pi / n  # the middles of the sides
        apothem = math.cos(math.pi / n)
        if pyramid:  # (cos, sin) . (x, y) / apothem + z <= 1
            sides = np.column_stack([np.cos(angles) / apothem, np.sin(angles) / apothem,
                                     np.ones(n)])
            normals = np.concatenate([[[0.0, 0.0, -1.0]], sides])
            offsets = np.concatenate([[0.0], np.ones(n)])
        else:
            sides = np.column_stack([np.cos(angles), np.sin(angles), np.zeros(n)])
            normals = np.concatenate([[[0.0, 0.0, -1.0], [0.0, 0.0, 1.0]], sides])
            offsets = np.concatenate([[0.0, 1.0], np.full(n, apothem)])
        _planes[key] = (normals, offsets)
    return _planes[key]


def many_sides(n: int, pyramid: bool, o, d):
    """A polygon of very many sides: its half-spaces a block at a time."""
    import numpy as np

    normals, offsets = prism_planes(n, pyramid)
    best_in, best_out = np.full(len(o), -INF), np.full(len(o), INF)
    face_in, face_out = np.zeros(len(o), np.int64), np.zeros(len(o), np.int64)
    for start in range(0, len(normals), 512):
        t, face = halfspaces(normals[start:start + 512], offsets[start:start + 512], o, d)
        # a block's own span: its entry and exit (inf for none: the ray misses)
        missing = ~np.isfinite(t[:, 0]) & ~np.isfinite(t[:, 1])
        enter = np.where(missing, INF, t[:, 0])
        leave = np.where(missing, -INF, t[:, 1])
        better = enter > best_in
        best_in = np.where(better, enter, best_in)
        face_in = np.where(better, face[:, 0] + start, face_in)
        better = leave < best_out
        best_out = np.where(better, leave, best_out)
        face_out = np.where(better, face[:, 1] + start, face_out)
    return single(best_in, best_out, face_in, face_out)


def polygon_spans(pyramid: bool):
    """The spans of rays through the prism (or the pyramid) on the regular N-gon:
    N + 2 (N + 1) half-spaces, or past 512 sides the polygon found by angle."""
    def spans(shape, o, d):
        n = int(shape[0])
        if n > 512:
            return many_sides(n, pyramid, o, d)
        return halfspaces(*prism_planes(n, pyramid), o, d)
    return spans


def round_normal(cone: bool):
    """The outward normal of the cylinder (or the cone) at p on face 0 (the side),
    1 (the bottom) or 2 (the top): the side's normal points away from the axis and,
    on the cone, up as steeply as the side leans."""
    def normal(shape, p, face):
        import numpy as np

        n = np.zeros_like(p)
        side = face == 0
        n[side, 0], n[side, 1] = p[side, 0], p[side, 1]
        if cone:
            n[side, 2] = np.hypot(p[side, 0], p[side, 1])
        n[face == 1, 2] = -1
        n[face == 2, 2] = 1
        return n
    return normal


def polygon_normal(pyramid: bool):
    def normal(shape, p, face):
        return prism_planes(int(shape[0]), pyramid)[0][face]
    return normal


def roots(a, b, c):
    """The two roots of a t^2 + b t + c (t1 <= t2), NaN where there are none."""
    import numpy as np

    with np.errstate(divide="ignore", invalid="ignore"):
        disc = b * b - 4 * a * c
        root = np.sqrt(disc)
        q = -0.5 * (b + np.copysign(root, b))
        t1, t2 = q / a, c / q
    return np.minimum(t1, t2), np.maximum(t1, t2)


def slab(o, d, low=0.0, high=1.0):
    """The span of each ray in low <= z <= high, with its faces (0 the bottom, 1 the top)."""
    import numpy as np

    oz, dz = o[:, 2], d[:, 2]
    with np.errstate(divide="ignore", invalid="ignore"):
        t0, t1 = (low - oz) / dz, (high - oz) / dz
    flat = dz == 0
    inside = (oz >= low) & (oz <= high)
    enter = np.where(flat, np.where(inside, -INF, INF), np.minimum(t0, t1))
    leave = np.where(flat, np.where(inside, INF, -INF), np.maximum(t0, t1))
    face_in = np.where(dz > 0, 0, 1)
    return enter, leave, face_in, 1 - face_in


def outline(shape):
    import numpy as np

    points = np.asarray(shape, dtype=np.float64).reshape(-1, 2)
    return points, np.roll(points, -1, axis=0)


def pairs(crossings, faces, n):
    """Spans from the sorted crossings of closed surfaces along each ray (even-odd)."""
    import numpy as np

    order = np.argsort(crossings, axis=1, kind="stable")
    t = np.take_along_axis(crossings, order, axis=1)
    face = np.take_along_axis(faces, order, axis=1)
    count = np.sum(np.isfinite(t), axis=1)
    odd = count % 2 == 1  # grazing a vertex: drop the last crossing
    if np.any(odd):
        rows = np.flatnonzero(odd)
        t[rows, count[odd] - 1] = INF
    keep = int(np.max(count)) if len(count) else 0
    keep += keep % 2
    return t[:, :keep], face[:, :keep]

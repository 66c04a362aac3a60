"""``!ex``: a simple polygon (x1, y1, ..., either orientation) in z = 0 swept to
z = 1: every face flat (two caps, a wall per side). A ray meets a convex one
as half-spaces, any other as the even-odd crossings of its walls clipped by
its caps."""

from __future__ import annotations

import math

from castor.diagnostics import Location
from castor.primitives import rays
from castor.primitives.base import Mesh, PrimitiveKind
from castor.primitives.facets import joined, quads

INF = math.inf


def check(shape: tuple, location: Location, path: object) -> None:
    from castor.primitives.simple_polygon import polygon

    polygon(shape, "polygon", location, path)


def extrusion(values: tuple) -> Mesh:
    """The simple polygon (x1, y1, ...) in z = 0 swept to z = 1."""
    import numpy as np

    from castor.primitives.simple_polygon import polygon, signed_area
    from castor.mesh.adapter import triangulate

    points = polygon(values, "polygon", None, "")
    if signed_area(points) < 0:
        points = points[::-1].copy()
    n = len(points)
    cap = triangulate(points)
    vertices = np.concatenate([np.column_stack([points, np.zeros(n)]),
                               np.column_stack([points, np.ones(n)])])
    j = np.arange(n)
    k = (j + 1) % n
    side = quads(vertices, np.column_stack([j, k, n + k, n + j]), 2)
    return joined(vertices, [cap[:, ::-1], cap + n, side.triangles],
                  [np.zeros(len(cap), np.int64), np.ones(len(cap), np.int64), side.faces],
                  side.surfaces)


def box(shape: tuple):
    xs, ys = shape[0::2], shape[1::2]
    return (min(xs), min(ys), 0.0), (max(xs), max(ys), 1.0)


_convex: dict[tuple, tuple | None] = {}


def _convex_planes(shape):
    """The half-spaces of an extrusion whose polygon is convex (faces numbered
    as the walls and caps), or None."""
    import numpy as np

    if shape not in _convex:
        a, b = rays.outline(shape)
        e = b - a
        turns = e[:, 0] * np.roll(e[:, 1], -1) - e[:, 1] * np.roll(e[:, 0], -1)
        planes = None
        if np.all(turns > 0) or np.all(turns < 0):
            sign = 1.0 if np.all(turns > 0) else -1.0  # counter-clockwise: outward (ey, -ex)
            walls = np.column_stack([sign * e[:, 1], -sign * e[:, 0], np.zeros(len(e))])
            normals = np.concatenate([[[0.0, 0.0, -1.0], [0.0, 0.0, 1.0]], walls])
            offsets = np.concatenate([[0.0, 1.0], np.einsum("ij,ij->i", walls[:, :2], a)])
            planes = (normals, offsets)
        _convex[shape] = planes
    return _convex[shape]


def spans(shape, o, d):
    import numpy as np

    planes = _convex_planes(shape)
    if planes is not None:
        return rays.halfspaces(*planes, o, d)
    a, b = rays.outline(shape)
    e = b - a  # (m, 2)
    ox, oy, dx, dy = o[:, :1], o[:, 1:2], d[:, :1], d[:, 1:2]
    # o + t d = a + u e  (in x, y)
    det = dx * (-e[:, 1]) - dy * (-e[:, 0])
    rx, ry = a[:, 0] - ox, a[:, 1] - oy
    with np.errstate(divide="ignore", invalid="ignore"):
        t = (rx * (-e[:, 1]) - ry * (-e[:, 0])) / det
        u = (dx * ry - dy * rx) / det
    hit = (det != 0) & (u >= 0) & (u < 1)
    crossings = np.where(hit, t, INF)
    faces = np.broadcast_to(np.arange(len(a)) + 2, crossings.shape)
    t2, f2 = rays.pairs(crossings, faces, len(a))
    n = len(o)
    vertical = (d[:, 0] == 0) & (d[:, 1] == 0)
    if np.any(vertical):  # a ray along z: inside the polygon or not
        rows = np.flatnonzero(vertical)
        inside = _inside_polygon(o[rows, :2], a, b)
        if t2.shape[1] == 0:
            t2, f2 = np.full((n, 2), INF), np.zeros((n, 2), np.int64)
        t2[rows] = INF
        t2[rows[inside], 0] = -INF
        t2[rows[inside], 1] = INF
    s0, s1, c0, c1 = rays.slab(o, d)
    enter, leave = t2[:, 0::2], t2[:, 1::2]
    new_in, new_out = np.maximum(enter, s0[:, None]), np.minimum(leave, s1[:, None])
    f_in = np.where(s0[:, None] > enter, c0[:, None], f2[:, 0::2])
    f_out = np.where(s1[:, None] < leave, c1[:, None], f2[:, 1::2])
    ok = new_in <= new_out
    t = np.empty_like(t2)
    face = np.empty_like(f2)
    t[:, 0::2] = np.where(ok, new_in, INF)
    t[:, 1::2] = np.where(ok, new_out, INF)
    face[:, 0::2], face[:, 1::2] = f_in, f_out
    # empty spans to the end, the others in order
    order = np.argsort(t[:, 0::2], axis=1, kind="stable")
    t_in = np.take_along_axis(t[:, 0::2], order, axis=1)
    t_out = np.take_along_axis(t[:, 1::2], order, axis=1)
    t[:, 0::2], t[:, 1::2] = t_in, t_out
    face[:, 0::2] = np.take_along_axis(face[:, 0::2], order, axis=1)
    face[:, 1::2] = np.take_along_axis(face[:, 1::2], order, axis=1)
    return t, face


def _inside_polygon(points, a, b):
    import numpy as np

    x, y = points[:, :1], points[:, 1:2]
    crosses = ((a[:, 1] > y) != (b[:, 1] > y))
    with np.errstate(divide="ignore", invalid="ignore"):
        xc = a[:, 0] + (y - a[:, 1]) * (b[:, 0] - a[:, 0]) / (b[:, 1] - a[:, 1])
    return np.sum(crosses & (x < xc), axis=1) % 2 == 1


def normal(shape, p, face):
    import numpy as np

    a, b = rays.outline(shape)
    e = b - a
    n = np.zeros_like(p)
    wall = face >= 2
    edge = e[face[wall] - 2]
    n[wall, 0], n[wall, 1] = edge[:, 1], -edge[:, 0]
    n[face == 0, 2] = -1
    n[face == 1, 2] = 1
    return n




PRIMITIVE = PrimitiveKind(
    place=90, name="ex", title="extrusion", solid="a simple polygon in z = 0 swept to z = 1",
    arguments=(), pair_names=("x", "y"), curved=False, check=check, box=box,
    mesh=lambda shape, facets: extrusion(shape),
    triangles=lambda shape, facets: 4 * (len(shape) // 2),
    spans=spans, normal=normal)

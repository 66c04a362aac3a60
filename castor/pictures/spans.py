"""Where rays are inside each unit primitive, computed on its exact surface.

For rays ``o + t d`` in a primitive's own space (``d`` need not be a unit
vector: the parameter ``t`` is the scene ray's own, so that the spans of all
primitives can be combined), ``SPANS[kind].spans(shape, o, d)`` gives the
spans as two (n, 2K) arrays: ``t`` (entry, exit, entry, exit, ...; sorted;
``inf`` where a ray has fewer than K spans) and ``face`` (which face of the
primitive each crossing lies on). ``SPANS[kind].normal(shape, p, face)``
gives the (unnormalised) outward normal at points ``p`` on the given faces.

The cube, prisms and pyramids are intersections of half-spaces; the sphere,
cylinder and cone quadrics; the torus a quartic; ``!ex`` the even-odd
crossings of its walls clipped by its caps; ``!rv`` the crossings of the
cones, cylinders and discs its profile's segments sweep.
"""

from __future__ import annotations

import math
from typing import Callable, NamedTuple

import numpy as np

INF = np.inf


class Kind(NamedTuple):
    spans: Callable  # spans(shape, o, d) -> (t, face)
    normal: Callable  # normal(shape, p, face) -> (n, 3)
    box: Callable  # box(shape) -> (low, high) of the unit primitive


def _empty_like(n: int, k: int = 1):
    return np.full((n, 2 * k), INF), np.zeros((n, 2 * k), np.int64)


def _single(enter, leave, face_in, face_out):
    """One span per ray (enter <= leave), or none."""
    ok = enter <= leave
    t = np.empty((len(enter), 2))
    t[:, 0] = np.where(ok, enter, INF)
    t[:, 1] = np.where(ok, leave, INF)
    face = np.empty((len(enter), 2), np.int64)
    face[:, 0] = face_in
    face[:, 1] = face_out
    return t, face


# --- half-spaces: n . x <= c ------------------------------------------------


def _halfspaces(normals: np.ndarray, offsets: np.ndarray, o: np.ndarray, d: np.ndarray):
    """The span of each ray inside the intersection of the half-spaces; the
    face of a crossing is the number of its plane."""
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
    return _single(enter, leave, face_in, face_out)


def _halfspace_normal(normals):
    def normal(shape, p, face):
        return normals[face]
    return normal


_CUBE_PLANES = (np.array([[-1, 0, 0], [1, 0, 0], [0, -1, 0], [0, 1, 0], [0, 0, -1], [0, 0, 1]],
                         dtype=np.float64), np.array([0, 1, 0, 1, 0, 1], dtype=np.float64))


def _cube_spans(shape, o, d):
    return _halfspaces(*_CUBE_PLANES, o, d)


_polygon_planes: dict[tuple, tuple] = {}


def _prism_planes(n: int, pyramid: bool):
    key = (n, pyramid)
    if key not in _polygon_planes:
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
        _polygon_planes[key] = (normals, offsets)
    return _polygon_planes[key]


def _many_sides(n: int, pyramid: bool, o, d):
    """A polygon of very many sides: its half-spaces a block at a time."""
    normals, offsets = _prism_planes(n, pyramid)
    best_in, best_out = np.full(len(o), -INF), np.full(len(o), INF)
    face_in, face_out = np.zeros(len(o), np.int64), np.zeros(len(o), np.int64)
    for start in range(0, len(normals), 512):
        t, face = _halfspaces(normals[start:start + 512], offsets[start:start + 512], o, d)
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
    return _single(best_in, best_out, face_in, face_out)


def _prism_spans(shape, o, d):
    n = int(shape[0])
    if n > 512:
        return _many_sides(n, False, o, d)
    return _halfspaces(*_prism_planes(n, False), o, d)


def _pyramid_spans(shape, o, d):
    n = int(shape[0])
    if n > 512:
        return _many_sides(n, True, o, d)
    return _halfspaces(*_prism_planes(n, True), o, d)


def _polygon_normal(pyramid: bool):
    def normal(shape, p, face):
        return _prism_planes(int(shape[0]), pyramid)[0][face]
    return normal


# --- quadrics ----------------------------------------------------------------


def _roots(a, b, c):
    """The two roots of a t^2 + b t + c (t1 <= t2), NaN where there are none."""
    with np.errstate(divide="ignore", invalid="ignore"):
        disc = b * b - 4 * a * c
        root = np.sqrt(disc)
        q = -0.5 * (b + np.copysign(root, b))
        t1, t2 = q / a, c / q
    return np.minimum(t1, t2), np.maximum(t1, t2)


def _slab(o, d, low=0.0, high=1.0):
    """The span of each ray in low <= z <= high, with its faces (0 the bottom, 1 the top)."""
    oz, dz = o[:, 2], d[:, 2]
    with np.errstate(divide="ignore", invalid="ignore"):
        t0, t1 = (low - oz) / dz, (high - oz) / dz
    flat = dz == 0
    inside = (oz >= low) & (oz <= high)
    enter = np.where(flat, np.where(inside, -INF, INF), np.minimum(t0, t1))
    leave = np.where(flat, np.where(inside, INF, -INF), np.maximum(t0, t1))
    face_in = np.where(dz > 0, 0, 1)
    return enter, leave, face_in, 1 - face_in


def _sphere_spans(shape, o, d):
    a = np.einsum("ij,ij->i", d, d)
    b = 2 * np.einsum("ij,ij->i", o, d)
    c = np.einsum("ij,ij->i", o, o) - 1
    t1, t2 = _roots(a, b, c)
    ok = np.isfinite(t1) & np.isfinite(t2)
    return _single(np.where(ok, t1, INF), np.where(ok, t2, -INF), 0, 0)


def _sphere_normal(shape, p, face):
    return p


def _cylinder_spans(shape, o, d):
    a = d[:, 0] ** 2 + d[:, 1] ** 2
    b = 2 * (o[:, 0] * d[:, 0] + o[:, 1] * d[:, 1])
    c = o[:, 0] ** 2 + o[:, 1] ** 2 - 1
    t1, t2 = _roots(a, b, c)
    vertical = a == 0
    t1 = np.where(vertical, np.where(c <= 0, -INF, INF), t1)
    t2 = np.where(vertical, np.where(c <= 0, INF, -INF), t2)
    ok = ~(np.isnan(t1) | np.isnan(t2))
    t1, t2 = np.where(ok, t1, INF), np.where(ok, t2, -INF)
    s0, s1, f0, f1 = _slab(o, d)
    enter = np.maximum(t1, s0)
    leave = np.minimum(t2, s1)
    return _single(enter, leave, np.where(s0 > t1, f0 + 1, 0), np.where(s1 < t2, f1 + 1, 0))


def _cylinder_normal(shape, p, face):
    n = np.zeros_like(p)
    side = face == 0
    n[side, 0], n[side, 1] = p[side, 0], p[side, 1]
    n[face == 1, 2] = -1
    n[face == 2, 2] = 1
    return n


def _cone_spans(shape, o, d):
    w0, dw = 1 - o[:, 2], -d[:, 2]
    a = d[:, 0] ** 2 + d[:, 1] ** 2 - dw ** 2
    b = 2 * (o[:, 0] * d[:, 0] + o[:, 1] * d[:, 1] - w0 * dw)
    c = o[:, 0] ** 2 + o[:, 1] ** 2 - w0 ** 2
    a = np.where(np.abs(a) < 1e-14, 1e-14, a)
    t1, t2 = _roots(a, b, c)
    real = np.isfinite(t1) & np.isfinite(t2)
    s0, s1, f0, f1 = _slab(o, d)
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
    return _single(best_in, best_out, face_in, face_out)


def _cone_normal(shape, p, face):
    n = np.zeros_like(p)
    side = face == 0
    n[side, 0], n[side, 1] = p[side, 0], p[side, 1]
    n[side, 2] = np.hypot(p[side, 0], p[side, 1])
    n[face == 1, 2] = -1
    n[face == 2, 2] = 1
    return n


# --- the torus: a quartic ----------------------------------------------------


def _torus_spans(shape, o, d):
    k = shape[0]
    n = len(o)
    scale = np.linalg.norm(d, axis=1)
    u = d / scale[:, None]
    # start each ray near the torus (at its bounding sphere) for accuracy
    start = -np.einsum("ij,ij->i", o, u)
    p = o + start[:, None] * u
    # (|p + s u|^2 + 1 - k^2)^2 - 4 ((px + s ux)^2 + (py + s uy)^2) = 0
    pu = np.einsum("ij,ij->i", p, u)
    pp = np.einsum("ij,ij->i", p, p)
    e = pp + 1 - k * k
    c3 = 4 * pu  # the quartic is monic: its s^4 coefficient is 1
    c2 = 2 * e + 4 * pu * pu - 4 * (u[:, 0] ** 2 + u[:, 1] ** 2)
    c1 = 4 * pu * e - 8 * (p[:, 0] * u[:, 0] + p[:, 1] * u[:, 1])
    c0 = e * e - 4 * (p[:, 0] ** 2 + p[:, 1] ** 2)
    companion = np.zeros((n, 4, 4))
    companion[:, 0, :] = -np.column_stack([c3, c2, c1, c0])
    companion[:, 1, 0] = companion[:, 2, 1] = companion[:, 3, 2] = 1
    roots = np.linalg.eigvals(companion) if n else np.zeros((0, 4), complex)
    real = np.abs(roots.imag) <= 1e-6 * (1 + np.abs(roots.real))
    s = np.where(real, roots.real, np.nan)
    for _ in range(2):  # Newton polishes the eigenvalues
        f = (((s + c3[:, None]) * s + c2[:, None]) * s + c1[:, None]) * s + c0[:, None]
        g = ((4 * s + 3 * c3[:, None]) * s + 2 * c2[:, None]) * s + c1[:, None]
        with np.errstate(divide="ignore", invalid="ignore"):
            step = np.where(g != 0, f / g, 0)
        s = s - np.where(np.abs(step) < 1e-2 * (1 + k), step, 0)
    s = np.sort(np.where(np.isnan(s), INF, s), axis=1)
    count = np.sum(np.isfinite(s), axis=1)
    s = np.where((count % 2 == 1)[:, None], INF, s)  # a tangent double root: no span
    t = (s + start[:, None]) / scale[:, None]
    return t, np.zeros((n, 4), np.int64)


def _torus_normal(shape, p, face):
    k = shape[0]
    q = np.einsum("ij,ij->i", p, p) + 1 - k * k
    n = p * q[:, None]
    n[:, 0] -= 2 * p[:, 0]
    n[:, 1] -= 2 * p[:, 1]
    return n


# --- !ex: walls crossed even-odd, clipped by the caps ------------------------


def _outline(shape):
    points = np.asarray(shape, dtype=np.float64).reshape(-1, 2)
    return points, np.roll(points, -1, axis=0)


def _pairs(crossings, faces, n):
    """Spans from the sorted crossings of closed surfaces along each ray (even-odd)."""
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


_convex: dict[tuple, tuple | None] = {}


def _convex_planes(shape):
    """The half-spaces of an extrusion whose polygon is convex (faces numbered
    as the walls and caps), or None."""
    if shape not in _convex:
        a, b = _outline(shape)
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


def _extrusion_spans(shape, o, d):
    planes = _convex_planes(shape)
    if planes is not None:
        return _halfspaces(*planes, o, d)
    a, b = _outline(shape)
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
    t2, f2 = _pairs(crossings, faces, len(a))
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
    s0, s1, c0, c1 = _slab(o, d)
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
    x, y = points[:, :1], points[:, 1:2]
    crosses = ((a[:, 1] > y) != (b[:, 1] > y))
    with np.errstate(divide="ignore", invalid="ignore"):
        xc = a[:, 0] + (y - a[:, 1]) * (b[:, 0] - a[:, 0]) / (b[:, 1] - a[:, 1])
    return np.sum(crosses & (x < xc), axis=1) % 2 == 1


def _extrusion_normal(shape, p, face):
    a, b = _outline(shape)
    e = b - a
    n = np.zeros_like(p)
    wall = face >= 2
    edge = e[face[wall] - 2]
    n[wall, 0], n[wall, 1] = edge[:, 1], -edge[:, 0]
    n[face == 0, 2] = -1
    n[face == 1, 2] = 1
    return n


def _extrusion_box(shape):
    points = np.asarray(shape, dtype=np.float64).reshape(-1, 2)
    low, high = points.min(axis=0), points.max(axis=0)
    return (low[0], low[1], 0.0), (high[0], high[1], 1.0)


# --- !rv: the surfaces its profile's segments sweep --------------------------


def _revolution_spans(shape, o, d):
    a, b = _outline(shape)
    crossings, faces = [], []
    ox, oy, oz = o[:, 0], o[:, 1], o[:, 2]
    dx, dy, dz = d[:, 0], d[:, 1], d[:, 2]
    qa = dx * dx + dy * dy
    qb = 2 * (ox * dx + oy * dy)
    qc = ox * ox + oy * oy
    for index, ((r1, z1), (r2, z2)) in enumerate(zip(a, b)):
        if r1 == 0 and r2 == 0:
            continue
        if z1 == z2:  # a disc or a ring in z = z1
            with np.errstate(divide="ignore", invalid="ignore"):
                t = (z1 - oz) / dz
            px, py = ox + t * dx, oy + t * dy
            rho = np.sqrt(px * px + py * py)
            lo, hi = min(r1, r2), max(r1, r2)
            # the segment includes its first point, not its last
            ok = (dz != 0) & (rho > lo) & (rho <= hi) if r1 > r2 else \
                (dz != 0) & (rho >= lo) & (rho < hi)
            crossings.append(np.where(ok, t, INF))
            faces.append(index)
            continue
        # r = r1 + m (z - z1), m = (r2 - r1) / (z2 - z1): rho^2 = (c + m t dz)^2
        m = (r2 - r1) / (z2 - z1)
        c = r1 + m * (oz - z1)
        g = m * dz
        t1, t2 = _roots(qa - g * g, qb - 2 * c * g, qc - c * c)
        for t in (t1, t2):
            z = oz + t * dz
            u = (z - z1) / (z2 - z1)
            r = c + g * t
            ok = np.isfinite(t) & (u >= 0) & (u < 1) & (r >= 0)
            crossings.append(np.where(ok, t, INF))
            faces.append(index)
    if not crossings:
        return _empty_like(len(o), 0)
    crossings = np.column_stack(crossings)
    faces = np.broadcast_to(np.array(faces, np.int64), crossings.shape)
    return _pairs(crossings, faces, len(a))


def _revolution_normal(shape, p, face):
    a, b = _outline(shape)
    e = b - a
    dr, dz = e[face, 0], e[face, 1]
    rho = np.hypot(p[:, 0], p[:, 1])
    safe = np.where(rho > 0, rho, 1)
    # the profile's normal (dz, -dr) turned about the axis to the point
    n = np.column_stack([dz * p[:, 0] / safe, dz * p[:, 1] / safe, -dr])
    return n


def _revolution_box(shape):
    points = np.asarray(shape, dtype=np.float64).reshape(-1, 2)
    r = float(points[:, 0].max())
    return (-r, -r, float(points[:, 1].min())), (r, r, float(points[:, 1].max()))


_UNIT = ((0.0, 0.0, 0.0), (1.0, 1.0, 1.0))
_ROUND = ((-1.0, -1.0, 0.0), (1.0, 1.0, 1.0))

SPANS: dict[str, Kind] = {
    "cu": Kind(_cube_spans, _halfspace_normal(_CUBE_PLANES[0]), lambda shape: _UNIT),
    "sp": Kind(_sphere_spans, _sphere_normal, lambda shape: ((-1.0,) * 3, (1.0,) * 3)),
    "cy": Kind(_cylinder_spans, _cylinder_normal, lambda shape: _ROUND),
    "co": Kind(_cone_spans, _cone_normal, lambda shape: _ROUND),
    "to": Kind(_torus_spans, _torus_normal,
               lambda shape: ((-1 - shape[0], -1 - shape[0], -shape[0]),
                              (1 + shape[0], 1 + shape[0], shape[0]))),
    "pr": Kind(_prism_spans, _polygon_normal(False), lambda shape: _ROUND),
    "py": Kind(_pyramid_spans, _polygon_normal(True), lambda shape: _ROUND),
    "ex": Kind(_extrusion_spans, _extrusion_normal, _extrusion_box),
    "rv": Kind(_revolution_spans, _revolution_normal, _revolution_box),
}

# a smooth solid (LANGUAGE.md §7.1): its shape is its refined facets, ready
# for rays (castor.pictures.mesh_rays.MeshRays), its box theirs
SPANS["smooth"] = Kind(lambda rays, o, d: rays.spans(o, d),
                       lambda rays, p, face: rays.normal(p, face), lambda rays: rays.box())

"""``!rv``: a simple profile (r1, z1, ..., all r >= 0) turned a full circle
about the z axis. Each segment of the profile sweeps one surface: a flat disc
or ring where it is level, else a band of a cone or cylinder (curved surface
number = the segment's number). A ray meets it as the crossings of those
cones, cylinders and discs."""

from __future__ import annotations

import math

from castor.diagnostics import Location
from castor.primitives import rays
from castor.primitives.base import FLAT, Mesh, PrimitiveKind
from castor.primitives.facets import circle_segments, joined, plane_stretch, quantize, signed_volume

INF = math.inf


def check(shape: tuple, location: Location, path: object) -> None:
    from castor.primitives.simple_polygon import profile

    profile(shape, location, path)


def revolution(values: tuple, segments: int) -> Mesh:
    """The simple profile (r1, z1, ...) turned a full circle about the z axis."""
    import numpy as np

    from castor.primitives.simple_polygon import profile, signed_area

    outline = profile(values, None, "")
    if signed_area(outline) < 0:
        outline = outline[::-1].copy()
    n = segments
    m = len(outline)
    on_axis = outline[:, 0] == 0
    # vertex numbers: one per profile point on the axis, n per point off it
    first = np.zeros(m, np.int64)
    count = np.where(on_axis, 1, n)
    first[1:] = np.cumsum(count)[:-1]
    angles = 2 * np.pi * np.arange(n) / n
    cos, sin = np.cos(angles), np.sin(angles)
    sin[0] = 0.0
    blocks = []
    for (r, z), axis in zip(outline, on_axis):
        if axis:
            blocks.append([[0.0, 0.0, z]])
        else:
            blocks.append(np.column_stack([r * cos, r * sin, np.full(n, z)]))
    vertices = np.concatenate([np.asarray(b, dtype=np.float64) for b in blocks])
    j = np.arange(n)
    k = (j + 1) % n
    tris, faces, surfaces = [], [], []
    face = 0
    for a in range(m):
        b = (a + 1) % m
        if on_axis[a] and on_axis[b]:
            continue
        va = first[a] + (0 if on_axis[a] else j)
        vb = first[b] + (0 if on_axis[b] else j)
        va1 = first[a] + (0 if on_axis[a] else k)
        vb1 = first[b] + (0 if on_axis[b] else k)
        # profile counter-clockwise in (r, z): a quad (a_j, b_j, b_j+1, a_j+1) faces out
        # after turning the orientation round (checked below by the volume's sign)
        if on_axis[a]:
            block = np.column_stack([va1 * np.ones(n, np.int64), vb, vb1])
        elif on_axis[b]:
            block = np.column_stack([va, vb * np.ones(n, np.int64), va1])
        else:
            block = np.concatenate([np.column_stack([va, vb, vb1]), np.column_stack([va, vb1, va1])])
        tris.append(block)
        per = n if (on_axis[a] or on_axis[b]) else 2 * n
        faces.append(face + (np.arange(per) % n))
        face += n
        # a level segment sweeps a flat disc or ring; any other, curved surface a
        surfaces.append(np.full(n, FLAT if outline[a, 1] == outline[b, 1] else a, np.int64))
    mesh = joined(vertices, tris, faces, np.concatenate(surfaces))
    if signed_volume(mesh.vertices, mesh.triangles) < 0:
        mesh = mesh._replace(triangles=mesh.triangles[:, ::-1].copy())
    return mesh


def facets(shape: tuple, linear, tolerance: float) -> tuple[int]:
    """(segments,): those of its largest ring, as stretched in its xy plane.
    The profile is straight segments, kept as they are: between two rings a
    facet differs from the surface only across, along a ring's chord, which
    lies in an xy plane whatever the map does along z."""
    radius = max(shape[0::2]) if shape else 0.0
    return (circle_segments(radius, quantize(tolerance / plane_stretch(linear))),)


def box(shape: tuple):
    r = max(shape[0::2])
    return (-r, -r, min(shape[1::2])), (r, r, max(shape[1::2]))


def spans(shape, o, d):
    import numpy as np

    a, b = rays.outline(shape)
    crossings, faces = [], []
    ox, oy, oz = o[:, 0], o[:, 1], o[:, 2]
    dx, dy, dz = d[:, 0], d[:, 1], d[:, 2]
    qa = dx * dx + dy * dy
    qb = 2 * (ox * dx + oy * dy)
    qc = ox * ox + oy * oy
    # a ray parallel to a disc meets its plane nowhere (t infinite, then 0 * inf),
    # one that misses a cone has no roots: masked below, never a warning
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        for index, ((r1, z1), (r2, z2)) in enumerate(zip(a, b)):
            if r1 == 0 and r2 == 0:
                continue
            if z1 == z2:  # a disc or a ring in z = z1
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
            t1, t2 = rays.roots(qa - g * g, qb - 2 * c * g, qc - c * c)
            for t in (t1, t2):
                z = oz + t * dz
                u = (z - z1) / (z2 - z1)
                r = c + g * t
                ok = np.isfinite(t) & (u >= 0) & (u < 1) & (r >= 0)
                crossings.append(np.where(ok, t, INF))
                faces.append(index)
    if not crossings:
        return rays.empty_like(len(o), 0)
    crossings = np.column_stack(crossings)
    faces = np.broadcast_to(np.array(faces, np.int64), crossings.shape)
    return rays.pairs(crossings, faces, len(a))


def normal(shape, p, face):
    import numpy as np

    a, b = rays.outline(shape)
    e = b - a
    dr, dz = e[face, 0], e[face, 1]
    rho = np.hypot(p[:, 0], p[:, 1])
    safe = np.where(rho > 0, rho, 1)
    # the profile's normal (dz, -dr) turned about the axis to the point
    n = np.column_stack([dz * p[:, 0] / safe, dz * p[:, 1] / safe, -dr])
    return n




PRIMITIVE = PrimitiveKind(
    place=95, name="rv", title="revolution", solid="a simple profile (r, z), r >= 0, turned about z",
    arguments=(), pair_names=("r", "z"), curved=True, check=check, box=box,
    mesh=lambda shape, facets: revolution(shape, facets[0]),
    triangles=lambda shape, facets: 2 * (len(shape) // 2) * facets[0],
    spans=spans, normal=normal, facets=facets)

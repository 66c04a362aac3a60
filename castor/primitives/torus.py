"""``!to``: the torus about the z axis, centre circle of radius 1 in z = 0,
tube radius K: one curved surface of quads; a ray meets it as a quartic."""

from __future__ import annotations

import math

from castor.diagnostics import GeometryError, Location
from castor.primitives.base import Argument, Mesh, PrimitiveKind
from castor.primitives.facets import (circle_segments, largest_stretch, plane_stretch, quads,
                                     quantize)

INF = math.inf


def check(shape: tuple, location: Location, path: object) -> None:
    k = shape[0]
    if not 0 < k < 1:
        raise GeometryError(f"the tube radius K of {path} must lie strictly between 0 and 1, "
                            f"not {k:g}", location)


def facets(shape, linear, tolerance) -> tuple[int, int]:
    """(around the axis, around the tube), each circle within half the
    tolerance: the circles about the axis (radius up to 1 + K) as stretched in
    the xy plane, the tube's circles (radius K, each in an upright plane
    through the axis) by the largest stretch of any such plane, which is the
    largest stretch of all (every direction lies in one of them). A point of
    the torus and the point of its quad at the same angles differ by a gap of
    the first circle plus a gap of the second, so the two halves add up."""
    k = shape[0]
    return (circle_segments(1.0 + k, quantize(tolerance / plane_stretch(linear)) / 2),
            circle_segments(k, quantize(tolerance / largest_stretch(linear)) / 2))


def torus(k: float, around: int, tube: int) -> Mesh:
    """Torus: centre circle of radius 1 in z = 0, tube radius k."""
    import numpy as np

    theta = 2 * np.pi * np.arange(around) / around
    phi = 2 * np.pi * np.arange(tube) / tube
    radius = 1.0 + k * np.cos(phi)
    vertices = np.empty((around, tube, 3))
    vertices[..., 0] = np.cos(theta)[:, None] * radius[None, :]
    vertices[..., 1] = np.sin(theta)[:, None] * radius[None, :]
    vertices[..., 2] = (k * np.sin(phi))[None, :]
    vertices[0, :, 1] = 0.0
    i = np.arange(around)[:, None]
    j = np.arange(tube)[None, :]
    i1, j1 = (i + 1) % around, (j + 1) % tube
    corners = np.stack([i * tube + j, i1 * tube + j, i1 * tube + j1, i * tube + j1], axis=-1)
    return quads(vertices.reshape(-1, 3), corners.reshape(-1, 4), 0, surface=0)


def spans(shape, o, d):
    import numpy as np

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


def normal(shape, p, face):
    import numpy as np

    k = shape[0]
    q = np.einsum("ij,ij->i", p, p) + 1 - k * k
    n = p * q[:, None]
    n[:, 0] -= 2 * p[:, 0]
    n[:, 1] -= 2 * p[:, 1]
    return n


PRIMITIVE = PrimitiveKind(
    place=50, name="to", title="torus", solid="centre circle of radius 1 in z = 0, tube radius K",
    arguments=(Argument("K", "the tube radius, 0 < K < 1"),), pair_names=None, curved=True,
    check=check,
    box=lambda shape: ((-1 - shape[0], -1 - shape[0], -shape[0]),
                       (1 + shape[0], 1 + shape[0], shape[0])),
    mesh=lambda shape, facets: torus(shape[0], *facets),
    triangles=lambda shape, facets: 2 * math.prod(facets),
    spans=spans, normal=normal, facets=facets)

"""A z-buffer renderer in numpy: flat-shaded polygons, wireframes and edges.

Triangles are rasterized in batches: every candidate pixel of a batch's
bounding boxes is tested at once with barycentric coordinates, and the nearest
surface per pixel wins (np.minimum.at). No Python loop runs per pixel.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from castor.view.scene import Picture

BACKGROUND = np.array([1.0, 1.0, 1.0])
EDGE_COLOUR = np.array([0.1, 0.1, 0.12])
_BATCH_PIXELS = 3_000_000


@dataclass
class Camera:
    eye: np.ndarray
    look: np.ndarray
    up: np.ndarray
    fov: float  # vertical field of view, degrees

    def basis(self):
        forward = self.look - self.eye
        forward = forward / np.linalg.norm(forward)
        right = np.cross(forward, self.up)
        if np.linalg.norm(right) < 1e-9:
            right = np.cross(forward, np.array([0.0, 1.0, 0.0]))
        right /= np.linalg.norm(right)
        up = np.cross(right, forward)
        return right, up, forward


def frame_camera(points: np.ndarray, azimuth: float, elevation: float, aspect: float) -> Camera:
    """A camera looking from (azimuth, elevation) that frames all the points,
    as close as it can while every point stays in the picture."""
    if len(points) == 0:
        points = np.zeros((1, 3))
    low, high = points.min(axis=0), points.max(axis=0)
    centre = (low + high) / 2
    radius = max(float(np.linalg.norm(high - low)) / 2, 1e-9)
    a, e = math.radians(azimuth), math.radians(elevation)
    direction = np.array([math.cos(e) * math.cos(a), math.cos(e) * math.sin(a), math.sin(e)])
    fov = 35.0
    up = np.array([0.0, 0.0, 1.0])
    if abs(direction[2]) > 0.999:
        up = np.array([0.0, 1.0, 0.0])
    camera = Camera(centre + direction * radius * 3, centre, up, fov)
    right, true_up, forward = camera.basis()
    # the 8 corners of the box suffice: the nearest distance at which each
    # corner is inside the picture, for a camera looking at the centre
    box = np.array([[x, y, z] for x in (low[0], high[0]) for y in (low[1], high[1])
                    for z in (low[2], high[2])])
    tan_v = math.tan(math.radians(fov) / 2) * 0.94
    tan_h = tan_v * aspect
    for _ in range(3):  # fit, then move sideways to centre the picture, and fit again
        corners = box - centre
        across, along, depth = corners @ right, corners @ true_up, corners @ forward
        distance = float(np.max(np.maximum(np.abs(across) / tan_h, np.abs(along) / tan_v)
                                - depth))
        distance = max(distance, radius * 0.5, 1e-9)
        u, v = across / (distance + depth), along / (distance + depth)
        centre = centre + (right * (u.max() + u.min()) / 2
                           + true_up * (v.max() + v.min()) / 2) * distance
    return Camera(centre - forward * distance, centre, up, fov)


def _project(points: np.ndarray, camera: Camera, width: int, height: int):
    right, up, forward = camera.basis()
    rel = points - camera.eye
    x, y, z = rel @ right, rel @ up, rel @ forward
    scale = (height / 2) / math.tan(math.radians(camera.fov) / 2)
    z_safe = np.where(z > 1e-9, z, 1e-9)
    sx = width / 2 + x / z_safe * scale
    sy = height / 2 - y / z_safe * scale
    return np.column_stack([sx, sy]), z


def _shade(picture: Picture, camera: Camera) -> np.ndarray:
    """Polygon colours lit from over the viewer's left shoulder."""
    right, up, forward = camera.basis()
    light = -forward * 0.55 + up * 0.65 - right * 0.45
    light /= np.linalg.norm(light)
    pts = picture.points
    normals = np.zeros((picture.polygon_count, 3))
    starts = picture.offsets[:-1]
    sizes = np.diff(picture.offsets)
    nxt = np.arange(len(pts)) + 1
    nxt[picture.offsets[1:] - 1] = starts
    cross = np.cross(pts, pts[nxt])
    polygon = np.repeat(np.arange(len(sizes)), sizes)
    np.add.at(normals, polygon, cross)
    length = np.linalg.norm(normals, axis=1, keepdims=True)
    normals = np.divide(normals, length, out=np.zeros_like(normals), where=length > 0)
    diffuse = np.clip(normals @ light, 0, 1)
    facing = np.clip(-(normals @ forward), 0, 1)
    intensity = 0.28 + 0.55 * diffuse + 0.17 * facing
    return np.clip(picture.colours * intensity[:, None], 0, 1)


def render(picture: Picture, camera: Camera, width: int, height: int,
           mode: str = "shaded") -> np.ndarray:
    """An (height, width, 3) uint8 image of the picture."""
    image = np.tile(BACKGROUND, (height, width, 1))
    depth = np.full(height * width, np.inf)
    screen, z = _project(picture.points, camera, width, height)
    if mode != "wire" and picture.polygon_count:
        colours = _shade(picture, camera)
        tris, polygon = picture.triangles()
        visible = np.all(z[tris] > 1e-6, axis=1)
        tris, polygon = tris[visible], polygon[visible]
        pixel_colour = np.zeros((height * width, 3))
        _rasterize(screen, z, tris, polygon, colours, width, height, depth, pixel_colour)
        hit = np.isfinite(depth)
        image.reshape(-1, 3)[hit] = pixel_colour[hit]
    if mode in ("wire", "edges"):
        _draw_edges(picture, screen, z, image, depth if mode == "edges" else None, width, height)
    return np.clip(np.rint(image * 255), 0, 255).astype(np.uint8)


def _rasterize(screen, z, tris, polygon, colours, width, height, depth, pixel_colour):
    a, b, c = screen[tris[:, 0]], screen[tris[:, 1]], screen[tris[:, 2]]
    low = np.floor(np.minimum(np.minimum(a, b), c)).astype(np.int64)
    high = np.ceil(np.maximum(np.maximum(a, b), c)).astype(np.int64)
    low = np.clip(low, 0, [width - 1, height - 1])
    high = np.clip(high, 0, [width - 1, height - 1])
    spans = (high - low + 1)
    areas = spans[:, 0] * spans[:, 1]
    on_screen = (high[:, 0] >= low[:, 0]) & (high[:, 1] >= low[:, 1]) & (areas > 0)
    index = np.flatnonzero(on_screen)
    start = 0
    cumulative = np.cumsum(areas[index])
    while start < len(index):
        base = cumulative[start - 1] if start else 0
        stop = int(np.searchsorted(cumulative, base + _BATCH_PIXELS, side="right"))
        stop = max(stop, start + 1)
        batch = index[start:stop]
        _rasterize_batch(batch, a, b, c, low, spans, areas, z, tris, polygon, colours,
                         width, depth, pixel_colour)
        start = stop


def _rasterize_batch(batch, a, b, c, low, spans, areas, z, tris, polygon, colours, width,
                     depth, pixel_colour):
    counts = areas[batch]
    tri = np.repeat(batch, counts)
    local = np.arange(int(counts.sum())) - np.repeat(np.cumsum(counts) - counts, counts)
    w = spans[tri, 0]
    px = low[tri, 0] + local % w
    py = low[tri, 1] + local // w
    cx, cy = px + 0.5, py + 0.5
    ax, ay = a[tri, 0], a[tri, 1]
    bx, by = b[tri, 0], b[tri, 1]
    qx, qy = c[tri, 0], c[tri, 1]
    area = (bx - ax) * (qy - ay) - (by - ay) * (qx - ax)
    with np.errstate(divide="ignore", invalid="ignore"):
        w0 = ((bx - cx) * (qy - cy) - (by - cy) * (qx - cx)) / area
        w1 = ((qx - cx) * (ay - cy) - (qy - cy) * (ax - cx)) / area
        w2 = 1 - w0 - w1
    eps = -1e-9
    inside = (area != 0) & (w0 >= eps) & (w1 >= eps) & (w2 >= eps)
    if not np.any(inside):
        return
    tri, px, py = tri[inside], px[inside], py[inside]
    w0, w1, w2 = w0[inside], w1[inside], w2[inside]
    corners = tris[tri]
    # perspective-correct depth: interpolate 1/z across the screen
    inv = w0 / z[corners[:, 0]] + w1 / z[corners[:, 1]] + w2 / z[corners[:, 2]]
    d = 1.0 / inv
    pixel = py * width + px
    np.minimum.at(depth, pixel, d)
    win = d <= depth[pixel]
    pixel_colour[pixel[win]] = colours[polygon[tri[win]]]


def _draw_edges(picture, screen, z, image, depth, width, height):
    """Polygon outlines; with a depth buffer, only where the surface is visible."""
    pts = picture.offsets
    count = len(picture.points)
    if count == 0:
        return
    nxt = np.arange(count) + 1
    nxt[pts[1:] - 1] = pts[:-1]
    start, end = np.arange(count), nxt
    keep = (z[start] > 1e-6) & (z[end] > 1e-6)
    start, end = start[keep], end[keep]
    lengths = np.ceil(np.linalg.norm(screen[end] - screen[start], axis=1)).astype(np.int64) + 1
    lengths = np.minimum(lengths, 4 * (width + height))
    edge = np.repeat(np.arange(len(start)), lengths)
    t = (np.arange(int(lengths.sum())) - np.repeat(np.cumsum(lengths) - lengths, lengths)) \
        / np.maximum(np.repeat(lengths, lengths) - 1, 1)
    s0, s1 = start[edge], end[edge]
    xy = screen[s0] * (1 - t)[:, None] + screen[s1] * t[:, None]
    inv = (1 - t) / z[s0] + t / z[s1]
    d = 1.0 / inv
    px, py = np.floor(xy[:, 0]).astype(np.int64), np.floor(xy[:, 1]).astype(np.int64)
    ok = (px >= 0) & (px < width) & (py >= 0) & (py < height)
    px, py, d = px[ok], py[ok], d[ok]
    if depth is not None:
        # near the visible surface: allow for the depth's own interpolation error
        pixel = py * width + px
        ok = d <= depth[pixel] * (1 + 2e-3) + 1e-9
        px, py = px[ok], py[ok]
    image[py, px] = EDGE_COLOUR

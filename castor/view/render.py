"""A z-buffer renderer in numpy: flat-shaded polygons, wireframes and edges.

Triangles are rasterized in batches: every candidate pixel of a batch's
bounding boxes is tested at once with barycentric coordinates, and the nearest
surface per pixel wins (np.minimum.at). No Python loop runs per pixel.
"""

from __future__ import annotations

import numpy as np

from castor.pictures.camera import Camera
from castor.view.scene import Picture

BACKGROUND = np.array([1.0, 1.0, 1.0])
EDGE_COLOUR = np.array([0.1, 0.1, 0.12])
_BATCH_PIXELS = 3_000_000


def _project(points: np.ndarray, camera: Camera, width: int, height: int):
    return camera.project(points)


def _shade(picture: Picture, camera: Camera) -> np.ndarray:
    """Polygon colours lit as castor's pictures are (castor.pictures.shade), by
    the default sun, without shadows."""
    from castor.options import DEFAULT_SUN
    from castor.pictures.camera import direction
    from castor.pictures.shade import intensity

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
    if camera.orthographic:
        towards = np.broadcast_to(-camera.forward, normals.shape)
    else:
        towards = camera.eye - pts[starts]
        towards = towards / np.maximum(np.linalg.norm(towards, axis=1, keepdims=True), 1e-300)
    back = np.einsum("ij,ij->i", normals, towards) < 0
    normals[back] *= -1
    strength = intensity(normals, towards, direction(*DEFAULT_SUN), np.ones(len(normals)))
    return np.clip(picture.colours * strength[:, None], 0, 1)


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

"""A z-buffer renderer in numpy: lit polygons, outline edges and wireframes.

The picture is drawn at twice its size and averaged down, so edges are
anti-aliased. Triangles are rasterized in batches: every candidate pixel of a
batch's bounding boxes is tested at once with barycentric coordinates, and the
nearest surface per pixel wins (np.minimum.at); each pixel keeps the number of
its polygon, from which its colour and normal come. No Python loop runs per
pixel. Edges are outlines only: ``--edges`` from the changes of depth and
of surface between pixels (as castor's pictures; castor.mesh.creases), ``--wire`` the polygons' edges
except those between two coplanar polygons, so a flat face cut into convex
pieces shows no diagonals.

The facets of one curved surface (a sphere's, a smooth solid's: guessed from
the polygons' paths and the turns between them, ``_surfaces``) are shaded
smoothly, as castor's pictures shade a smooth solid
(castor.pictures.mesh_rays): each pixel takes the normal interpolated across
its triangle from the normals at its corners, the mean of the normals of the
facets of the same surface around each vertex. A flat face, and each side of
a crease, keeps its own normal.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from castor.mesh.creases import COPLANAR, curved_kinds, guessed_same_surface
from castor.pictures.camera import Camera
from castor.formats.cps import StreamFrame

BACKGROUND = np.array([1.0, 1.0, 1.0])
EDGE_COLOUR = np.array([0.12, 0.12, 0.14])
SUPERSAMPLE = 2  # drawn at this many times the size on each side, then averaged
_BATCH_PIXELS = 400_000
SMOOTH_CORNERS = 8  # see _smooth_paths


def _normals(picture: StreamFrame) -> np.ndarray:
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
    return np.divide(normals, length, out=np.zeros_like(normals), where=length > 0)


def _shade(picture: StreamFrame, camera: Camera,
           normals: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Polygon colours lit as castor's pictures are (castor.pictures.shade), by
    the default sun, without shadows; the normals are turned to the viewer, and
    which were is returned beside the colours."""
    if camera.orthographic:
        towards = np.broadcast_to(-camera.forward, normals.shape)
    else:
        towards = camera.eye - picture.points[picture.offsets[:-1]]
    back = np.einsum("ij,ij->i", normals, towards) < 0
    normals[back] *= -1
    return _lit(picture.colours, normals, camera), back


def _lit(colours: np.ndarray, normals: np.ndarray, camera: Camera) -> np.ndarray:
    """Colours lit by the default sun for unit normals turned to the viewer,
    with one direction to the viewer for all, so that the pieces of a flat face
    are lit alike."""
    from castor.settings import DEFAULT_SUN
    from castor.pictures.shade import intensity, sun_light

    towards = np.broadcast_to(-camera.forward, normals.shape)
    light, _ = sun_light(DEFAULT_SUN, camera)  # beside the camera, as castor's pictures
    strength = intensity(normals, towards, light, np.ones(len(normals)))
    return np.clip(colours * strength[:, None], 0, 1)


def render(picture: StreamFrame, camera: Camera, width: int, height: int,
           mode: str = "shaded") -> np.ndarray:
    """An (height, width, 3) uint8 image of the picture: ``mode`` "shaded",
    "edges" (shaded with outline edges) or "wire"."""
    from castor.pictures.shade import edges

    k = SUPERSAMPLE
    big_w, big_h = width * k, height * k
    big = dataclasses.replace(camera, width=big_w, height=big_h)
    screen, z = big.project(picture.points)
    depth = np.full(big_h * big_w, np.inf)
    owner = np.full(big_h * big_w, -1, np.int32)
    image = np.empty((big_h * big_w, 3), np.float32)
    image[:] = BACKGROUND
    normals = _normals(picture)
    if mode != "wire" and picture.polygon_count:
        surfaces = _surfaces(picture, normals)  # before the normals are turned to the viewer
        tris, polygon = picture.triangles()
        corners = _corner_normals(picture, tris, polygon, surfaces)
        colours, back = _shade(picture, big, normals)
        visible = np.all(z[tris] > 1e-6, axis=1)
        tris, polygon = tris[visible], polygon[visible]
        # each pixel's triangle, then its polygon
        _rasterize(screen, z, tris, np.arange(len(tris)), big_w, big_h, depth, owner,
                   big.orthographic)
        hit = np.flatnonzero(owner >= 0)
        triangle = owner[hit]
        owner[hit] = polygon[triangle]
        image[hit] = colours[owner[hit]]
        if corners is not None:
            _shade_smoothly(image, hit, triangle, polygon, tris, corners[visible], back, screen, z,
                            picture, big)
    image = image.reshape(big_h, big_w, 3)
    if mode == "edges" and picture.polygon_count:
        strength = np.zeros((big_h, big_w), np.float32)
        owner2, depth2 = owner.reshape(big_h, big_w), depth.reshape(big_h, big_w)
        surface = np.append(surfaces, -1)  # owner -1: nothing
        band = 128
        for top in range(0, big_h, band):  # a band of rows at a time: bounded memory
            rows = slice(top, min(top + band + 1, big_h))
            here = owner2[rows]
            pixel_normals = np.zeros(here.shape + (3,), np.float32)
            hit = here >= 0
            pixel_normals[hit] = normals[here[hit]]
            part = edges(surface[here], depth2[rows].astype(np.float32), pixel_normals)
            strength[rows] = np.maximum(strength[rows], part)
        # lines two fine pixels wide: one pixel of the picture
        strength[:-1] = np.maximum(strength[:-1], strength[1:])
        strength[:, :-1] = np.maximum(strength[:, :-1], strength[:, 1:])
        for channel in range(3):  # in place: no picture-sized temporaries
            layer = image[..., channel]
            layer -= strength * (layer - np.float32(EDGE_COLOUR[channel]))
    if mode == "wire":
        _draw_edges(picture, screen, z, image, None, big_w, big_h, _outline_edges(picture, normals))
    out = np.empty((height, width, 3), np.uint8)
    for channel in range(3):
        layer = image[..., channel].reshape(height, k, width, k).mean(axis=(1, 3))
        out[..., channel] = np.clip(np.rint(layer * 255), 0, 255)
    return out


def _corner_normals(picture: StreamFrame, tris: np.ndarray, polygon: np.ndarray,
                    surfaces: np.ndarray) -> np.ndarray | None:
    """(T, 3, 3) unit normals at the corners of the triangles, of the facets of
    curved surfaces (as castor.pictures.mesh_rays.corner_normals, from the
    triangles of the same surface around each vertex), each polygon's own
    normal on the others; None when no surface has two facets."""
    from castor.pictures.mesh_rays import corner_normals

    facets = np.bincount(surfaces, minlength=len(surfaces))
    if not (facets >= 2).any():
        return None
    vertex = _vertex_numbers(picture)[tris]
    p = picture.points[tris]
    area_normals = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    # a polygon alone on its surface: a group of its own (its normal everywhere)
    group = np.where(facets[surfaces] >= 2, surfaces, len(surfaces) + np.arange(len(surfaces)))
    return corner_normals(picture.points, vertex, area_normals, group[polygon])


def _shade_smoothly(image, hit, triangle, polygon, tris, corners, back, screen, z,
                    picture: StreamFrame, camera: Camera) -> None:
    """The pixels ``hit`` (of the triangles ``triangle``) of curved surfaces lit
    with the normal interpolated at each from the corners of its triangle, in
    the scene (perspective-correct), turned as its polygon was to the viewer."""
    corner_turn = np.abs(np.einsum("tij,tkj->tik", corners, corners)).min(axis=(1, 2))
    curved = corner_turn[triangle] < 1 - 1e-9  # the corners' normals differ: not flat
    hit, triangle = hit[curved], triangle[curved]
    width = camera.width
    for start in range(0, len(hit), _BATCH_PIXELS):  # bounded memory
        pixel, t = hit[start:start + _BATCH_PIXELS], triangle[start:start + _BATCH_PIXELS]
        centre = np.column_stack([pixel % width, pixel // width]) + 0.5
        weights = _screen_weights(centre, screen[tris[t]], z[tris[t]], camera.orthographic)
        normals = np.einsum("ij,ijk->ik", weights, corners[t])
        normals /= np.maximum(np.linalg.norm(normals, axis=1), 1e-300)[:, None]
        p = polygon[t]
        normals[back[p]] *= -1
        image[pixel] = _lit(picture.colours[p], normals, camera)


def _screen_weights(centre: np.ndarray, corners: np.ndarray, z: np.ndarray,
                    orthographic: bool) -> np.ndarray:
    """(n, 3) weights of a triangle's corners at points of the screen inside it
    (corners (n, 3, 2), their depths z (n, 3)), for a value that varies linearly
    in the scene: the screen's barycentric weights, over z in perspective."""
    a, b, c = corners[:, 0], corners[:, 1], corners[:, 2]
    e1, e2, e = b - a, c - a, centre - a
    det = e1[:, 0] * e2[:, 1] - e2[:, 0] * e1[:, 1]
    det = np.where(np.abs(det) > 0, det, 1.0)
    v = (e[:, 0] * e2[:, 1] - e2[:, 0] * e[:, 1]) / det
    w = (e1[:, 0] * e[:, 1] - e[:, 0] * e1[:, 1]) / det
    weights = np.clip(np.column_stack([1 - v - w, v, w]), 0, None)
    if not orthographic:
        weights = weights / z
    total = weights.sum(axis=1, keepdims=True)
    return np.where(total > 0, weights / np.where(total > 0, total, 1), 1 / 3)


def _outline_edges(picture: StreamFrame, normals: np.ndarray) -> np.ndarray:
    """For each polygon edge (point i to the next), whether it is drawn: not
    when the polygon across it lies in the same plane."""
    count = len(picture.points)
    if count == 0:
        return np.zeros(0, bool)
    first, second, polygon, _ends = _shared_edges(picture)
    turn = np.einsum("ij,ij->i", normals[polygon[first]], normals[polygon[second]])
    flat = np.abs(turn) > 1 - 1e-9
    draw = np.ones(count, bool)
    draw[first[flat]] = False
    draw[second[flat]] = False
    return draw


def _surfaces(picture: StreamFrame, normals: np.ndarray) -> np.ndarray:
    """Each polygon's surface number: neighbouring polygons that are facets of
    one curved surface of one primitive share one. The stream gives each
    polygon's path, not its surface: castor.mesh.creases guesses it from the
    path's kind and the turn between the polygons."""
    count = picture.polygon_count
    label = np.arange(count)
    if len(picture.points) == 0:
        return label
    first, second, polygon, ends = _shared_edges(picture)
    p, q = polygon[first], polygon[second]
    if picture.path_of is not None:
        origin = picture.path_of
        curved = curved_kinds([path.rpartition("!")[2] for path in picture.paths])
        curved |= _smooth_paths(origin[p], origin[q], ends, normals[p], normals[q],
                                len(picture.paths))
        curved |= _unmerged_paths(picture, first, second, normals, len(picture.paths))
    else:  # a mesh file: no paths
        origin = np.zeros(count, np.int64)
        curved = np.ones(1, bool)
    cosine = np.einsum("ij,ij->i", normals[p], normals[q])
    smooth = guessed_same_surface(origin[p] == origin[q], curved[origin[p]], cosine)
    p, q = p[smooth], q[smooth]
    while len(p):  # each facet takes the lowest number of its surface
        lowest = np.minimum(label[p], label[q])
        new = label.copy()
        np.minimum.at(new, p, lowest)
        np.minimum.at(new, q, lowest)
        new = new[new]
        if np.array_equal(new, label):
            break
        label = new
    return label


def _smooth_paths(path_a, path_b, ends, normal_a, normal_b, count: int) -> np.ndarray:
    """For each path, whether its polygons are the facets of a smooth solid
    (``@s``, LANGUAGE.md §7.1), whose path ends in the kind of a flat
    primitive: at a vertex of a flat primitive at most three of the edges
    between its own faces turn (a corner of a cube, a prism or an extrusion;
    the pieces of one face meet flat), save the apex of a pyramid; on a
    smooth solid four or more turn at nearly every vertex. A path with
    ``SMOOTH_CORNERS`` such vertices is taken for a smooth solid (a frame
    may hold a few pyramids of one path; a smooth solid has hundreds). ``path_a``, ``path_b``,
    ``ends`` (vertex numbers) and the normals are those of the shared edges."""
    same = (path_a == path_b) & (np.einsum("ij,ij->i", normal_a, normal_b) < 1 - COPLANAR)
    if not same.any():
        return np.zeros(count, bool)
    path = np.repeat(path_a[same], 2)
    vertex = ends[same].ravel()
    pairs, turning = np.unique(path * (int(vertex.max()) + 1) + vertex, return_counts=True)
    corners = pairs[turning >= 4] // (int(vertex.max()) + 1)
    return np.bincount(corners, minlength=count)[:count] >= SMOOTH_CORNERS


def _unmerged_paths(picture: StreamFrame, first, second, normals, count: int) -> np.ndarray:
    """For each path, whether it holds ``SMOOTH_CORNERS`` pairs of neighbouring
    polygons that lie in one plane, have one colour and would make a convex
    polygon together: castor merges the pieces of a flat face while the
    result stays convex (castor.mesh.merge), never the facets of a curved
    surface, so such pairs are the facets of a smooth solid curved one way
    only (the side of a smoothed prism between its creases), which
    ``_smooth_paths`` cannot tell from a prism of many sides. ``first`` and
    ``second`` start the shared edges in their two polygons."""
    polygon = np.repeat(np.arange(picture.polygon_count), np.diff(picture.offsets))
    p, q = polygon[first], polygon[second]
    path = picture.path_of
    flat = np.einsum("ij,ij->i", normals[p], normals[q]) >= 1 - COPLANAR
    keep = flat & (path[p] == path[q]) & np.all(picture.colours[p] == picture.colours[q], axis=1)
    if not keep.any():
        return np.zeros(count, bool)
    first, second, p = first[keep], second[keep], p[keep]
    offsets = picture.offsets
    nxt = np.arange(len(picture.points)) + 1
    nxt[offsets[1:] - 1] = offsets[:-1]
    before = np.empty_like(nxt)
    before[nxt] = np.arange(len(nxt))
    pts, normal = picture.points, normals[p]
    scale = np.linalg.norm(pts[nxt[first]] - pts[first], axis=1)

    def convex(a, corner, b):  # the turn at ``corner`` from a to b, clearly convex
        turn = np.einsum("ij,ij->i", np.cross(pts[corner] - pts[a], pts[b] - pts[corner]), normal)
        return turn > 1e-6 * scale ** 2

    # in the union, the first polygon's edge a -> b is gone: before a comes
    # its own point before a, after a the second polygon's point after a;
    # before b the second polygon's point before b, after b the first's after b
    a, b = first, nxt[first]
    union = convex(before[a], a, nxt[nxt[second]]) & convex(before[second], b, nxt[b])
    return np.bincount(path[p][union], minlength=count)[:count] >= SMOOTH_CORNERS


def _shared_edges(picture: StreamFrame):
    """The edges two polygons share: for each, the point that starts it in
    one polygon and in the other, every point's polygon, and the edges' two
    vertices (points numbered once for all the polygons they are in)."""
    count = len(picture.points)
    vertex = _vertex_numbers(picture)
    offsets = picture.offsets
    nxt = np.arange(count) + 1
    nxt[offsets[1:] - 1] = offsets[:-1]
    a, b = vertex, vertex[nxt]
    key = np.minimum(a, b) * (int(vertex.max()) + 1) + np.maximum(a, b)
    polygon = np.repeat(np.arange(picture.polygon_count), np.diff(offsets))
    order = np.argsort(key, kind="stable")
    sorted_key = key[order]
    pair = np.flatnonzero(sorted_key[1:] == sorted_key[:-1])
    single = np.ones(len(pair), bool)  # exactly two polygons share the edge
    single[1:] &= pair[1:] != pair[:-1] + 1
    single[:-1] &= pair[:-1] + 1 != pair[1:]
    pair = pair[single]
    first = order[pair]
    return first, order[pair + 1], polygon, np.column_stack([a[first], b[first]])


def _vertex_numbers(picture: StreamFrame) -> np.ndarray:
    """For each point of each polygon, a number for its place: equal for the
    points where polygons meet (to 1e-9 of the picture's size)."""
    scale = max(float(np.abs(picture.points).max()), 1.0) * 1e-9
    quantized = np.round(picture.points / scale).astype(np.int64)
    _, vertex = np.unique(quantized, axis=0, return_inverse=True)
    return vertex.ravel()


def _rasterize(screen, z, tris, polygon, width, height, depth, owner, orthographic=False):
    """Each triangle row by row: the pixels whose centres it covers, in batches
    of fragments; the nearest wins each pixel. The work goes with the area
    covered, not with the triangles' bounding boxes."""
    if len(tris) == 0:
        return
    p = screen[tris]  # (T, 3, 2)
    # depth, affine on the screen: 1/z in perspective, z itself in an orthographic view
    w = z[tris] if orthographic else 1.0 / z[tris]
    x0, y0 = p[:, 0, 0], p[:, 0, 1]
    ex1, ey1 = p[:, 1, 0] - x0, p[:, 1, 1] - y0
    ex2, ey2 = p[:, 2, 0] - x0, p[:, 2, 1] - y0
    det = ex1 * ey2 - ex2 * ey1
    keep = np.abs(det) > 1e-12
    tris, polygon, p, w = tris[keep], polygon[keep], p[keep], w[keep]
    x0, y0, ex1, ey1, ex2, ey2, det = (v[keep] for v in (x0, y0, ex1, ey1, ex2, ey2, det))
    dw1, dw2 = w[:, 1] - w[:, 0], w[:, 2] - w[:, 0]
    gx = (dw1 * ey2 - dw2 * ey1) / det  # d(w)/dx
    gy = (dw2 * ex1 - dw1 * ex2) / det  # d(w)/dy
    g0 = w[:, 0] - gx * x0 - gy * y0
    ys = p[:, :, 1]
    row0 = np.clip(np.ceil(ys.min(axis=1) - 0.5), 0, height).astype(np.int64)
    row1 = np.clip(np.floor(ys.max(axis=1) - 0.5), -1, height - 1).astype(np.int64)
    rows = np.maximum(row1 - row0 + 1, 0)
    xs = p[:, :, 0]
    across = np.clip(np.ceil(xs.max(axis=1)) - np.floor(xs.min(axis=1)) + 1, 1, width)
    ends = np.cumsum(rows * across)  # at most this many fragments: batches of bounded memory
    start = 0
    while start < len(tris):
        base = ends[start - 1] if start else 0
        stop = int(np.searchsorted(ends, base + _BATCH_PIXELS, side="right"))
        stop = max(stop, start + 1)
        _rows(np.arange(start, stop), p, rows, row0, gx, gy, g0, polygon, width, depth, owner,
              orthographic)
        start = stop


def _rows(batch, p, rows, row0, gx, gy, g0, polygon, width, depth, owner, orthographic):
    counts = rows[batch]
    tri = np.repeat(batch, counts)
    if len(tri) == 0:
        return
    row = row0[tri] + np.arange(len(tri)) - np.repeat(np.cumsum(counts) - counts, counts)
    cy = row + 0.5
    left = np.full(len(tri), np.inf)
    right = np.full(len(tri), -np.inf)
    for i, j in ((0, 1), (1, 2), (2, 0)):
        ax, ay = p[tri, i, 0], p[tri, i, 1]
        bx, by = p[tri, j, 0], p[tri, j, 1]
        crosses = (np.minimum(ay, by) <= cy) & (cy <= np.maximum(ay, by)) & (ay != by)
        with np.errstate(divide="ignore", invalid="ignore"):
            x = ax + (cy - ay) * (bx - ax) / (by - ay)
        left = np.where(crosses, np.minimum(left, x), left)
        right = np.where(crosses, np.maximum(right, x), right)
    col0 = np.clip(np.ceil(left - 0.5), 0, width).astype(np.int64)
    col1 = np.clip(np.floor(right - 0.5), -1, width - 1).astype(np.int64)
    spans = np.maximum(col1 - col0 + 1, 0)
    spans[~np.isfinite(left)] = 0
    total = int(spans.sum())
    if total == 0:
        return
    piece = np.repeat(np.arange(len(tri)), spans)
    px = col0[piece] + np.arange(total) - np.repeat(np.cumsum(spans) - spans, spans)
    py = row[piece]
    t = tri[piece]
    w = gx[t] * (px + 0.5) + gy[t] * (py + 0.5) + g0[t]
    d = w if orthographic else 1.0 / w
    pixel = py * width + px
    np.minimum.at(depth, pixel, d)
    win = d <= depth[pixel]
    owner[pixel[win]] = polygon[t[win]]


def _draw_edges(picture, screen, z, image, depth, width, height, drawn=None):
    """Polygon outlines (those ``drawn``), two pixels wide; with a depth
    buffer, only where the surface is visible."""
    pts = picture.offsets
    count = len(picture.points)
    if count == 0:
        return
    nxt = np.arange(count) + 1
    nxt[pts[1:] - 1] = pts[:-1]
    start, end = np.arange(count), nxt
    keep = (z[start] > 1e-6) & (z[end] > 1e-6)
    if drawn is not None:
        keep &= drawn
    start, end = start[keep], end[keep]
    lengths = np.ceil(np.linalg.norm(screen[end] - screen[start], axis=1)).astype(np.int64) + 1
    lengths = np.minimum(lengths, 4 * (width + height))
    edge = np.repeat(np.arange(len(start)), lengths)
    t = (np.arange(int(lengths.sum())) - np.repeat(np.cumsum(lengths) - lengths, lengths)) \
        / np.maximum(np.repeat(lengths, lengths) - 1, 1)
    s0, s1 = start[edge], end[edge]
    xy = screen[s0] * (1 - t)[:, None] + screen[s1] * t[:, None]
    px, py = np.floor(xy[:, 0] - 0.5).astype(np.int64), np.floor(xy[:, 1] - 0.5).astype(np.int64)
    px, py = np.concatenate([px, px + 1, px, px + 1]), np.concatenate([py, py, py + 1, py + 1])
    d = np.tile(1.0 / ((1 - t) / z[s0] + t / z[s1]), 4)
    ok = (px >= 0) & (px < width) & (py >= 0) & (py < height)
    px, py, d = px[ok], py[ok], d[ok]
    if depth is not None:
        # near the visible surface: allow for the depth's own interpolation error
        pixel = py * width + px
        ok = d <= depth[pixel] * (1 + 2e-3) + 1e-9
        px, py = px[ok], py[ok]
    image[py, px] = EDGE_COLOUR

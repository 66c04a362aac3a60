"""Regularity (LANGUAGE.md §7) judged on the stream alone: every polygon
planar, convex, of positive area, winding once; no shell of zero volume; no
sheet (a polygon with the same side on both faces)."""

from __future__ import annotations

import numpy as np

from .stream import Frame, Polygon, newell
from .winding import winding_numbers


def polygon_defects(polygon: Polygon, slack: float = 1e-7) -> list[str]:
    """What is wrong with one polygon: too few vertices, a repeated vertex,
    zero area, not planar, not convex, or winding more than once."""
    pts = polygon.points
    n = len(pts)
    if n < 3:
        return ["fewer than 3 vertices"]
    defects = []
    rounded = [tuple(p) for p in pts.tolist()]
    if len(set(rounded)) != n:
        defects.append("a repeated vertex")
    size = max(float(np.ptp(pts, axis=0).max()), 1e-300)
    normal = newell(pts)
    length = float(np.linalg.norm(normal))
    if length <= 1e-12 * size * size:
        return defects + ["zero area"]
    normal /= length
    if np.abs((pts - pts.mean(axis=0)) @ normal).max() > slack * max(size, 1.0):
        defects.append("not planar")
    edges = np.roll(pts, -1, axis=0) - pts
    following = np.roll(edges, -1, axis=0)
    turns = np.cross(edges, following) @ normal
    lengths = np.linalg.norm(edges, axis=1) * np.linalg.norm(following, axis=1)
    if np.any(turns < -slack * lengths):
        defects.append("not convex")
    # the exterior angles of a simple convex polygon add up to one turn
    u = edges - np.outer(edges @ normal, normal)
    angle = np.arctan2(np.cross(u, np.roll(u, -1, axis=0)) @ normal,
                       np.einsum("ij,ij->i", u, np.roll(u, -1, axis=0)))
    if abs(angle.sum() - 2 * np.pi) > 1e-6:
        defects.append(f"winds {angle.sum() / (2 * np.pi):.2f} times")
    return defects


def frame_polygon_defects(frame: Frame, slack: float = 1e-7) -> list[tuple[int, list[str]]]:
    """``polygon_defects`` of every polygon of a frame, the same tests made
    on all the polygons' arrays at once (a smooth frame has tens of
    thousands): (polygon number, its defects) where it has any."""
    if not frame.polygons:
        return []
    corners, starts = _polygon_arrays(frame)
    sizes = np.diff(starts)
    out: dict[int, list[str]] = {}
    few = np.flatnonzero(sizes < 3)
    for i in few.tolist():
        out[i] = ["fewer than 3 vertices"]
    polygon = np.repeat(np.arange(len(sizes)), sizes)
    # a repeated vertex: two corners of one polygon at the same exact position
    key = np.lexsort((corners[:, 2], corners[:, 1], corners[:, 0], polygon))
    same = ((polygon[key][1:] == polygon[key][:-1])
            & (corners[key][1:] == corners[key][:-1]).all(axis=1))
    repeated = np.zeros(len(sizes), bool)
    repeated[polygon[key][1:][same]] = True
    following = np.arange(len(corners)) + 1
    following[starts[1:] - 1] = starts[:-1]
    after = following[following]
    low = np.minimum.reduceat(corners, starts[:-1], axis=0)
    high = np.maximum.reduceat(corners, starts[:-1], axis=0)
    size = np.maximum((high - low).max(axis=1), 1e-300)
    centre = np.add.reduceat(corners, starts[:-1], axis=0) / sizes[:, None]
    about = corners - centre[polygon]  # Newell's normal about the centre, as newell
    normal = np.zeros((len(sizes), 3))
    np.add.at(normal, polygon, np.cross(about, about[following]))
    length = np.linalg.norm(normal, axis=1)
    flat = length <= 1e-12 * size * size
    unit = normal / np.where(flat, 1.0, length)[:, None]
    n = unit[polygon]
    away = np.abs(np.einsum("ij,ij->i", corners - centre[polygon], n))
    not_planar = np.maximum.reduceat(away, starts[:-1]) > slack * np.maximum(size, 1.0)
    edges = corners[following] - corners
    next_edges = corners[after] - corners[following]
    turns = np.einsum("ij,ij->i", np.cross(edges, next_edges), n)
    lengths = np.linalg.norm(edges, axis=1) * np.linalg.norm(next_edges, axis=1)
    concave = np.zeros(len(sizes), bool)
    concave[polygon[turns < -slack * lengths]] = True
    u = edges - np.einsum("ij,ij->i", edges, n)[:, None] * n
    u_next = u[following]
    angle = np.arctan2(np.einsum("ij,ij->i", np.cross(u, u_next), n),
                       np.einsum("ij,ij->i", u, u_next))
    total = np.add.reduceat(angle, starts[:-1])
    winds = np.abs(total - 2 * np.pi) > 1e-6
    for i in np.flatnonzero(repeated | flat | not_planar | concave | winds).tolist():
        if sizes[i] < 3:
            continue
        defects = ["a repeated vertex"] if repeated[i] else []
        if flat[i]:
            out[i] = defects + ["zero area"]
            continue
        if not_planar[i]:
            defects.append("not planar")
        if concave[i]:
            defects.append("not convex")
        if winds[i]:
            defects.append(f"winds {total[i] / (2 * np.pi):.2f} times")
        out[i] = defects
    return sorted(out.items())


def shells(frame: Frame) -> list[list[int]]:
    """The polygons of each connected shell (polygons sharing a vertex position)."""
    parent = {}

    def find(k):
        while parent.setdefault(k, k) != k:
            parent[k] = parent[parent[k]]
            k = parent[k]
        return k

    for i, p in enumerate(frame.polygons):
        for v in p.points.tolist():
            parent[find(("v", tuple(v)))] = find(("p", i))
    groups: dict = {}
    for i in range(len(frame.polygons)):
        groups.setdefault(find(("p", i)), []).append(i)
    return list(groups.values())


def shell_defects(frame: Frame, thickness: float = 1e-9) -> list[str]:
    """Shells of (about) zero volume: their volume over half their area, a mean
    thickness, is below ``thickness`` times the frame's size. (The shells
    as ``shells`` finds them, polygons sharing a vertex position, found on
    the frame's arrays at once.)"""
    if not frame.polygons:
        return []
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    size = max(float(np.abs(frame.box()).max()), 1.0)
    corners, starts = _polygon_arrays(frame)
    sizes = np.diff(starts)
    count = len(sizes)
    polygon = np.repeat(np.arange(count), sizes)
    _, vertex = np.unique(corners, axis=0, return_inverse=True)
    vertex = vertex.ravel()
    nodes = count + int(vertex.max()) + 1
    graph = coo_matrix((np.ones(len(polygon)), (polygon, count + vertex)), shape=(nodes, nodes))
    _, label = connected_components(graph, directed=False)
    label = label[:count]
    following = np.arange(len(corners)) + 1
    following[starts[1:] - 1] = starts[:-1]
    normal = np.zeros((count, 3))
    np.add.at(normal, polygon, np.cross(corners, corners[following]))
    area = np.linalg.norm(normal, axis=1) / 2
    # each polygon's fan from its first corner: a . (b x c) / 6 per triangle
    fans = np.maximum(sizes - 2, 0)
    owner = np.repeat(np.arange(count), fans)
    k = np.arange(len(owner)) - np.repeat(np.cumsum(fans) - fans, fans)
    first = starts[owner]
    cone = np.einsum("ij,ij->i", corners[first],
                     np.cross(corners[first + k + 1], corners[first + k + 2])) / 6
    volume = np.bincount(label[owner], weights=cone, minlength=label.max() + 1)
    shell_area = np.bincount(label, weights=area, minlength=label.max() + 1)
    members = np.bincount(label, minlength=label.max() + 1)
    defects = []
    for s in np.flatnonzero(np.abs(volume) <= thickness * size * shell_area / 2).tolist():
        defects.append(f"a shell of {members[s]} polygons has volume {volume[s]:.3g} "
                       f"for area {shell_area[s]:.3g}")
    return defects


def _polygon_arrays(frame: Frame):
    """All the frame's corners (C, 3), where each polygon's start (P + 1,)."""
    sizes = np.array([len(p.points) for p in frame.polygons], dtype=np.int64)
    corners = np.concatenate([np.asarray(p.points, dtype=np.float64).reshape(-1, 3)
                              for p in frame.polygons])
    return corners, np.concatenate([[0], np.cumsum(sizes)])


def _fan_arrays(frame: Frame) -> np.ndarray:
    """The polygons as fans of triangles from their first corners, (T, 3, 3)."""
    corners, starts = _polygon_arrays(frame)
    sizes = np.diff(starts)
    owner = np.repeat(np.arange(len(sizes)), np.maximum(sizes - 2, 0))
    k = np.arange(len(owner)) - np.repeat(np.cumsum(np.maximum(sizes - 2, 0))
                                          - np.maximum(sizes - 2, 0), np.maximum(sizes - 2, 0))
    first = starts[owner]
    return np.stack([corners[first], corners[first + k + 1], corners[first + k + 2]], axis=1)


def sheet_defects(frame: Frame, offset: float = 1e-8) -> list[str]:
    """Polygons that do not part inside from outside: just behind each polygon
    (at a point inside it) the winding number must be 1, just in front 0. A
    sheet of two coincident faces, or a face folded back on itself, fails."""
    if not frame.polygons:
        return []
    triangles = _fan_arrays(frame)
    size = max(float(np.abs(frame.box()).max()), 1.0)
    corners, starts = _polygon_arrays(frame)
    sizes = np.diff(starts)
    polygon = np.repeat(np.arange(len(sizes)), sizes)
    following = np.arange(len(corners)) + 1
    following[starts[1:] - 1] = starts[:-1]
    centres = np.add.reduceat(corners, starts[:-1], axis=0) / sizes[:, None]
    about = corners - centres[polygon]  # Newell's normal about the centre: about
    normal = np.zeros((len(sizes), 3))  # the origin, rounding tilts a thin one
    np.add.at(normal, polygon, np.cross(about, about[following]))
    length = np.linalg.norm(normal, axis=1)
    # a needle narrower than the offset (a strip 1.4e-9 wide along an edge of
    # the solid, which the engine's rounding leaves) has no point that far
    # behind it that is not past the edge: the test cannot see it
    extent = (np.maximum.reduceat(corners, starts[:-1], axis=0)
              - np.minimum.reduceat(corners, starts[:-1], axis=0)).max(axis=1)
    kept = np.flatnonzero((length > 0) & (length / 2 >= offset * size * extent))
    normal = normal[kept] / length[kept, None]
    centre = centres[kept]
    # four points well inside the (convex) polygon, none on a line through
    # its centre and a corner: solids that touch along a line (which is no
    # sheet) often touch along a diagonal, and one point may lie on it
    k = np.arange(4)
    first = corners[starts[kept][:, None] + k % sizes[kept][:, None]]
    second = corners[starts[kept][:, None] + (k + 1) % sizes[kept][:, None]]
    inner = 0.47 * first + 0.31 * second + 0.22 * centre[:, None]
    step = (offset * size * normal)[:, None]
    points = np.stack([inner - step, inner + step], axis=2).reshape(-1, 3)
    names = [frame.polygons[i].path for i in kept.tolist()]
    w = winding_numbers(triangles, points).reshape(-1, 4, 2)
    wrong = (np.abs(w[:, :, 0] - 1) > 0.01) | (np.abs(w[:, :, 1]) > 0.01)
    bad = np.flatnonzero(wrong.sum(axis=1) >= 2)
    return [f"polygon {kept[i]} of {names[i]} has winding {w[i, 0, 0]:.3f} behind and "
            f"{w[i, 0, 1]:.3f} in front" for i in bad.tolist()]


def regularity_defects(frame: Frame, sheets: bool = True) -> list[str]:
    """Every defect LANGUAGE.md §7 rules out, as readable lines (empty if none)."""
    defects = [f"polygon {i} of {frame.polygons[i].path}: {', '.join(d)}"
               for i, d in frame_polygon_defects(frame)]
    defects += shell_defects(frame)
    if sheets:
        defects += sheet_defects(frame)
    return defects

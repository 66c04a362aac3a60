"""Read castor's polygon stream back and check the geometry a test needs.

Kept independent of castor's own modules, so that the tests judge the output
as any other program reading the stream would.
"""

from __future__ import annotations

import math
import subprocess
import sys
import tempfile
from collections import Counter
from dataclasses import dataclass, field

import numpy as np


@dataclass
class Polygon:
    path: str
    colour: tuple[float, float, float]
    points: np.ndarray  # (n, 3)


@dataclass
class Frame:
    number: int
    where: str
    polygons: list[Polygon] = field(default_factory=list)

    def volume(self) -> float:
        return sum(_fan_volume(p.points) for p in self.polygons)

    def box(self) -> np.ndarray:
        pts = np.concatenate([p.points for p in self.polygons])
        return np.array([pts.min(axis=0), pts.max(axis=0)])

    def area(self, colour=None, path_part=None) -> float:
        total = 0.0
        for p in self.polygons:
            if colour is not None and p.colour != tuple(colour):
                continue
            if path_part is not None and path_part not in p.path:
                continue
            total += np.linalg.norm(_newell(p.points)) / 2
        return total

    def colours(self) -> set:
        return {p.colour for p in self.polygons}

    def paths(self) -> set:
        return {p.path for p in self.polygons}


def parse_stream(text: str) -> list[Frame]:
    lines = text.splitlines()
    assert lines and lines[0] == "castor-polygons 1", "missing header"
    frames: list[Frame] = []
    current = None
    for line in lines[1:]:
        fields = line.split(" ")
        if fields[0] == "frame":
            assert current is None, "frame inside a frame"
            current = Frame(int(fields[1]), fields[2])
        elif fields[0] == "poly":
            path = fields[1]
            colour = tuple(float(x) for x in fields[2:5])
            n = int(fields[5])
            coords = [float(x) for x in fields[6:]]
            assert len(coords) == 3 * n, f"vertex count mismatch in {line[:80]}"
            current.polygons.append(Polygon(path, colour, np.array(coords).reshape(n, 3)))
        elif fields[0] == "endframe":
            assert int(fields[1]) == current.number
            assert int(fields[2]) == len(current.polygons), "endframe count mismatch"
            frames.append(current)
            current = None
        else:
            raise AssertionError(f"unknown record: {line[:80]}")
    assert current is None, "frame not ended"
    return frames


def _newell(points: np.ndarray) -> np.ndarray:
    """Twice the polygon's vector area (Newell), taken about its centre: about
    the origin, the rounding of coordinates of 2 swamps the normal of a
    triangle 2e-4 long and 1e-10 high, and a planar one read as tilted."""
    points = points - points.mean(axis=0)
    nxt = np.roll(points, -1, axis=0)
    return np.cross(points, nxt).sum(axis=0)


def _fan_volume(points: np.ndarray) -> float:
    a = points[0]
    total = 0.0
    for i in range(1, len(points) - 1):
        total += float(np.dot(a, np.cross(points[i], points[i + 1]))) / 6
    return total


def check_closed(frame: Frame) -> None:
    """Every directed edge is matched by exactly one opposite edge (by exact position)."""
    edges = Counter()
    for p in frame.polygons:
        pts = [tuple(v) for v in p.points.tolist()]
        for i in range(len(pts)):
            edges[(pts[i], pts[(i + 1) % len(pts)])] += 1
    for (a, b), count in edges.items():
        assert count == 1, f"edge {a}->{b} used {count} times"
        assert edges.get((b, a)) == 1, f"edge {a}->{b} has no opposite edge"


def check_convex_planar(frame: Frame, slack: float = 1e-7) -> None:
    for p in frame.polygons:
        pts = p.points
        assert len(pts) >= 3
        normal = _newell(pts)
        length = np.linalg.norm(normal)
        assert length > 0, f"degenerate polygon {p.path}"
        normal /= length
        size = np.ptp(pts, axis=0).max()
        distance = (pts - pts.mean(axis=0)) @ normal
        assert np.abs(distance).max() <= slack * max(size, 1.0), f"non-planar polygon {p.path}"
        edges = np.roll(pts, -1, axis=0) - pts
        turns = np.cross(edges, np.roll(edges, -1, axis=0)) @ normal
        scale = np.linalg.norm(edges, axis=1) * np.linalg.norm(np.roll(edges, -1, axis=0), axis=1)
        assert np.all(turns >= -slack * scale), f"non-convex polygon {p.path}"


def check_solid(frame: Frame) -> None:
    check_closed(frame)
    check_convex_planar(frame)
    if frame.polygons:
        assert frame.volume() > 0, "surface is not outward oriented"


def write(tmp_path, name, text):
    """Write a test's file (its folders made as needed); its path."""
    path = tmp_path / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)
    return path


def hear_ctrl_c() -> None:
    """For ``preexec_fn``: the castor a test starts hears Ctrl-C (SIGINT) even when
    the tests themselves were started as a background job of a shell, which
    starts them with SIGINT ignored and would pass that on to castor."""
    import signal

    signal.signal(signal.SIGINT, signal.SIG_DFL)


def run(*args, stdin: str | None = None, cwd=None, check_status=None):
    """Run castor; returns (status, stdout, stderr)."""
    # run outside the source tree, so that the installed package is what runs
    result = subprocess.run([sys.executable, "-m", "castor", *args], input=stdin,
                            capture_output=True, text=True, cwd=cwd or tempfile.gettempdir(),
                            timeout=600)
    assert "Traceback" not in result.stderr, result.stderr
    if check_status is not None:
        assert result.returncode == check_status, result.stderr
    return result.returncode, result.stdout, result.stderr


def frames_of(scene: str, *args) -> list[Frame]:
    """Facetize a scene given as text; fails on any error message. castor's
    command line runs in this process (what it writes is read back as from a
    pipe): the tests make hundreds of scenes, and each process start costs more
    than most of them; the process as a whole is tested through ``run``."""
    status, out, err = run_here("--no-cpp", *args, stdin=scene)
    assert status == 0, err
    return parse_stream(out)


def run_here(*args, stdin: str = ""):
    """castor's command line in this process: (status, stdout, stderr)."""
    import io

    from castor.cli import main

    saved = sys.stdin, sys.stdout, sys.stderr
    sys.stdin, sys.stdout, sys.stderr = io.StringIO(stdin), io.StringIO(), io.StringIO()
    try:
        status = main(list(args))
    except SystemExit as exc:  # usage errors exit through argparse
        status = exc.code
    finally:
        out, err = sys.stdout.getvalue(), sys.stderr.getvalue()
        sys.stdin, sys.stdout, sys.stderr = saved
    assert "Traceback" not in err, err
    return status, out, err


# --- regularity (LANGUAGE.md §7): judged on the stream alone ---------------

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
    normal = _newell(pts)
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
    about = corners - centre[polygon]  # Newell's normal about the centre, as _newell
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


def winding_numbers(triangles: np.ndarray, points: np.ndarray) -> np.ndarray:
    """The generalized winding number of a triangle surface at each point.

    On a closed surface (every directed edge, by exact positions, used as
    often the other way) it is an integer, the signed number of times a ray
    from the point crosses the surface (Jacobson et al. 2013, §3): that count
    is made here along one ray direction for all points, the triangles found
    through a grid, so that thousands of points against tens of thousands of
    triangles take a moment rather than minutes. An open surface's (fractional)
    number is the sum of the triangles' solid angles (Van Oosterom and
    Strackee), point by triangle."""
    triangles = np.asarray(triangles, dtype=np.float64).reshape(-1, 3, 3)
    points = np.asarray(points, dtype=np.float64).reshape(-1, 3)
    if not len(triangles) or not len(points):
        return np.zeros(len(points))
    ids = _closed_vertex_ids(triangles)
    if ids is None:
        return _solid_angle_winding(triangles, points)
    return _crossing_winding(triangles, ids, points)


def _solid_angle_winding(triangles: np.ndarray, points: np.ndarray) -> np.ndarray:
    """Sum of the triangles' solid angles at each point, over 4 pi."""
    out = np.zeros(len(points))
    for start in range(0, len(points), 64):
        q = points[start:start + 64]
        a = triangles[None, :, 0, :] - q[:, None, :]
        b = triangles[None, :, 1, :] - q[:, None, :]
        c = triangles[None, :, 2, :] - q[:, None, :]
        la, lb, lc = (np.linalg.norm(x, axis=2) for x in (a, b, c))
        det = np.einsum("qtj,qtj->qt", a, np.cross(b, c))
        div = (la * lb * lc + np.einsum("qtj,qtj->qt", a, b) * lc
               + np.einsum("qtj,qtj->qt", b, c) * la + np.einsum("qtj,qtj->qt", c, a) * lb)
        out[start:start + 64] = np.arctan2(det, div).sum(axis=1) / (2 * np.pi)
    return out


def _closed_vertex_ids(triangles: np.ndarray) -> np.ndarray | None:
    """Each corner's vertex number (one per exact position), if the surface is
    closed: every directed edge used as often as its reverse; else None."""
    flat = triangles.reshape(-1, 3)
    _, ids = np.unique(flat, axis=0, return_inverse=True)
    ids = ids.reshape(-1, 3)
    start = ids.ravel()
    end = ids[:, [1, 2, 0]].ravel()
    n = int(ids.max()) + 1
    forward = np.sort(start * n + end)
    backward = np.sort(end * n + start)
    return ids if np.array_equal(forward, backward) else None


# a fixed rotation in no special direction: rays along its third axis run
# along no edge or face a scene's grid and right angles make
_RAY_FRAME = None


def _ray_frame() -> np.ndarray:
    global _RAY_FRAME
    if _RAY_FRAME is None:
        a, b, c = 0.6180339887, 1.2247448714, 0.4142135624
        rx = np.array([[1, 0, 0], [0, math.cos(a), -math.sin(a)], [0, math.sin(a), math.cos(a)]])
        ry = np.array([[math.cos(b), 0, math.sin(b)], [0, 1, 0], [-math.sin(b), 0, math.cos(b)]])
        rz = np.array([[math.cos(c), -math.sin(c), 0], [math.sin(c), math.cos(c), 0], [0, 0, 1]])
        _RAY_FRAME = rz @ ry @ rx
    return _RAY_FRAME


def _crossing_winding(triangles: np.ndarray, ids: np.ndarray, points: np.ndarray,
                      pairs_per_chunk: int = 4_000_000) -> np.ndarray:
    """Signed crossings of a closed surface by a ray from each point (up the
    third axis of ``_ray_frame``). Each edge's side test is computed from its
    two ends in one order (the lower vertex number first) for both triangles
    on it, and a point exactly on an edge's line belongs to one side only: a
    ray through an edge is counted once, never twice or not at all."""
    frame = _ray_frame()
    t = triangles @ frame.T
    q = points @ frame.T
    x, y = t[:, :, 0], t[:, :, 1]
    area = ((x[:, 1] - x[:, 0]) * (y[:, 2] - y[:, 0]) - (x[:, 2] - x[:, 0]) * (y[:, 1] - y[:, 0]))
    turn = np.sign(area)  # +1 where the triangle faces up the ray
    keep = turn != 0
    t, ids, turn = t[keep], ids[keep], turn[keep]
    if not len(t):
        return np.zeros(len(points))
    # each side (corner k to k + 1) from its lower-numbered end
    start, end = ids, ids[:, [1, 2, 0]]
    forward = start < end  # the side runs from its lower end
    low = np.where(forward[:, :, None], t, t[:, [1, 2, 0]])
    high = np.where(forward[:, :, None], t[:, [1, 2, 0]], t)
    lx, ly = low[:, :, 0], low[:, :, 1]
    dx, dy = high[:, :, 0] - lx, high[:, :, 1] - ly
    # the side of each line (from its lower end) the triangle's inside lies on;
    # a point on the line is inside where that side is the left
    inside_sign = np.where(forward, 1.0, -1.0) * turn[:, None]
    normal = np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0])
    # the grid: about as many cells as triangles
    lo = np.minimum(t[:, :, :2].min(axis=1).min(axis=0), q[:, :2].min(axis=0))
    hi = np.maximum(t[:, :, :2].max(axis=1).max(axis=0), q[:, :2].max(axis=0))
    cells = int(min(max(math.sqrt(len(t)), 1), 512))
    step = np.maximum((hi - lo) / cells, 1e-300)

    def cell(v):
        return np.clip(((v - lo) / step).astype(np.int64), 0, cells - 1)

    first = cell(t[:, :, :2].min(axis=1))
    last = cell(t[:, :, :2].max(axis=1))
    span = last - first + 1
    per = span[:, 0] * span[:, 1]
    owner = np.repeat(np.arange(len(t)), per)
    local = np.arange(len(owner)) - np.repeat(np.cumsum(per) - per, per)
    cx = first[owner, 0] + local % span[owner, 0]
    cy = first[owner, 1] + local // span[owner, 0]
    key = cy * cells + cx
    order = np.argsort(key, kind="stable")
    owner, key = owner[order], key[order]
    bounds = np.searchsorted(key, np.arange(cells * cells + 1))
    point_cell = cell(q[:, :2])
    point_key = point_cell[:, 1] * cells + point_cell[:, 0]
    begin, count = bounds[point_key], bounds[point_key + 1] - bounds[point_key]
    out = np.zeros(len(points))
    chunk_start = 0
    while chunk_start < len(points):
        total = np.cumsum(count[chunk_start:])
        chunk_end = chunk_start + max(1, int(np.searchsorted(total, pairs_per_chunk)))
        counts = count[chunk_start:chunk_end]
        which = np.repeat(np.arange(chunk_start, chunk_end), counts)
        offset = np.arange(len(which)) - np.repeat(np.cumsum(counts) - counts, counts)
        tri = owner[np.repeat(begin[chunk_start:chunk_end], counts) + offset]
        px, py, pz = q[which, 0], q[which, 1], q[which, 2]
        inside = np.ones(len(which), bool)
        for k in range(3):
            side = dx[tri, k] * (py - ly[tri, k]) - dy[tri, k] * (px - lx[tri, k])
            wanted = inside_sign[tri, k]
            inside &= (side * wanted > 0) | ((side == 0) & (wanted > 0))
        tri, which, px, py, pz = tri[inside], which[inside], px[inside], py[inside], pz[inside]
        n = normal[tri]
        height = t[tri, 0, 2] - (n[:, 0] * (px - t[tri, 0, 0]) + n[:, 1] * (py - t[tri, 0, 1])) / n[:, 2]
        above = height > pz
        out += np.bincount(which[above], weights=turn[tri[above]], minlength=len(points))
        chunk_start = chunk_end
    return out


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

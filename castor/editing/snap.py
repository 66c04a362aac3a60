"""Snapping ("recalage") on the exact solids of a frame (CLI.md, "Editing on screen").

A ray from the camera meets the frame's solids where the ray tracer says
(castor.pictures.trace, exact: a sphere's point is on the sphere). Around
that point, the planes of the primitives whose boxes are near give every
line and point where a corner, an edge, an edge's middle or a face's centre
could be; castor.editing.solids keeps those where the evaluated solid really
has one (three faces that meet at a corner though no primitive has it, as a
wall's top under the roof; never a seam inside a union). Within 10 pixels,
the first of corner, midpoint, centre, edge, then the axes (and the
parallels and perpendiculars of the edges) from the previous point, wins;
else the face (a flat face's point on a 0.05 m grid in its plane), or with
nothing hit, the grid on the ground z = 0. A corner or an edge the ray passes
within 10 pixels of without meeting its solid (just outside an outline, over
the ground or a face behind) is found by castor.editing.beside. A typed distance puts the point
at that distance from the previous one, along the direction found.
"""

from __future__ import annotations

from typing import Callable, NamedTuple

import numpy as np

from castor.csg.paths import join
from castor.editing.beside import beside
from castor.editing.solids import Solids, distinct, edge_along, edge_middle, is_corner

RADIUS = 10.0  # pixels
GRID = 0.05  # metres
_PARALLEL = 1e-9  # |1 - |cos|| below this: parallel planes or lines
_ORDER = ("corner", "midpoint", "centre", "edge", "axis", "parallel", "perpendicular")


class Snap(NamedTuple):
    point: tuple[float, float, float]
    feature: str  # "corner", "midpoint", "centre", "edge", "axis x", ..., "face", "grid"
    source: str | None  # FILE:LINE:COL of the primitive, as written
    path: str | None  # its path in the frame (LANGUAGE.md §8)

    def as_json(self) -> dict:
        return {"point": [float(v) for v in self.point], "feature": self.feature,
                "source": self.source, "path": self.path}


class Prepared:
    """A frame made ready for snapping: compiled for rays once, its primitives'
    planes worked out as snaps come near them."""

    def __init__(self, frame, source_of: Callable):
        from castor.pictures.trace import compile_frame

        self.frame = frame
        self.solids = Solids(compile_frame(frame))
        self.source_of = source_of  # Location -> "FILE:LINE:COL" as written

    def named(self, number: int | None) -> tuple[str | None, str | None]:
        """The source and path of leaf ``number``."""
        if number is None:
            return None, None
        from castor.pictures.trace import above_text

        node, above = self.solids.traced.leaves[number].origin
        above = above_text(above)
        path = join((above, node.path)) if hasattr(node, "path") else above
        return self.source_of(node.location), path


def prepare(frame, source_of: Callable = str) -> Prepared:
    return Prepared(frame, source_of)


class _View:
    """The ray and what one pixel measures at a point."""

    def __init__(self, origin, direction, pixel: float | None, pixel_size: float | None):
        self.origin = np.asarray(origin, np.float64)
        d = np.asarray(direction, np.float64)
        self.direction = d / np.linalg.norm(d)
        self.pixel, self.pixel_size = pixel, pixel_size

    def pixels(self, points: np.ndarray) -> np.ndarray:
        """How many pixels each point is off the ray, on the screen (inf behind)."""
        points = np.asarray(points, np.float64).reshape(-1, 3)
        rel = points - self.origin
        depth = rel @ self.direction
        across = np.linalg.norm(rel - depth[:, None] * self.direction, axis=1)
        if self.pixel_size is not None:
            return across / self.pixel_size
        with np.errstate(divide="ignore", invalid="ignore"):
            out = across / (self.pixel * depth)
        return np.where(depth > 0, out, np.inf)

    def nearest_first(self, points: np.ndarray) -> np.ndarray:
        """The order of the points by their distance off the ray on the screen
        (to a tenth of a pixel), then by depth: of two points drawn at the same
        place (a plan's top and bottom corners), the one in front first."""
        points = np.asarray(points, np.float64).reshape(-1, 3)
        depth = (points - self.origin) @ self.direction
        return np.lexsort((depth, np.round(self.pixels(points), 1)))

    def metres(self, point: np.ndarray) -> float:
        """The size of a pixel at ``point``."""
        if self.pixel_size is not None:
            return self.pixel_size
        return self.pixel * max(float((point - self.origin) @ self.direction), 0.0)

    def closest_on_line(self, start: np.ndarray, direction: np.ndarray) -> np.ndarray:
        """The point of the line (start, direction) nearest the ray."""
        u = direction / np.linalg.norm(direction)
        d = self.direction
        w = start - self.origin
        b = u @ d
        denominator = 1.0 - b * b
        if denominator < 1e-12:
            return start
        s = (b * (w @ d) - (w @ u)) / denominator
        return start + s * u


def snap(prepared: Prepared, origin, direction, pixel: float | None = None,
         pixel_size: float | None = None, previous=None, distance: float | None = None
         ) -> Snap | None:
    """The snapped point of a ray; None if the ray meets nothing and the ground
    is behind the camera. ``pixel``: the angle of a pixel (radians), or
    ``pixel_size`` (metres) for an orthographic view."""
    view = _View(origin, direction, pixel, pixel_size)
    solids = prepared.solids
    previous = None if previous is None else np.asarray(previous, np.float64)
    t, face = solids.traced.first_hit(view.origin[None], view.direction[None])
    found: dict[str, list] = {}
    hit = number = plane = None
    if np.isfinite(t[0]):
        hit = view.origin + t[0] * view.direction
        number = int(face[0] >> 32)
        plane = _features(solids, view, hit, number, int(face[0]), found)
    if not found.get("corner"):  # beside the outline: the ground or a face behind is hit
        beside(solids, view, RADIUS, found)
    if previous is not None:
        _inferences(solids, view, previous, found)
    result = None
    for kind in _ORDER:
        if found.get(kind):
            points = np.array([item[0] for item in found[kind]])
            point, name, leaf = found[kind][int(view.nearest_first(points)[0])]
            result = Snap(tuple(point), name, *prepared.named(leaf))
            break
    if result is None and hit is not None:
        result = Snap(tuple(_on_grid(solids, hit, plane)), "face", *prepared.named(number))
    if result is None:
        d = view.direction
        if d[2] == 0 or -view.origin[2] / d[2] <= 0:
            return None
        ground = view.origin - view.origin[2] / d[2] * d
        point = np.round(ground / GRID) * GRID
        result = Snap((float(point[0]), float(point[1]), 0.0), "grid", None, None)
    if distance is not None and previous is not None:
        way = np.asarray(result.point) - previous
        length = np.linalg.norm(way)
        if length > 0:
            result = result._replace(point=tuple(previous + way * (distance / length)))
    return result._replace(point=tuple(float(v) + 0.0 for v in result.point))


def _features(solids: Solids, view: _View, hit, number: int, face: int, found: dict):
    """Corners, midpoints, centres and edges near the hit; returns the hit
    face's plane (normal, offset) when it is flat, else None."""
    radius = RADIUS * view.metres(hit)
    whole, solids = solids, solids.around(hit, 4 * radius + 10 * solids.step)
    near = solids.near(hit, radius)
    normals, offsets, centres, owners = solids.gathered(near)
    mine = _own_plane(solids, hit, face, normals, offsets, owners == number)
    # centres of flat faces near the ray, where the solid has that face
    close = np.flatnonzero((view.pixels(centres) <= RADIUS) & _within(centres, hit, radius)) \
        if len(centres) else []
    if len(close):
        there = solids.carries(normals[close], centres[close])
        found["centre"] = [(centres[k], "centre", int(owners[k])) for k in np.asarray(close)[there]]
    if len(mine) == 0:
        return None
    f = int(mine[0])
    plane = (normals[f], offsets[f])
    keep = distinct(normals, offsets, solids.size)
    others = [k for k in keep if abs(abs(normals[k] @ plane[0]) - 1) > _PARALLEL]
    found["corner"] = [(c, "corner", number) for c in
                       _corners(solids, view, hit, radius, plane, normals[keep], offsets[keep])]
    if found["corner"]:
        return plane  # the first feature in the order: no need to look further
    edges = _edges(solids, view, hit, radius, plane, normals[others], offsets[others])
    found["edge"] = [(point, "edge", number) for point, _ in edges]
    middle = edge_middle(whole, plane, (edges[0][0], edges[0][1][1])) if edges else None
    if middle is not None and view.pixels(middle)[0] <= RADIUS:
        found["midpoint"] = [(middle, "midpoint", number)]
    if not edges and _curved_near(solids, near):  # a column's rim round its flat top
        found["edge"] = [(point, "edge", number) for point in
                         _boundary(solids, view, hit, 3 * radius, plane)]
    return plane


def _boundary(solids: Solids, view: _View, hit, reach: float, plane, count: int = 16) -> list:
    """Where the hit flat face ends, looked for along ``count`` directions of its
    plane from the hit (within ``reach``): the point of its outline nearest the
    ray, when within the radius (any outline, straight or curved): the end is
    bracketed in eighths of the reach, then the most promising one halved."""
    n = plane[0]
    u = np.cross(n, [1.0, 0.0, 0.0] if abs(n[0]) < 0.9 else [0.0, 1.0, 0.0])
    u /= np.linalg.norm(u)
    v = np.cross(n, u)
    angles = np.linspace(0, 2 * np.pi, count, endpoint=False)
    ways = np.cos(angles)[:, None] * u + np.sin(angles)[:, None] * v
    steps = np.linspace(reach / 8, reach, 8)
    probes = (hit + steps[None, :, None] * ways[:, None, :]).reshape(-1, 3)
    carried = solids.carries(np.broadcast_to(n, probes.shape), probes).reshape(count, 8)
    ended = ~carried
    found = np.flatnonzero(ended.any(axis=1))
    if len(found) == 0:
        return []
    first = np.argmax(ended[found], axis=1)
    high = steps[first]
    low = np.where(first > 0, steps[np.maximum(first - 1, 0)], 0.0)
    ways = ways[found]
    rough = view.pixels(hit + ((low + high) / 2)[:, None] * ways)
    keep = np.argsort(rough)[:1]
    low, high, ways = low[keep], high[keep], ways[keep]
    normals = np.broadcast_to(n, ways.shape)
    for _ in range(60):
        if np.max(high - low) <= 1e-11 * solids.size:
            break
        middle = (low + high) / 2
        inner = solids.carries(normals, hit + middle[:, None] * ways)
        low = np.where(inner, middle, low)
        high = np.where(inner, high, middle)
    points = hit + low[:, None] * ways
    near = view.pixels(points)
    best = int(np.argmin(near))
    return [points[best]] if near[best] <= RADIUS else []


def _curved_near(solids: Solids, numbers) -> bool:
    from castor.primitives import PRIMITIVES

    leaves = solids.traced.leaves
    return any(leaves[k].kind == "smooth" or PRIMITIVES[leaves[k].kind].curved for k in numbers)


def _own_plane(solids: Solids, hit, face: int, normals, offsets, owned) -> np.ndarray:
    """The rows of the hit face's plane: a flat face of the leaf hit, through
    the point, turned as the surface is there (none: the face is curved)."""
    normal = solids.traced.normals(hit[None], np.array([face]))[0]
    return np.flatnonzero(owned & (np.abs(normals @ hit - offsets) < 1e-6 * solids.size)
                          & (normals @ normal > 1 - 1e-6))


def face_at(prepared: Prepared, origin, direction):
    """The face a ray meets first: (the point, the leaf, its plane (normal,
    offset) when the face is flat, else None), or None."""
    view = _View(origin, direction, 1.0, None)
    solids = prepared.solids
    t, face = solids.traced.first_hit(view.origin[None], view.direction[None])
    if not np.isfinite(t[0]):
        return None
    hit = view.origin + t[0] * view.direction
    number = int(face[0] >> 32)
    planes = solids.planes(number)
    mine = _own_plane(solids, hit, int(face[0]), planes.normals, planes.offsets,
                      np.ones(len(planes.offsets), bool))
    plane = (planes.normals[mine[0]], planes.offsets[mine[0]]) if len(mine) else None
    return hit, number, plane


def _within(points: np.ndarray, hit: np.ndarray, radius: float) -> np.ndarray:
    """The points near enough the hit for its neighbourhood to decide about them."""
    return np.linalg.norm(points - hit, axis=1) <= 3 * radius


def _line(plane, normal, offset):
    """The line where two planes meet: a point and a unit direction."""
    n1, o1 = plane
    u = np.cross(n1, normal)
    u /= np.linalg.norm(u)
    a = np.array([n1, normal, u])
    start = np.linalg.solve(a, np.array([o1, offset, 0.0]))
    return start, u


def _edges(solids: Solids, view: _View, hit, radius: float, plane, normals, offsets) -> list:
    """The edges of the solid on the hit face's plane near the ray, nearest first:
    (the point nearest the ray, its line)."""
    candidates = []
    for normal, offset in zip(normals, offsets):
        line = _line(plane, normal, offset)
        point = view.closest_on_line(*line)
        if view.pixels(point)[0] <= RADIUS and np.linalg.norm(point - hit) <= 3 * radius:
            candidates.append((point, line))
    if not candidates:
        return []
    ok = edge_along(solids, np.array([c[0] for c in candidates]), plane,
                     np.array([c[1][1] for c in candidates]))
    edges = [c for c, good in zip(candidates, ok) if good]
    edges.sort(key=lambda c: view.pixels(c[0])[0])
    return edges


def _corners(solids: Solids, view: _View, hit, radius: float, plane, normals, offsets) -> list:
    """Points of the hit face's plane near the ray where three faces of the
    solid meet (planes whose normals span space)."""
    n1, o1 = plane
    count = len(offsets)
    if count < 2:
        return []
    i, j = np.triu_indices(count, 1)
    a = np.stack([np.broadcast_to(n1, (len(i), 3)), normals[i], normals[j]], axis=1)
    det = np.linalg.det(a)
    ok = np.abs(det) > 1e-9
    if not ok.any():
        return []
    b = np.column_stack([np.full(ok.sum(), o1), offsets[i[ok]], offsets[j[ok]]])
    points = np.linalg.solve(a[ok], b[:, :, None])[:, :, 0]
    points = points[(view.pixels(points) <= RADIUS) & _within(points, hit, radius)]
    if len(points) == 0:
        return []
    _, first = np.unique(np.round(points / (1e-9 * solids.size)), axis=0, return_index=True)
    points = points[np.sort(first)]
    return [p for p in points if is_corner(solids, p, normals, offsets)]


def _inferences(solids: Solids, view: _View, previous: np.ndarray, found: dict) -> None:
    """The axes through the previous point, and the parallels and perpendiculars
    of the edges it lies on, where the ray passes near them."""
    axes = []
    for name, axis in zip("xyz", np.eye(3)):
        point = previous + axis * ((view.closest_on_line(previous, axis) - previous) @ axis)
        if view.pixels(point)[0] <= RADIUS and np.linalg.norm(point - previous) > 0:
            axes.append((point, f"axis {name}", None))
    found["axis"] = axes
    near = solids.near(previous, solids.step * 10)
    normals, offsets, _, _ = solids.gathered(near)
    keep = distinct(normals, offsets, solids.size)
    through = [k for k in keep if abs(normals[k] @ previous - offsets[k]) < 1e-8 * solids.size]
    parallels, perpendiculars = [], []
    for a in range(len(through)):
        for b in range(a + 1, len(through)):
            na, nb = normals[through[a]], normals[through[b]]
            u = np.cross(na, nb)
            if np.linalg.norm(u) < 1e-6:
                continue
            u /= np.linalg.norm(u)
            if np.max(np.abs(u)) > 1 - 1e-9:
                continue  # an axis already
            for direction, kind in ((u, parallels), (np.cross(na, u), perpendiculars),
                                    (np.cross(nb, u), perpendiculars)):
                point = view.closest_on_line(previous, direction)
                if view.pixels(point)[0] <= RADIUS:
                    kind.append((point, "parallel" if kind is parallels else "perpendicular",
                                 None))
    found["parallel"] = parallels
    found["perpendicular"] = perpendiculars


def _on_grid(solids: Solids, hit: np.ndarray, plane) -> np.ndarray:
    """A flat face's point rounded to the grid in its plane (kept where the face
    is); a curved face's point as it is."""
    if plane is None:
        return hit
    n, offset = plane
    u = np.cross(n, [0.0, 0.0, 1.0])
    if np.linalg.norm(u) < 1e-9:
        u = np.array([1.0, 0.0, 0.0])
    u /= np.linalg.norm(u)
    v = np.cross(n, u)
    base = n * offset
    rel = hit - base
    point = base + np.round(rel @ u / GRID) * GRID * u + np.round(rel @ v / GRID) * GRID * v
    if solids.carries(n[None], point[None])[0]:
        return point
    return hit

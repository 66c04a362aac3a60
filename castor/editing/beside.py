"""The corners and edges a ray passes near, whether it meets the solid or not
(CLI.md, "Editing on screen").

castor.editing.snap looks for features around the point a ray meets; a ray
that passes 3 pixels outside an object's outline meets the ground or a face
behind it, far from the object's corner. So the primitives whose boxes come
within the snap radius of the ray (on the screen) are gathered, and the lines
where two of their planes meet are tried: the point of each line nearest the
ray, if it is within the radius; then where a third plane crosses such a line
(a corner candidate). A candidate counts where the evaluated solid has it
(castor.editing.solids: faces on three planes meeting there; a face on one
side of the line only) and where the camera sees it (no solid before it).
"""

from __future__ import annotations

import numpy as np

from castor.editing.solids import Solids, edge_along, edge_middle, is_corner

LEAVES = 48  # at most this many primitives near the ray: those the ray reaches first
LINES = 64  # at most this many lines where two planes meet, the nearest the ray
TRIED = 8  # at most this many candidates of a kind checked against the solid, nearest first
_PARALLEL = 1e-6


def beside(solids: Solids, view, radius: float, found: dict) -> None:
    """Add to ``found`` the corners, the edge and its middle near the ray
    (within ``radius`` pixels), as (point, name, leaf) like the hit's own."""
    leaves, margins = _near_ray(solids, view, radius)
    if len(leaves) == 0:
        return
    normals, offsets, _, owners = solids.gathered(leaves)
    if len(offsets) < 2:
        return
    rows = np.searchsorted(leaves, owners)  # each plane's leaf, as a row of ``leaves``
    lows, highs = solids.lows[leaves], solids.highs[leaves]
    lines = _lines(solids, view, radius, normals, offsets, rows, lows, highs, margins)
    if lines is None:
        if not _has_edge(found):
            _rims(solids, view, radius, leaves, found)
        return
    corners = _corners(solids, view, radius, (normals, offsets, owners), rows, lows, highs,
                       lines)
    if corners:
        found.setdefault("corner", []).extend(corners)
        return  # the first in snap's order: the edges are not needed
    _edge(solids, view, radius, (normals, offsets, owners), lines, found)
    if not _has_edge(found):
        _rims(solids, view, radius, leaves, found)


def _has_edge(found: dict) -> bool:
    """Whether an edge (or its middle, or a face's centre) is found already:
    a rim would come after it in snap's order."""
    return any(found.get(kind) for kind in ("midpoint", "centre", "edge"))


def _rims(solids: Solids, view, radius: float, leaves: np.ndarray, found: dict) -> None:
    """The rim of a curved primitive's flat face (a column's top) that the ray
    passes near without meeting it: where the ray crosses the face's plane, the
    face's outline between that point and the face's centre (a circle's point
    nearest it), found by halving the part of that segment within the radius
    on the screen; if seen, as an edge."""
    from castor.primitives import PRIMITIVES

    kinds = [solids.traced.leaves[k].kind for k in leaves]
    curved = leaves[[kind != "smooth" and PRIMITIVES[kind].curved for kind in kinds]] \
        if len(leaves) else leaves
    if len(curved) == 0:
        return
    normals, offsets, centres, owners = solids.gathered(curved)
    across = normals @ view.direction
    with np.errstate(divide="ignore", invalid="ignore"):
        t = (offsets - normals @ view.origin) / across
    ok = np.flatnonzero((np.abs(across) > _PARALLEL) & (t > 0))
    if len(ok) == 0:
        return
    ok = ok[np.argsort(t[ok])[:TRIED]]  # the planes the ray crosses first
    normals, centres, owners = normals[ok], centres[ok], owners[ok]
    crossed = view.origin + t[ok, None] * view.direction
    way = crossed - centres
    # the part of each segment centre -> crossing within the radius on the
    # screen (the crossing is on the ray): the rim counts only if it lies there
    beyond, first = np.zeros(len(way)), np.ones(len(way))  # fractions of the way
    for _ in range(40):
        middle = (beyond + first) / 2
        within = view.pixels(centres + middle[:, None] * way) <= radius
        beyond, first = np.where(within, beyond, middle), np.where(within, middle, first)
    start = centres + first[:, None] * way
    low = np.minimum(start, crossed).min(axis=0)
    high = np.maximum(start, crossed).max(axis=0)
    local = solids.around((low + high) / 2, float(np.max(high - low)) / 2 + 10 * solids.step)
    # the face reaches that part, and ends before the crossing (the ray misses it)
    inner = local.carries(normals, start) & ~local.carries(normals, crossed)
    if not inner.any():
        return
    keep = np.flatnonzero(inner)[:2]  # the two faces the ray crosses first
    normals, centres, owners, way, first, start, crossed = (
        a[keep] for a in (normals, centres, owners, way, first, start, crossed))
    low = np.minimum(start, crossed).min(axis=0)
    high = np.maximum(start, crossed).max(axis=0)
    local = solids.around((low + high) / 2, float(np.max(high - low)) / 2 + 10 * solids.step)
    low, high = first, np.ones(len(way))
    for _ in range(60):
        if np.max((high - low) * np.linalg.norm(way, axis=1)) <= 1e-10 * solids.size:
            break
        middle = (low + high) / 2
        carried = local.carries(normals, centres + middle[:, None] * way)
        low, high = np.where(carried, middle, low), np.where(carried, high, middle)
    points = centres + low[:, None] * way
    near = np.flatnonzero(view.pixels(points) <= radius)
    if len(near) == 0:
        return
    near = near[view.nearest_first(points[near])]
    seen = _visible(solids, view, points[near])
    if seen.any():
        k = near[int(np.argmax(seen))]
        found.setdefault("edge", []).append((points[k], "edge", int(owners[k])))


def _edge(solids: Solids, view, radius: float, planes, lines, found: dict) -> None:
    """The nearest of the lines near the ray that is an edge of the solid and
    seen, and its middle if within the radius and seen, into ``found``."""
    normals, offsets, owners = planes
    i, j, _, ways, nearest = lines
    order = view.nearest_first(nearest)[:TRIED]
    # an edge where either plane's face ends at the line: one classification
    # of the probes of every candidate on both planes
    sides = np.stack([i[order], j[order]])
    edged = edge_along(solids, nearest[np.concatenate([order, order])],
                       (normals[sides.ravel()], None), ways[np.concatenate([order, order])])
    edged = edged.reshape(2, -1)
    rows = np.flatnonzero(edged.any(axis=0))
    if len(rows) == 0:
        return
    planes = sides[np.argmax(edged[:, rows], axis=0), rows]  # the plane whose face ends
    # the nearest edge's middle, seen or not with the edges in one trace
    middle = edge_middle(solids, (normals[planes[0]], offsets[planes[0]]),
                         (nearest[order[rows[0]]], ways[order[rows[0]]]))
    near_middle = middle is not None and view.pixels(middle)[0] <= radius
    points = nearest[order[rows]]
    seen = _visible(solids, view, np.vstack([points, middle]) if near_middle else points)
    for n, row in enumerate(rows):
        if not seen[n]:
            continue
        k, leaf = order[row], int(owners[i[order[row]]])
        found.setdefault("edge", []).append((nearest[k], "edge", leaf))
        if n > 0:  # the nearest edge is hidden: this one's middle
            middle = edge_middle(solids, (normals[planes[n]], offsets[planes[n]]),
                                 (nearest[k], ways[k]))
            near_middle = middle is not None and view.pixels(middle)[0] <= radius \
                and _visible(solids, view, middle[None])[0]
        elif near_middle:
            near_middle = seen[-1]
        if near_middle:
            found.setdefault("midpoint", []).append((middle, "midpoint", leaf))
        return


def _near_ray(solids: Solids, view, radius: float) -> tuple[np.ndarray, np.ndarray]:
    """The leaves whose boxes come within ``radius`` pixels of the ray (their
    boxes grown by what the radius measures at their far side), and that
    margin of each, in metres."""
    if len(solids.lows) == 0:
        return np.zeros(0, np.int64), np.zeros(0)
    centres = (solids.lows + solids.highs) / 2
    halves = (solids.highs - solids.lows) / 2
    far = (centres - view.origin) @ view.direction + halves @ np.abs(view.direction)
    if view.pixel_size is not None:
        margins = np.full(len(far), radius * view.pixel_size)
    else:
        margins = radius * view.pixel * np.maximum(far, 0.0)
    low, high = solids.lows - margins[:, None], solids.highs + margins[:, None]
    d = view.direction
    with np.errstate(divide="ignore", invalid="ignore"):
        t0 = (low - view.origin) / d
        t1 = (high - view.origin) / d
    flat = d == 0
    within = (low <= view.origin) & (view.origin <= high)
    enter = np.where(flat, np.where(within, -np.inf, np.inf), np.fmin(t0, t1)).max(axis=1)
    leave = np.where(flat, np.where(within, np.inf, -np.inf), np.fmax(t0, t1)).min(axis=1)
    near = np.flatnonzero((enter <= leave) & (leave >= 0) & (far > 0))
    if len(near) > LEAVES:
        near = np.sort(near[np.argsort(enter[near], kind="stable")[:LEAVES]])
    return near, margins[near]


def _lines(solids: Solids, view, radius: float, normals, offsets, rows, lows, highs, margins):
    """The lines where two planes of the leaves meet that pass within the radius
    of the ray, near both leaves: (first plane, second plane, a point of each,
    its unit direction, its point nearest the ray), or None."""
    count = len(offsets)
    i, j = np.triu_indices(count, 1)
    # two planes whose leaves' boxes (grown by the margins) meet
    grown_low, grown_high = lows - margins[:, None], highs + margins[:, None]
    a, b = rows[i], rows[j]
    touch = np.all((grown_low[a] <= grown_high[b]) & (grown_low[b] <= grown_high[a]), axis=1)
    i, j = i[touch], j[touch]
    ways = np.cross(normals[i], normals[j])
    length = np.linalg.norm(ways, axis=1)
    keep = length > _PARALLEL
    i, j, ways = i[keep], j[keep], ways[keep] / length[keep, None]
    if len(i) == 0:
        return None
    system = np.stack([normals[i], normals[j], ways], axis=1)
    values = np.column_stack([offsets[i], offsets[j], np.zeros(len(i))])
    starts = np.linalg.solve(system, values[:, :, None])[:, :, 0]
    nearest = _closest(view, starts, ways)
    ok = view.pixels(nearest) <= radius
    for side in (rows[i], rows[j]):
        ok &= np.all((grown_low[side] <= nearest) & (nearest <= grown_high[side]), axis=1)
    if not ok.any():
        return None
    ok = np.flatnonzero(ok)
    if len(ok) > LINES:  # a ray along a row of primitives: the nearest lines
        ok = ok[view.nearest_first(nearest[ok])[:LINES]]
    return i[ok], j[ok], starts[ok], ways[ok], nearest[ok]


def _closest(view, starts: np.ndarray, ways: np.ndarray) -> np.ndarray:
    """The point of each line (start, unit direction) nearest the ray."""
    d = view.direction
    w = starts - view.origin
    b = ways @ d
    denominator = 1.0 - b * b
    with np.errstate(divide="ignore", invalid="ignore"):
        s = np.where(denominator > 1e-12, (b * (w @ d) - np.einsum("ij,ij->i", w, ways))
                     / denominator, 0.0)
    return starts + s[:, None] * ways


def _corners(solids: Solids, view, radius: float, planes, rows, lows, highs, lines) -> list:
    """Where a third plane crosses the lines near the ray, within the radius:
    the nearest such point that is a corner of the solid and seen, if any.
    ``planes``: normals, offsets and leaf numbers; ``rows``: each plane's box."""
    normals, offsets, leaves = planes
    i, j, starts, ways, _ = lines
    across = ways @ normals.T  # (lines, planes)
    with np.errstate(divide="ignore", invalid="ignore"):
        s = (offsets[None, :] - starts @ normals.T) / across
    ok = np.abs(across) > _PARALLEL
    line, plane = np.nonzero(ok)
    points = starts[line] + s[line, plane][:, None] * ways[line]
    near = view.pixels(points) <= radius
    tolerance = 1e-6 * solids.size
    for side in (rows[i[line]], rows[j[line]], rows[plane]):
        near &= np.all((lows[side] - tolerance <= points) & (points <= highs[side] + tolerance),
                       axis=1)
    points, owners = points[near], leaves[i[line[near]]]
    if len(points) == 0:
        return []
    _, first = np.unique(np.round(points / (1e-9 * solids.size)), axis=0, return_index=True)
    points, owners = points[first], owners[first]
    order = view.nearest_first(points)[:TRIED]
    points, owners = points[order], owners[order]
    seen = _visible(solids, view, points)
    for point, visible, owner in zip(points, seen, owners):
        if visible and is_corner(solids, point, normals, offsets):
            return [(point, "corner", int(owner))]
    return []


def _visible(solids: Solids, view, points: np.ndarray) -> np.ndarray:
    """Whether the camera sees each point: no solid on the ray to it before it."""
    points = np.asarray(points, np.float64).reshape(-1, 3)
    if view.pixel_size is not None:
        depth = (points - view.origin) @ view.direction
        origins = points - depth[:, None] * view.direction
        directions = np.broadcast_to(view.direction, points.shape)
    else:
        rel = points - view.origin
        depth = np.linalg.norm(rel, axis=1)
        origins = np.broadcast_to(view.origin, points.shape)
        directions = rel / np.where(depth > 0, depth, 1.0)[:, None]
    t, _ = solids.traced.first_hit(np.ascontiguousarray(origins),
                                   np.ascontiguousarray(directions))
    return ~(t < depth - 1e-6 * solids.size)

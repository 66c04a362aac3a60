"""Where a surface passes through itself, and the thin walls a smooth solid
turns inside out (LANGUAGE.md §7, §7.1).

Catmull–Clark's limit surface lies inside its control mesh where the mesh is
convex. Where a boolean left a thin wedge of material between a flat face
(bounded by creases, so it stays in its plane) and a curved one, the curved
side moves in by more than the wedge is thick near its tip, and passes
through the flat side: a pocket of winding -1, no solid. The oracle's
plain-Python subdivision does the same, so it is the surface, not a slip.

``crossing_pairs`` finds the triangles of a closed surface that cross one
another (no shared corner, a side of one through the inside of the other):
their boxes are put in the cells of a grid, and the pairs that share a cell
and whose boxes meet are tested exactly, a piece at a time. ``uncrossed``
puts back the corners that went through, told by the winding number beside
where two triangles meet: -1 just in front of both is a wall turned inside
out, 2 just behind both two parts pushed into each other. A corner moves by
no more than ``reach`` (the tolerance) and stops a hair past the other
side's plane, so the wall keeps a thickness and the surface stays within
the tolerance of the limit; a flat face's corners never move.
"""

from __future__ import annotations

import numpy as np

# a box over more cells than this is compared with every other box at once
_WIDE = 64
# crossings looked at in one round of ``uncrossed`` (each costs two winding
# numbers, each a pass over the whole surface)
_LOOKED = 64


def _pairs_in_cells(cells: np.ndarray, owners: np.ndarray, chunk: int):
    """Every pair of owners that share a cell, as keys (``_keys``), in pieces of
    about ``chunk`` pairs; a pair in several cells comes once from each."""
    order = np.lexsort((owners, cells))
    cells, owners = cells[order], owners[order]
    starts = np.flatnonzero(np.r_[True, cells[1:] != cells[:-1]])
    sizes = np.diff(np.r_[starts, len(cells)])
    # each member pairs with the members after it in its cell
    after = np.repeat(starts + sizes, sizes) - np.arange(len(cells)) - 1
    total = np.cumsum(after)
    begin = 0
    while begin < len(cells):
        end = int(np.searchsorted(total, total[begin] - after[begin] + chunk, side="right"))
        end = max(end, begin + 1)
        part = after[begin:end]
        first = np.repeat(np.arange(begin, end), part)
        offset = np.arange(len(first)) - np.repeat(np.cumsum(part) - part, part) + 1
        yield _keys(owners[first], owners[first + offset])
        begin = end


def _keys(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Each pair of different owners as one number, the lower first (unsorted, repeated)."""
    low, high = np.minimum(a, b), np.maximum(a, b)
    keep = low != high
    return low[keep] * (1 << 31) + high[keep]


def _boxes_meet(lo: np.ndarray, hi: np.ndarray, pairs: np.ndarray) -> np.ndarray:
    a, b = pairs[:, 0], pairs[:, 1]
    return np.all((lo[a] <= hi[b]) & (lo[b] <= hi[a]), axis=1)


def _cells(lo, hi, origin, cell, owners):
    """The grid cells each box of ``owners`` covers: (cell numbers, owners), one row a cell."""
    first = np.floor((lo[owners] - origin) / cell).astype(np.int64)
    last = np.floor((hi[owners] - origin) / cell).astype(np.int64)
    span = last - first + 1
    reps = span.prod(axis=1)
    owner = np.repeat(np.arange(len(owners)), reps)
    k = np.arange(len(owner)) - np.repeat(np.cumsum(reps) - reps, reps)
    s = span[owner]
    x = first[owner, 0] + k % s[:, 0]
    y = first[owner, 1] + (k // s[:, 0]) % s[:, 1]
    z = first[owner, 2] + k // (s[:, 0] * s[:, 1])
    size = np.floor((hi.max(axis=0) - origin) / cell).astype(np.int64) + 2
    return (x * size[1] + y) * size[2] + z, owners[owner]


def _spans(lo, hi, origin, cell):
    return (np.floor((hi - origin) / cell) - np.floor((lo - origin) / cell) + 1).prod(axis=1)


def _candidates(lo: np.ndarray, hi: np.ndarray, chunk: int = 1 << 16):
    """Pairs of boxes that may meet, as keys in pieces (repeated, unsorted):
    through a grid of cells twice the median box; the boxes over more than 64
    of its cells (a flat face's long triangles beside a curved surface's small
    ones) are paired with every box through a second grid, twice their own
    median."""
    origin = lo.min(axis=0)
    floor = 1e-12 * max(1.0, float(np.abs(hi).max()))
    cell = np.maximum(2 * np.median(hi - lo, axis=0), floor)
    wide = _spans(lo, hi, origin, cell) > _WIDE
    yield from _pairs_in_cells(*_cells(lo, hi, origin, cell, np.flatnonzero(~wide)), chunk)
    if wide.any():
        coarse = np.maximum(2 * np.median(hi[wide] - lo[wide], axis=0), cell)
        cells, owners = _cells(lo, hi, origin, coarse, np.arange(len(lo)))
        order = np.argsort(cells, kind="stable")
        cells, owners = cells[order], owners[order]
        starts = np.flatnonzero(np.r_[True, cells[1:] != cells[:-1]])
        sizes = np.diff(np.r_[starts, len(cells)])
        group = np.repeat(np.arange(len(starts)), sizes)
        mine = np.flatnonzero(wide[owners])  # each wide box's rows, paired with its cells' rows
        reps = sizes[group[mine]]
        first = np.repeat(starts[group[mine]], reps)
        k = np.arange(len(first)) - np.repeat(np.cumsum(reps) - reps, reps)
        yield _keys(np.repeat(owners[mine], reps), owners[first + k])


def _pairs(keys: np.ndarray) -> np.ndarray:
    """Keys as pairs (a, b), each once."""
    keys = np.sort(keys)
    keys = keys[np.r_[True, keys[1:] != keys[:-1]]] if len(keys) else keys
    return np.column_stack([keys >> 31, keys & ((1 << 31) - 1)])


def near_pairs(lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """Pairs (a, b), a < b, of boxes that meet (``_candidates``, then their boxes)."""
    if len(lo) < 2:
        return np.zeros((0, 2), np.int64)
    pieces = []
    for keys in _candidates(lo, hi):
        pairs = _pairs(keys)
        pieces.append(pairs[_boxes_meet(lo, hi, pairs)])
    return np.unique(np.concatenate(pieces), axis=0)


def _orient(a, b, c, d):
    """The sign of the volume of the tetrahedra (a, b, c, d), row by row."""
    return np.sign(np.einsum("ij,ij->i", np.cross(b - a, c - a), d - a))


def _side_through(p, q, a, b, c):
    """Whether the segments pq pass through the insides of the triangles abc."""
    sp, sq = _orient(a, b, c, p), _orient(a, b, c, q)
    across = sp * sq < 0
    s1, s2, s3 = _orient(p, q, a, b), _orient(p, q, b, c), _orient(p, q, c, a)
    return across & (s1 == s2) & (s2 == s3) & (s1 != 0)


def _along_line(corners, origin, normal, line):
    """Where each triangle of ``corners`` meets the plane (origin, normal), as
    the least and greatest parameter along ``line`` (NaN where it does not)."""
    distance = np.einsum("ijk,ik->ij", corners - origin[:, None], normal)
    low = np.full(len(corners), np.inf)
    high = np.full(len(corners), -np.inf)
    for k in range(3):
        a, b = corners[:, k], corners[:, (k + 1) % 3]
        da, db = distance[:, k], distance[:, (k + 1) % 3]
        across = da * db < 0
        t = np.where(across, da / np.where(across, da - db, 1.0), 0.0)
        point = a + t[:, None] * (b - a)
        at = np.einsum("ij,ij->i", point, line)
        hit = across | (da == 0)
        low = np.where(hit, np.minimum(low, at), low)
        high = np.where(hit, np.maximum(high, at), high)
    return low, high


def crossing_middles(positions: np.ndarray, triangles: np.ndarray,
                     pairs: np.ndarray) -> np.ndarray:
    """For each pair of crossing triangles, the middle of the segment where
    they meet, inside both: each meets the other's plane along a segment of
    the two planes' common line, and the two segments overlap there."""
    corners = positions[triangles]
    a, b = corners[pairs[:, 0]], corners[pairs[:, 1]]
    na = np.cross(a[:, 1] - a[:, 0], a[:, 2] - a[:, 0])
    nb = np.cross(b[:, 1] - b[:, 0], b[:, 2] - b[:, 0])
    line = np.cross(na, nb)
    line /= np.maximum(np.linalg.norm(line, axis=1), 1e-300)[:, None]
    low_a, high_a = _along_line(a, b[:, 0], nb, line)
    low_b, high_b = _along_line(b, a[:, 0], na, line)
    middle = (np.maximum(low_a, low_b) + np.minimum(high_a, high_b)) / 2
    # the point of the common line at that parameter: the point of both
    # planes nearest the origin, moved along the line
    da = np.einsum("ij,ij->i", na, a[:, 0])
    db = np.einsum("ij,ij->i", nb, b[:, 0])
    both = np.cross(na, nb)
    base = (np.cross(nb, both) * da[:, None] + np.cross(both, na) * db[:, None]) / np.maximum(
        np.einsum("ij,ij->i", both, both), 1e-300)[:, None]
    return base + (middle - np.einsum("ij,ij->i", base, line))[:, None] * line


def crossing_pairs(positions: np.ndarray, triangles: np.ndarray) -> np.ndarray:
    """Pairs of triangles with no corner in common where a side of one passes
    through the inside of the other; the candidates are tested a piece at a
    time, so a surface of 200,000 triangles needs a few tens of megabytes."""
    corners = positions[triangles]
    lo, hi = corners.min(axis=1), corners.max(axis=1)
    found = [np.zeros((0, 2), np.int64)]
    if len(triangles) < 2:
        return found[0]
    for keys in _candidates(lo, hi):
        pairs = _pairs(keys)
        pairs = pairs[_boxes_meet(lo, hi, pairs)]
        shared = (triangles[pairs[:, 0], :, None] == triangles[pairs[:, 1], None, :]).any(axis=(1, 2))
        pairs = pairs[~shared]
        a, b = corners[pairs[:, 0]], corners[pairs[:, 1]]
        crossing = np.zeros(len(pairs), bool)
        for one, other in ((a, b), (b, a)):
            for k in range(3):
                crossing |= _side_through(one[:, k], one[:, (k + 1) % 3], other[:, 0],
                                          other[:, 1], other[:, 2])
        found.append(pairs[crossing])
    return np.unique(np.concatenate(found), axis=0)


def winding(positions: np.ndarray, triangles: np.ndarray, points: np.ndarray) -> np.ndarray:
    """The winding number of a closed surface at a few points: the sum of its
    triangles' solid angles (Van Oosterom and Strackee) over 4 pi."""
    corners = positions[triangles]
    out = np.zeros(len(points))
    for k, point in enumerate(points):
        a, b, c = (corners[:, j] - point for j in range(3))
        la, lb, lc = (np.linalg.norm(v, axis=1) for v in (a, b, c))
        top = np.einsum("ij,ij->i", a, np.cross(b, c))
        bottom = (la * lb * lc + np.einsum("ij,ij->i", a, b) * lc
                  + np.einsum("ij,ij->i", a, c) * lb + np.einsum("ij,ij->i", b, c) * la)
        out[k] = 2 * np.arctan2(top, bottom).sum() / (4 * np.pi)
    return out


def uncrossed(positions: np.ndarray, triangles: np.ndarray, movable: np.ndarray,
              reach: float, rounds: int = 8) -> np.ndarray:
    """``positions`` with the corners that went through another part of the
    surface put back. Where two triangles cross, the winding number just in
    front of both, at the middle of where they meet, is -1 for a thin wall
    turned inside out: each ``movable`` corner of one that lies in front of
    the other's plane goes back behind it. Just behind both it is 2 for two
    parts pushed into each other: each corner behind the other's plane goes
    back in front of it. Each time by a hair past the plane (a thousandth of
    ``reach``), and only corners nearer the plane than ``reach``. Returns the
    new positions; crossings deeper than ``reach``, or of corners that may
    not move, stay after ``rounds``."""
    positions = positions.copy()
    hair = reach * 1e-3
    for _ in range(rounds):
        pairs = crossing_pairs(positions, triangles)
        if not len(pairs):
            break
        p = positions[triangles]
        normal = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
        normal /= np.maximum(np.linalg.norm(normal, axis=1), 1e-300)[:, None]
        with np.errstate(invalid="ignore", divide="ignore"):
            middle = crossing_middles(positions, triangles, pairs)
        # two triangles in one plane that overlap have no common line: left
        planar = ~np.isfinite(middle).all(axis=1)
        pairs, middle = pairs[~planar][:_LOOKED], middle[~planar][:_LOOKED]
        if not len(pairs):
            break
        # a step of ``step`` along ``both`` is ``step`` in front of both planes
        cosine = np.einsum("ij,ij->i", normal[pairs[:, 0]], normal[pairs[:, 1]])
        both = (normal[pairs[:, 0]] + normal[pairs[:, 1]]) / np.maximum(1 + cosine, 1e-12)[:, None]
        # the step stays inside both triangles: the wedge in front of two
        # planes that face almost against each other is narrow
        room = np.full(len(pairs), np.inf)
        for side in (0, 1):
            for k in range(3):
                a, b = p[pairs[:, side], k], p[pairs[:, side], (k + 1) % 3]
                along = b - a
                off = np.cross(along, middle - a)
                room = np.minimum(room, np.linalg.norm(off, axis=1)
                                  / np.maximum(np.linalg.norm(along, axis=1), 1e-300))
        step = np.minimum(hair, 0.5 * room / np.linalg.norm(both, axis=1))
        probes = np.concatenate([middle + step[:, None] * both, middle - step[:, None] * both])
        seen = np.round(winding(positions, triangles, probes)).reshape(2, -1)
        inside_out, pushed_in = seen[0] < 0, seen[1] > 1
        vertex, plane, sense = [], [], []
        for one, other in ((0, 1), (1, 0)):
            for kind, wanted in ((inside_out, 1.0), (pushed_in, -1.0)):
                chosen = pairs[kind]
                vertex.append(triangles[chosen[:, one]].ravel())
                plane.append(np.repeat(chosen[:, other], 3))
                sense.append(np.full(3 * len(chosen), wanted))
        vertex, plane, sense = map(np.concatenate, (vertex, plane, sense))
        front = np.einsum("ij,ij->i", positions[vertex] - p[plane, 0], normal[plane])
        # inside out: corners in front go behind; pushed in: corners behind come out
        wrong = movable[vertex] & (front * sense > 0) & (np.abs(front) <= reach)
        if not wrong.any():
            break
        vertex, plane, front = vertex[wrong], plane[wrong], front[wrong]
        order = np.lexsort((-np.abs(front), vertex))  # the farthest plane first
        vertex, plane, front = vertex[order], plane[order], front[order]
        once = np.r_[True, vertex[1:] != vertex[:-1]]
        vertex, plane, front = vertex[once], plane[once], front[once]
        positions[vertex] -= (front + np.sign(front) * hair)[:, None] * normal[plane]
    return positions

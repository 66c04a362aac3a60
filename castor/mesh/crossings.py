"""Where a surface passes through itself, and the thin walls a smooth solid
turns inside out (LANGUAGE.md §7, §7.1).

Catmull–Clark's limit surface lies inside its control mesh where the mesh is
convex. Where a boolean left a thin wedge of material between a flat face
(bounded by creases, so it stays in its plane) and a curved one, the curved
side moves in by more than the wedge is thick near its tip, and passes
through the flat side: a pocket of winding -1, no solid. The oracle's
plain-Python subdivision does the same, so it is the surface, not a slip.

``crossing_pairs`` finds the triangles of a closed surface that cross one
another (no shared side, a side of one through the inside of the other):
their boxes are put in a loose hierarchy of grids (each box in cells at
least as long as it), and the pairs that share a cell and whose boxes meet
are tested, a piece at a time, with the signs of triple products (a sign
within rounding of zero counts as zero: triangles of one plane never cross).

``uncrossed`` puts back the corners that went through, told by the winding
number beside where two triangles meet: -1 just in front of both is a wall
turned inside out, 2 just behind both two parts pushed into each other. A
corner moves by no more than ``reach`` (the tolerance) and stops a hair past
the other side's plane, so the wall keeps a thickness and the surface stays
within the tolerance of the solid's (which has no pocket); the corners of a
face that stayed flat never move.
"""

from __future__ import annotations

import numpy as np

from castor.mesh.arrays import row_hash

# crossings looked at in one round of ``uncrossed`` (each costs two winding
# numbers, each a pass over the whole surface)
_LOOKED = 32
# candidate pairs made at once
_CHUNK = 1 << 16


def _keys(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Each pair of different owners as one number, the lower first (unsorted, repeated)."""
    low, high = np.minimum(a, b), np.maximum(a, b)
    keep = low != high
    return low[keep] * (1 << 31) + high[keep]


def _pairs(keys: np.ndarray) -> np.ndarray:
    """Keys as pairs (a, b), each once."""
    keys = np.sort(keys)
    keys = keys[np.r_[True, keys[1:] != keys[:-1]]] if len(keys) else keys
    return np.column_stack([keys >> 31, keys & ((1 << 31) - 1)])


def _boxes_meet(lo: np.ndarray, hi: np.ndarray, pairs: np.ndarray) -> np.ndarray:
    a, b = pairs[:, 0], pairs[:, 1]
    return np.all((lo[a] <= hi[b]) & (lo[b] <= hi[a]), axis=1)


def _cells(lo, hi, origin, cell, owners):
    """The cells of side ``cell`` each box of ``owners`` covers (at most two a
    side: each box is put in a grid at least as coarse as it is long), as
    (hashed cell numbers, owners), a row a cell. Two cells may share a number:
    that only adds candidates, which the boxes' own test takes out."""
    first = np.floor((lo[owners] - origin) / cell).astype(np.int64)
    last = np.floor((hi[owners] - origin) / cell).astype(np.int64)
    span = np.minimum(last - first + 1, 2)
    reps = span.prod(axis=1)
    row = np.repeat(np.arange(len(owners)), reps)
    k = np.arange(len(row)) - np.repeat(np.cumsum(reps) - reps, reps)
    s = span[row]
    x = first[row, 0] + k % s[:, 0]
    y = first[row, 1] + (k // s[:, 0]) % s[:, 1]
    z = first[row, 2] + k // (s[:, 0] * s[:, 1])
    return row_hash(np.column_stack([x, y, z])), owners[row]


def _chunks(counts: np.ndarray):
    """Ranges [begin, end) of rows whose ``counts`` add up to about _CHUNK."""
    total = np.cumsum(counts)
    begin = 0
    while begin < len(counts):
        end = int(np.searchsorted(total, total[begin] - counts[begin] + _CHUNK, side="right"))
        end = max(end, begin + 1)
        yield begin, end
        begin = end


def _pairs_in_cells(cells: np.ndarray, owners: np.ndarray):
    """Every pair of owners that share a cell, as keys, in pieces."""
    order = np.lexsort((owners, cells))
    cells, owners = cells[order], owners[order]
    starts = np.flatnonzero(np.r_[True, cells[1:] != cells[:-1]])
    sizes = np.diff(np.r_[starts, len(cells)])
    # each member pairs with the members after it in its cell
    after = np.repeat(starts + sizes, sizes) - np.arange(len(cells)) - 1
    for begin, end in _chunks(after):
        part = after[begin:end]
        first = np.repeat(np.arange(begin, end), part)
        offset = np.arange(len(first)) - np.repeat(np.cumsum(part) - part, part) + 1
        yield _keys(owners[first], owners[first + offset])


def _guests_in_cells(cells, owners, guest_cells, guests):
    """Every pair of a guest and an owner in the same cell, as keys, in pieces."""
    order = np.argsort(cells, kind="stable")
    cells, owners = cells[order], owners[order]
    start = np.searchsorted(cells, guest_cells, side="left")
    count = np.searchsorted(cells, guest_cells, side="right") - start
    for begin, end in _chunks(count):
        part = count[begin:end]
        first = np.repeat(start[begin:end], part)
        k = np.arange(len(first)) - np.repeat(np.cumsum(part) - part, part)
        yield _keys(np.repeat(guests[begin:end], part), owners[first + k])


def _candidates(lo: np.ndarray, hi: np.ndarray):
    """Pairs of boxes that may meet, as keys in pieces (repeated, unsorted),
    through a loose hierarchy of grids (cells twice the median box, then
    twice that, and so on): each box lives in the grid whose cells are at
    least as long as it, so it covers at most eight cells; it meets the boxes
    of its own grid in those cells and, as a guest, those of every coarser
    grid in the cells that hold it there. A flat face's long triangles beside
    a curved surface's small ones cost no more than the small ones."""
    origin = lo.min(axis=0)
    length = (hi - lo).max(axis=1)
    floor = 1e-12 * max(1.0, float(np.abs(hi).max()), float(np.abs(lo).max()))
    base = max(2 * float(np.median(length)), floor)
    level = np.ceil(np.log2(np.maximum(length / base, 1.0))).astype(np.int64)
    level += length > base * 2.0 ** level  # rounding: every box within its cells
    present = np.unique(level)
    for top in present:
        cell = base * 2.0 ** top
        residents = np.flatnonzero(level == top)
        cells, owners = _cells(lo, hi, origin, cell, residents)
        yield from _pairs_in_cells(cells, owners)
        finer = np.flatnonzero(level < top)
        if len(finer):
            guest_cells, guests = _cells(lo, hi, origin, cell, finer)
            yield from _guests_in_cells(cells, owners, guest_cells, guests)


def _meeting(lo: np.ndarray, hi: np.ndarray):
    """Pairs (a, b), a < b, of boxes that meet, in pieces (``_candidates``,
    then their boxes; a pair may come in several pieces)."""
    for keys in _candidates(lo, hi):
        pairs = _pairs(keys)
        yield pairs[_boxes_meet(lo, hi, pairs)]


def near_pairs(lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """Pairs (a, b), a < b, of boxes that meet, each once."""
    if len(lo) < 2:
        return np.zeros((0, 2), np.int64)
    return np.unique(np.concatenate([np.zeros((0, 2), np.int64), *_meeting(lo, hi)]), axis=0)


def _orient(a, b, c, d):
    """The sign of the volume of the tetrahedra (a, b, c, d), row by row; 0
    where it is within rounding of 0 (a trillionth of the product of the
    three sides from a), so that triangles of one plane that rounding tilts
    apart are not taken for crossing."""
    u, v, w = b - a, c - a, d - a
    volume = np.einsum("ij,ij->i", np.cross(u, v), w)
    scale = (np.einsum("ij,ij->i", u, u) * np.einsum("ij,ij->i", v, v)
             * np.einsum("ij,ij->i", w, w))
    return np.where(volume * volume <= 1e-24 * scale, 0.0, np.sign(volume))


def _sides(corners, normal, points):
    """The sign of each point's side of each triangle's plane, row by row (0
    within rounding: a trillionth of the normal's and the offset's lengths)."""
    offset = points - corners[:, 0]
    along = np.einsum("ij,ij->i", normal, offset)
    scale = np.einsum("ij,ij->i", normal, normal) * np.einsum("ij,ij->i", offset, offset)
    return np.where(along * along <= 1e-24 * scale, 0.0, np.sign(along))


def _crossing(a: np.ndarray, b: np.ndarray, na: np.ndarray, nb: np.ndarray) -> np.ndarray:
    """Whether a side of triangle a passes through the inside of triangle b,
    or the other way round (beyond rounding: a side in the other's plane, or
    through its side or corner, does not), pair by pair, given their normals:
    first which side of each one's plane the other's corners lie on, then,
    where that does not already rule it out, each side against the other
    triangle."""
    of_b = np.stack([_sides(a, na, b[:, k]) for k in range(3)], axis=1)
    spread = (of_b.max(axis=1) > 0) & (of_b.min(axis=1) < 0)
    rows = np.flatnonzero(spread)
    of_a = np.stack([_sides(b[rows], nb[rows], a[rows, k]) for k in range(3)], axis=1)
    spread = (of_a.max(axis=1) > 0) & (of_a.min(axis=1) < 0)
    rows, of_a = rows[spread], of_a[spread]
    crossing = np.zeros(len(a), bool)
    a, b, of_b = a[rows], b[rows], of_b[rows]
    for one, other, sides in ((a, b, of_a), (b, a, of_b)):
        for k in range(3):
            j = (k + 1) % 3
            p, q = one[:, k], one[:, j]
            across = sides[:, k] * sides[:, j] < 0
            s1 = _orient(p, q, other[:, 0], other[:, 1])
            s2 = _orient(p, q, other[:, 1], other[:, 2])
            s3 = _orient(p, q, other[:, 2], other[:, 0])
            crossing[rows] |= across & (s1 == s2) & (s2 == s3) & (s1 != 0)
    return crossing


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
    """Pairs of triangles with no side in common where a side of one passes
    through the inside of the other (two with a corner in common cross where
    the ring of triangles around it folds over); the candidates are tested a piece at a
    time (a surface of 200,000 triangles needs about 80 MB, of 770,000 about
    400 MB, as much as the smoothing that made it)."""
    corners = positions[triangles]
    lo, hi = corners.min(axis=1), corners.max(axis=1)
    normal = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    found = [np.zeros((0, 2), np.int64)]
    if len(triangles) < 2:
        return found[0]
    for pairs in _meeting(lo, hi):
        first, second = triangles[pairs[:, 0]], triangles[pairs[:, 1]]
        pairs = pairs[(first[:, :, None] == second[:, None, :]).sum(axis=(1, 2)) < 2]
        first, second = pairs[:, 0], pairs[:, 1]
        found.append(pairs[_crossing(corners[first], corners[second], normal[first],
                                     normal[second])])
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
        length = np.linalg.norm(normal, axis=1)
        normal /= np.maximum(length, 1e-300)[:, None]
        # only crossings where a corner could move are looked at: those of
        # corners that may not move, or too deep, must not hide them
        could = np.zeros(len(pairs), bool)
        for one, other in ((0, 1), (1, 0)):
            corners = triangles[pairs[:, one]]
            side = np.einsum("ijk,ik->ij", positions[corners] - p[pairs[:, other], :1],
                             normal[pairs[:, other]])
            could |= (movable[corners] & (side != 0) & (np.abs(side) <= reach)).any(axis=1)
        pairs = pairs[could & (length[pairs[:, 0]] > 0) & (length[pairs[:, 1]] > 0)]
        if not len(pairs):
            break
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

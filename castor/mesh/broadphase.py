"""The broad phase: which solids' boxes meet, before any boolean.

Operands whose boxes do not meet are never sent to the engine (their union
is the list of both); those that meet are found on a grid of cells, in a few
array operations for 200,000 boxes.
"""

from __future__ import annotations

import numpy as np

from castor.mesh.arrays import components, unique


def apart(a: np.ndarray, b: np.ndarray) -> bool:
    """Boxes with no common interior (touching counts as apart)."""
    return bool(np.any(np.maximum(a[0], b[0]) >= np.minimum(a[1], b[1])))


# Boxes closer than this, relative to the size of their coordinates, meet:
# faces that coincide on paper but differ by rounding (1.18 + 1 and 0.18 + 2)
# are one plane for the sheets' test (castor.mesh.sheets), so the solids
# must reach it together, or the sheet between them stays.
TOUCH = 1e-7


def _median(values: np.ndarray) -> np.ndarray:
    """np.median(values, axis=0), the same numbers (the middle one, or the mean of
    the middle two), without numpy.ma, which np.median imports (10-20 ms)."""
    count = len(values)
    middle = count // 2
    if count % 2:
        return np.partition(values, middle, axis=0)[middle]
    ordered = np.partition(values, (middle - 1, middle), axis=0)
    return (ordered[middle - 1] + ordered[middle]) / 2


def overlap_groups(boxes: np.ndarray) -> list[list[int]]:
    """Groups of operands whose boxes meet (touching counts, and so do boxes
    apart by less than TOUCH of the scene's size).

    Boxes go into the cells of a grid twice as large as a typical box; only boxes
    sharing a cell can meet, so a union of 200,000 cubes that do not meet is a
    few array operations, not a sweep in Python. A box over very many cells is
    compared with all the others at once."""
    n = len(boxes)
    slack = TOUCH * max(1.0, float(np.abs(boxes).max())) if n else 0.0
    lo, hi = boxes[:, 0, :] - slack, boxes[:, 1, :] + slack
    extent = hi - lo
    cell = np.maximum(2 * _median(extent), 1e-300)
    cell = np.where(cell > 0, cell, np.maximum(extent.max(axis=0), 1.0))
    first = np.floor(lo / cell).astype(np.int64)
    last = np.floor(hi / cell).astype(np.int64)
    span = last - first + 1
    cells = np.prod(span, axis=1)
    big = cells > 64
    pairs = []
    small = np.flatnonzero(~big)
    if len(small):
        # one entry per (box, cell it covers)
        counts = cells[small]
        owner = np.repeat(small, counts)
        k = np.arange(len(owner)) - np.repeat(np.cumsum(counts) - counts, counts)
        sx, sy = span[owner, 0], span[owner, 1]
        cx = first[owner, 0] + k % sx
        cy = first[owner, 1] + (k // sx) % sy
        cz = first[owner, 2] + k // (sx * sy)
        cx, cy, cz = cx - cx.min(), cy - cy.min(), cz - cz.min()
        key = (cx * (int(cy.max()) + 1) + cy) * (int(cz.max()) + 1) + cz
        order = np.argsort(key, kind="stable")
        key, owner = key[order], owner[order]
        starts = np.flatnonzero(np.r_[True, key[1:] != key[:-1]])
        sizes = np.diff(np.r_[starts, len(key)])
        for size in unique(sizes[sizes > 1]).tolist():
            members = owner[starts[sizes == size][:, None] + np.arange(size)]
            a, b = np.triu_indices(size, 1)
            pairs.append(np.stack([members[:, a].ravel(), members[:, b].ravel()], axis=1))
    for i in np.flatnonzero(big).tolist():
        others = np.arange(n)
        pairs.append(np.stack([np.full(n, i), others], axis=1)[others != i])
    label = np.arange(n)
    if pairs:
        pairs = np.sort(np.concatenate(pairs), axis=1)
        # each pair once, in the order of its rows (np.unique(axis=0)'s, a sort
        # of the rows as records, was most of the broad phase at 1,024 houses)
        keys = unique(pairs[:, 0] * n + pairs[:, 1])
        a, b = keys // n, keys % n
        meet = np.all((lo[a] <= hi[b]) & (lo[b] <= hi[a]), axis=1)
        a, b = a[meet], b[meet]
        label = components(n, a, b)
    order = np.argsort(label, kind="stable")
    bounds = np.flatnonzero(np.diff(label[order])) + 1
    return [group.tolist() for group in np.split(order, bounds)]


def meeting_boxes(first: np.ndarray, second: np.ndarray, eps: float,
                  chunk: int = 1 << 21) -> np.ndarray:
    """The pairs (i, j), in order, of 2D boxes (rows x0, y0, x1, y1) first[i]
    and second[j] whose interiors overlap by more than eps along both axes:
    ``a0 < b1 - eps``, ``b0 < a1 - eps`` along x and along y, exactly as a
    test of every pair would find them.

    The candidates are the pairs whose intervals meet along one axis (the
    one where fewer do), found by sorting: the cost is about the number of
    boxes and of candidates, not their product (a plane of 14,000 triangles
    against 7,000, where none meets, was 98 million tests and 400 MB)."""
    none = np.zeros((0, 2), np.int64)
    if not len(first) or not len(second):
        return none
    best = None
    for axis in (0, 1):
        ranges = _meeting_along(first[:, axis], first[:, axis + 2] - eps,
                                second[:, axis], second[:, axis + 2] - eps)
        count = sum(int(np.maximum(end - start, 0).sum()) for _, start, end, _, _ in ranges)
        if best is None or count < best[0]:
            best = (count, ranges)
    a, b = first, second
    found = []
    for owner, start, end, order, owner_is_first in best[1]:
        sizes = np.maximum(end - start, 0)
        ends = np.cumsum(sizes)
        begin = 0
        while begin < len(owner):  # at most about ``chunk`` candidates at a time
            stop = max(int(np.searchsorted(ends, (ends[begin] - sizes[begin]) + chunk, "right")),
                       begin + 1)
            n = sizes[begin:stop]
            rows = np.repeat(owner[begin:stop], n)
            offsets = np.arange(int(n.sum())) - np.repeat(np.cumsum(n) - n, n)
            others = order[np.repeat(start[begin:stop], n) + offsets]
            i, j = (rows, others) if owner_is_first else (others, rows)
            meet = ((a[i, 0] < b[j, 2] - eps) & (b[j, 0] < a[i, 2] - eps)
                    & (a[i, 1] < b[j, 3] - eps) & (b[j, 1] < a[i, 3] - eps))
            found.append(np.stack([i[meet], j[meet]], axis=1))
            begin = stop
    pairs = np.concatenate(found) if found else none
    return pairs[np.lexsort((pairs[:, 1], pairs[:, 0]))]


def _meeting_along(low_a, high_a, low_b, high_b) -> list:
    """The pairs whose intervals meet along one axis (``low_a < high_b`` and
    ``low_b < high_a``), as ranges of a sorted order: those where b starts
    within a (low_a <= low_b < high_a), then those where a starts within b
    (low_b < low_a < high_b). Each range: (owners, starts, ends, the sorted
    order the range indexes, whether the owners are of the first boxes)."""
    order_b = np.argsort(low_b, kind="stable")
    sorted_b = low_b[order_b]
    order_a = np.argsort(low_a, kind="stable")
    sorted_a = low_a[order_a]
    return [(np.arange(len(low_a)), np.searchsorted(sorted_b, low_a, "left"),
             np.searchsorted(sorted_b, high_a, "left"), order_b, True),
            (np.arange(len(low_b)), np.searchsorted(sorted_a, low_b, "right"),
             np.searchsorted(sorted_a, high_b, "left"), order_a, False)]

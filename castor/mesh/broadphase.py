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

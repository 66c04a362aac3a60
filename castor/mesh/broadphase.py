"""The broad phase: which solids' boxes meet, before any boolean.

Operands whose boxes do not meet are never sent to the engine (their union
is the list of both); those that meet are found on a grid of cells, in a few
array operations for 200,000 boxes.
"""

from __future__ import annotations

import numpy as np

from castor.mesh.arrays import components


def apart(a: np.ndarray, b: np.ndarray) -> bool:
    """Boxes with no common interior (touching counts as apart)."""
    return bool(np.any(np.maximum(a[0], b[0]) >= np.minimum(a[1], b[1])))


def overlap_groups(boxes: np.ndarray) -> list[list[int]]:
    """Groups of operands whose boxes meet (touching counts).

    Boxes go into the cells of a grid twice as large as a typical box; only boxes
    sharing a cell can meet, so a union of 200,000 cubes that do not meet is a
    few array operations, not a sweep in Python. A box over very many cells is
    compared with all the others at once."""
    n = len(boxes)
    lo, hi = boxes[:, 0, :], boxes[:, 1, :]
    extent = hi - lo
    cell = np.maximum(2 * np.median(extent, axis=0), 1e-300)
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
        for size in np.unique(sizes[sizes > 1]).tolist():
            members = owner[starts[sizes == size][:, None] + np.arange(size)]
            a, b = np.triu_indices(size, 1)
            pairs.append(np.stack([members[:, a].ravel(), members[:, b].ravel()], axis=1))
    for i in np.flatnonzero(big).tolist():
        others = np.arange(n)
        pairs.append(np.stack([np.full(n, i), others], axis=1)[others != i])
    label = np.arange(n)
    if pairs:
        pairs = np.unique(np.sort(np.concatenate(pairs), axis=1), axis=0)
        a, b = pairs[:, 0], pairs[:, 1]
        meet = np.all((lo[a] <= hi[b]) & (lo[b] <= hi[a]), axis=1)
        a, b = a[meet], b[meet]
        label = components(n, a, b)
    order = np.argsort(label, kind="stable")
    bounds = np.flatnonzero(np.diff(label[order])) + 1
    return [group.tolist() for group in np.split(order, bounds)]

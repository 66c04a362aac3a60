"""The array kit the mesh modules share: small vectorized helpers over rows
of numbers (hashes, groups, connected components), over triangles (edges
paired) and over convex polygons (fans of triangles). No geometry of its own:
no module of castor.mesh is imported here.
"""

from __future__ import annotations

import numpy as np


def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Row-wise cross product (numpy's np.cross is several times slower)."""
    out = np.empty(np.broadcast_shapes(a.shape, b.shape))
    out[..., 0] = a[..., 1] * b[..., 2] - a[..., 2] * b[..., 1]
    out[..., 1] = a[..., 2] * b[..., 0] - a[..., 0] * b[..., 2]
    out[..., 2] = a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]
    return out


def norm(a: np.ndarray) -> np.ndarray:
    """Row-wise length."""
    return np.sqrt(np.einsum("...j,...j->...", a, a))


def fan_triangles(offsets: np.ndarray, indices: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Each convex polygon as a fan of triangles; also the polygon of each triangle."""
    sizes = np.diff(offsets)
    per = np.maximum(sizes - 2, 0)
    polygon = np.repeat(np.arange(len(sizes)), per)
    first = offsets[:-1][polygon]
    k = np.arange(len(polygon)) - np.repeat(np.cumsum(per) - per, per)
    tris = np.column_stack([indices[first], indices[first + k + 1], indices[first + k + 2]])
    return tris, polygon


def row_hash(columns: np.ndarray) -> np.ndarray:
    """One number per row of integer columns (a multiplicative hash, wrapping):
    equal rows get equal numbers, so one sort finds them; two rows that share a
    number by chance are told apart by whoever needs them apart."""
    with np.errstate(over="ignore", invalid="ignore"):  # (casting huge rounded values too)
        columns = columns.astype(np.int64, copy=False)
        key = columns[:, 0] * np.int64(-7046029254386353131)
        for column in columns[:, 1:].T:
            key = key * np.int64(-4658895280553007687) + column
    return key


def shared_across(key: np.ndarray, owner: np.ndarray) -> bool:
    """Whether two owners have one key."""
    order = np.argsort(key, kind="stable")
    key, owner = key[order], owner[order]
    return bool(np.any((key[1:] == key[:-1]) & (owner[1:] != owner[:-1])))


def largest_of_each(area: np.ndarray, group: np.ndarray) -> np.ndarray:
    """For each group number, its member of largest area (the first of them,
    if several); -1 for a number no member has."""
    largest = np.full(int(group.max()) + 1, -1.0)
    np.maximum.at(largest, group, area)
    best = np.flatnonzero(area == largest[group])[::-1]
    first = np.full(len(largest), -1, np.int64)
    first[group[best]] = best
    return first


def same_place(vertices: np.ndarray) -> np.ndarray | None:
    """For each vertex, the first vertex at exactly its place; None if no two
    vertices share a place (the usual case, found with one sort)."""
    if len(vertices) < 2:
        return None
    bits = np.ascontiguousarray(vertices + 0.0).view(np.int64).reshape(-1, 3)  # -0 is 0
    key = row_hash(bits)
    order = np.argsort(key, kind="stable")
    sorted_key = key[order]
    repeated = np.flatnonzero(sorted_key[1:] == sorted_key[:-1])
    if not len(repeated):
        return None
    candidates = np.unique(np.concatenate([order[repeated], order[repeated + 1]]))
    _, first, group = np.unique(bits[candidates], axis=0, return_index=True, return_inverse=True)
    table = np.arange(len(vertices))
    table[candidates] = candidates[first][group.ravel()]
    return table if np.any(table != np.arange(len(vertices))) else None


def plane_sign(normals: np.ndarray) -> np.ndarray:
    """One sign for both sides of each plane (unit normals): that which makes
    its first component not about zero positive. (Not its largest component:
    two as large, as in (-0.61, 0.61, -0.5), are told apart by rounding, and
    the two sides of one plane got different signs.)"""
    significant = np.abs(normals) > 1e-3
    first = np.argmax(significant, axis=1)
    sign = np.sign(normals[np.arange(len(normals)), first])
    sign[sign == 0] = 1
    return sign


def paired(triangles: np.ndarray) -> bool:
    """Whether every edge is used as often one way as the other (closed, oriented)."""
    if len(triangles) == 0:
        return True
    a = triangles.ravel()
    b = np.roll(triangles, -1, axis=1).ravel()
    n = int(triangles.max()) + 1
    forward, fc = np.unique(a * n + b, return_counts=True)
    backward, bc = np.unique(b * n + a, return_counts=True)
    return len(forward) == len(backward) and bool(np.all(forward == backward) and np.all(fc == bc))


def unique(values: np.ndarray) -> np.ndarray:
    """np.unique(values) of integers: each value once, in order. np.unique alone
    (no counts, no indices) imports numpy.ma (10-20 ms of a run's start)."""
    ordered = np.sort(values, axis=None)
    keep = np.empty(len(ordered), dtype=bool)
    keep[:1] = True
    np.not_equal(ordered[1:], ordered[:-1], out=keep[1:])
    return ordered[keep]


def components(count: int, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """For ``count`` items joined in pairs (a[i], b[i]), the label of each item's
    connected group (its smallest member), by label propagation with pointer
    jumping: array operations, no Python loop over the items."""
    label = np.arange(count)
    while len(a):  # hook each root to the smallest label it meets, then jump
        la, lb = label[a], label[b]
        low = np.minimum(la, lb)
        np.minimum.at(label, la, low)
        np.minimum.at(label, lb, low)
        while True:
            jumped = label[label]
            if np.array_equal(jumped, label):
                break
            label = jumped
        if np.array_equal(label[a], label[b]):
            break
    return label


def digest(*arrays) -> bytes:
    """A 16-byte content key of arrays (their bytes in order): what the caches
    of parts, faces and planes that did not change are looked up by."""
    try:  # hashlib's own BLAKE2, without hashlib's 16 ms of OpenSSL set-up at start
        from _blake2 import blake2b
    except ImportError:
        from hashlib import blake2b

    hashed = blake2b(digest_size=16)
    for array in arrays:
        hashed.update(np.ascontiguousarray(array).data)
    return hashed.digest()

"""Flat triangles and coincident twins taken out of a closed surface.

The engine's rounding leaves a few triangles of (about) zero area, and where
two faces coincide turned towards each other, pairs of triangles on the same
three vertices: both are no part of a regular solid (LANGUAGE.md §7).
"""

from __future__ import annotations

import numpy as np

from castor.mesh.arrays import cross, same_place

# A triangle whose height is at most this fraction of its longest side is
# flat. Its plane is then no better known than its coordinates' rounding
# (about 1e-16 of their size) over that fraction: below about 1e-9 a needle
# the engine leaves among coplanar faces (a turned row of cubes: two
# corners 9e-9 apart, 5e-11 high over 0.06) is no plane at all, written as a
# polygon of its own. (1e-8 flipped triangles that are faces, a few 1e-9
# high, across edges of the solid: wide oracle, seed 22.)
_FLAT = 1e-9


def flat_triangles(vertices: np.ndarray, triangles: np.ndarray, chunk: int = 1 << 20) -> np.ndarray:
    """Which triangles have (about) zero area: a repeated vertex, or three in a line."""
    flat = np.zeros(len(triangles), bool)
    for start in range(0, len(triangles), chunk):  # in slices: a few temporaries of 3 x chunk
        t = triangles[start:start + chunk]
        p = vertices[t]
        e0, e1, e2 = p[:, 1] - p[:, 0], p[:, 2] - p[:, 1], p[:, 0] - p[:, 2]
        normal = cross(e0, -e2)
        twice_area_squared = np.einsum("ij,ij->i", normal, normal)
        longest_squared = np.maximum(np.maximum(np.einsum("ij,ij->i", e0, e0),
                                                np.einsum("ij,ij->i", e1, e1)),
                                     np.einsum("ij,ij->i", e2, e2))
        flat[start:start + chunk] = (twice_area_squared <= (_FLAT * longest_squared) ** 2) | (
            (t[:, 0] == t[:, 1]) | (t[:, 1] == t[:, 2]) | (t[:, 2] == t[:, 0]))
    return flat


def without_flat_triangles(vertices: np.ndarray, triangles: np.ndarray, origin_ids: np.ndarray,
                           face_ids: np.ndarray, twins: bool = True):
    """The same closed surface with no flat triangle (LANGUAGE.md §7).

    The engine leaves a few: two vertices at one place, or closer than the
    rounding of the triangle's size (welded into one, and the triangles
    between them dropped), or three in a line (the triangle's
    long edge is flipped with the neighbour across it, which splits the
    neighbour at the middle vertex: the flat triangle's area, zero, goes to a
    triangle in the neighbour's plane). Every edge stays paired. Returns the
    arrays unchanged if there is nothing to do.
    """
    flat = flat_triangles(vertices, triangles)
    if twins:  # (False where no two faces can coincide)
        triangles, origin_ids, face_ids, flat = _without_twins_at_one_place(
            vertices, triangles, origin_ids, face_ids, flat)
    twins = _coincident(triangles) if twins else None
    if twins is not None:  # a sheet of coincident triangles turned towards each other
        keep = ~twins
        triangles, origin_ids, face_ids = triangles[keep], origin_ids[keep], face_ids[keep]
        flat = flat[keep]
    if not flat.any():
        return triangles, origin_ids, face_ids
    triangles = triangles.copy()
    # weld the vertices of flat triangles that are at one place, or closer
    # than rounding: needles, and fins of two flat triangles back to back.
    # Closer than _FLAT of the scene's size is rounding: a triangle with such
    # an edge and any other edge up to the scene's size is flat by the test
    # above (rotated copies of a solid, cut again and again, leave clusters
    # of vertices a few 1e-12 apart that stand for one point)
    corners = np.unique(triangles[flat])
    points = vertices[corners]
    scale = max(1.0, float(np.abs(points).max()))
    remap = {}
    for i in range(len(corners)):
        close = np.flatnonzero(np.abs(points[i + 1:] - points[i]).max(axis=1) <= _FLAT * scale)
        for j in close.tolist():
            u, w = int(corners[i]), int(corners[i + 1 + j])
            ru, rw = remap.get(u, u), remap.get(w, w)
            if ru != rw:
                remap[max(ru, rw)] = min(ru, rw)
    if remap:
        table = np.arange(len(vertices))
        for u in sorted(remap):  # chains resolve to their smallest number
            table[u] = table[remap[u]]
        triangles = table[triangles]
    keep = ~((triangles[:, 0] == triangles[:, 1]) | (triangles[:, 1] == triangles[:, 2])
             | (triangles[:, 2] == triangles[:, 0]))
    keep &= ~_twins(triangles, corners)
    triangles, origin_ids, face_ids = triangles[keep], origin_ids[keep], face_ids[keep]
    flat = flat_triangles(vertices, triangles)
    if flat.any():
        triangles, origin_ids, face_ids = _flip_flat(vertices, triangles, origin_ids,
                                                     face_ids, flat)
    return triangles, origin_ids, face_ids


def _without_twins_at_one_place(vertices, triangles, origin_ids, face_ids, flat):
    """Triangles that would be coincident twins turned the other way, but for
    a vertex the engine left twice at one place: both go, and those vertices
    are welded (the sheet they made is gone, and the surface closes there)."""
    table = same_place(vertices)
    if table is None:
        return triangles, origin_ids, face_ids, flat
    twins = _coincident(table[triangles])
    if twins is None:
        return triangles, origin_ids, face_ids, flat
    involved = np.isin(table, table[np.unique(triangles[twins])])
    weld = np.where(involved, table, np.arange(len(vertices)))
    keep = ~twins
    return weld[triangles[keep]], origin_ids[keep], face_ids[keep], flat[keep]


def _coincident(triangles: np.ndarray) -> np.ndarray | None:
    """Triangles whose three vertices another triangle has, turned the other
    way (None if there is none: the usual case, found in a few array passes)."""
    if len(triangles) < 2:
        return None
    t = triangles
    n = int(t.max()) + 1
    if n ** 3 >= 2 ** 62:
        return None
    # a triangle and its twin have the same corners: look for a repeated set
    # first (one sort), the usual case being that there is none
    low, high = t.min(axis=1), t.max(axis=1)
    middle = t.sum(axis=1) - low - high
    same = np.sort((low * n + middle) * n + high)
    if not (same[1:] == same[:-1]).any():
        return None
    first = np.argmin(t, axis=1)[:, None]
    rows = np.arange(len(t))[:, None]
    forward = t[rows, (first + np.arange(3)) % 3]  # each turn from its smallest vertex
    backward = forward[:, [0, 2, 1]]
    key_f = (forward[:, 0] * n + forward[:, 1]) * n + forward[:, 2]
    key_b = (backward[:, 0] * n + backward[:, 1]) * n + backward[:, 2]
    hit = np.isin(key_f, key_b)
    if not hit.any():
        return None
    # pair them one to one, so every edge keeps its partner
    found = np.zeros(len(t), bool)
    waiting: dict[int, list[int]] = {}
    for i in np.flatnonzero(hit).tolist():
        partners = waiting.get(int(key_b[i]))
        if partners:
            found[partners.pop()] = True
            found[i] = True
        else:
            waiting.setdefault(int(key_f[i]), []).append(i)
    return found if found.any() else None


def _twins(triangles: np.ndarray, corners: np.ndarray) -> np.ndarray:
    """Triangles near ``corners`` paired with another of the same three
    vertices turned the other way: a sheet of zero thickness, both go."""
    near = np.flatnonzero(np.isin(triangles, corners).any(axis=1))
    found = np.zeros(len(triangles), bool)
    seen: dict[tuple, list[int]] = {}
    for i in near.tolist():
        a, b, c = triangles[i].tolist()
        k = min((a, b, c), (b, c, a), (c, a, b))  # this turn, from its smallest vertex
        reverse = min((a, c, b), (c, b, a), (b, a, c))
        partners = seen.get(reverse)
        if partners:
            found[partners.pop()] = True
            found[i] = True
        else:
            seen.setdefault(k, []).append(i)
    return found


def _flip_flat(vertices, triangles, origin_ids, face_ids, flat):
    """Flip the long edge of each triangle with three vertices in a line;
    where flipping leaves flat twins (two flat triangles on the same three
    vertices, turned against each other: a closed fin of no area, which the
    flips of a run of flat triangles along one edge can make), both go and
    the rest is flipped again, while each pass leaves fewer. A flat triangle
    that every flip leaves flat (its middle corner and a neighbour's both in
    line with it) loses its shortest edge instead (``_collapsed``)."""
    left = int(flat.sum())
    for _ in range(8):
        triangles, origin_ids, face_ids = _flipped(vertices, triangles, origin_ids, face_ids, flat)
        flat = flat_triangles(vertices, triangles)
        if not flat.any():
            break
        twins = _coincident(triangles[flat])
        if twins is None:
            if flat.sum() >= left:
                collapsed = _collapsed(vertices, triangles, flat)
                if collapsed is None:
                    break
                triangles, origin_ids, face_ids = (collapsed[0], origin_ids[collapsed[1]],
                                                   face_ids[collapsed[1]])
                flat = flat_triangles(vertices, triangles)
                if not flat.any():
                    break
            left = int(flat.sum())
            continue
        keep = np.ones(len(triangles), bool)
        keep[np.flatnonzero(flat)[twins]] = False
        triangles, origin_ids, face_ids = triangles[keep], origin_ids[keep], face_ids[keep]
        flat = flat[keep]
        if not flat.any():
            break
    return triangles, origin_ids, face_ids


def _collapsed(vertices, triangles, flat):
    """The surface with the shortest edge of flat triangles collapsed, where
    that changes nothing but the triangulation: the vertex that goes is
    moved onto the other end, every triangle around it lies in one plane
    (so the surface stays where it was: the engine leaves such vertices a
    rounding apart inside a face, 1.6e-5 apart in a turned row of cubes),
    the two ends have no other common neighbour than the corners across
    the edge (so the surface stays a 2-manifold), and no triangle turns
    over. Where neither end of the shortest edge can go, the third corner of
    the triangle across it, if as close, goes onto one of them. Returns
    (triangles, the rows kept), or None if no edge could go."""
    triangles = triangles.copy()
    keep = np.ones(len(triangles), bool)
    corners = np.unique(triangles[flat])
    near = np.flatnonzero(np.isin(triangles, corners).any(axis=1))
    around: dict[int, set[int]] = {}
    for i in near.tolist():
        for v in triangles[i].tolist():
            around.setdefault(v, set()).add(i)
    scale = max(1.0, float(np.abs(vertices[corners]).max()))
    done = False
    for i in np.flatnonzero(flat).tolist():
        if not keep[i]:
            continue
        t = triangles[i].tolist()
        p = vertices[t]
        lengths = [float(np.dot(p[(k + 1) % 3] - p[k], p[(k + 1) % 3] - p[k])) for k in range(3)]
        k = int(np.argmin(lengths))
        a, b = t[k], t[(k + 1) % 3]
        moves = [(b, a), (a, b)]
        # where neither end can go (a neighbour would turn over), the third
        # corner of the triangle across the short edge may, if it is as close
        # to both: a cluster of three points inside a face (a flattened turned
        # row of cubes, wide oracle seed 32: 1.9e-7 apart beside a needle
        # 0.3 long); the flat triangle loses its short edge on the next pass
        across = [j for j in around.get(a, ()) & around.get(b, ()) if keep[j] and j != i]
        if len(across) == 1:
            c = next(int(x) for x in triangles[across[0]] if x != a and x != b)
            if max(float(np.dot(vertices[c] - vertices[e], vertices[c] - vertices[e]))
                   for e in (a, b)) <= 4 * lengths[k]:
                moves += [(c, a), (c, b)]
                # (c's own ring, in full: it need not be a flat triangle's corner)
                around[c] = {int(j) for j in np.flatnonzero((triangles == c).any(axis=1))
                             if keep[j]}
        for gone, stays in moves:
            if _collapse(vertices, triangles, keep, around, gone, stays, scale):
                done = True
                break
    if not done:
        return None
    rows = np.flatnonzero(keep)
    return triangles[rows], rows


def _collapse(vertices, triangles, keep, around, gone, stays, scale) -> bool:
    """Collapse the edge (gone, stays) onto ``stays``, if it changes nothing
    but the triangulation (see _collapsed)."""
    ring = [j for j in around.get(gone, ()) if keep[j]]
    if not ring:
        return False
    shared = [j for j in ring if stays in triangles[j]]
    if len(shared) != 2:
        return False
    tips = {int(x) for j in shared for x in triangles[j] if x != gone and x != stays}
    neighbours_gone = {int(x) for j in ring for x in triangles[j]} - {gone}
    neighbours_stays = {int(x) for j in around.get(stays, ()) if keep[j]
                        for x in triangles[j]} - {stays}
    if (neighbours_gone & neighbours_stays) != tips:
        return False
    # every triangle around ``gone`` in one plane: that of the largest
    p = vertices[triangles[ring]]
    normals = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    areas = np.linalg.norm(normals, axis=1)
    unit = normals[int(np.argmax(areas))] / max(float(areas.max()), 1e-300)
    offset = float(unit @ vertices[stays])
    if np.abs(p.reshape(-1, 3) @ unit - offset).max() > 1e-9 * scale:
        return False
    moved = [j for j in ring if j not in shared]
    after = triangles[moved].copy()
    after[after == gone] = stays
    q = vertices[after]
    turned = np.cross(q[:, 1] - q[:, 0], q[:, 2] - q[:, 0]) @ unit
    if np.any(turned <= 0) or flat_triangles(vertices, after).any():
        return False
    triangles[moved] = after
    for j in shared:
        keep[j] = False
    for j in moved:
        around.setdefault(stays, set()).add(j)
    around[gone] = set()
    return True


def _flipped(vertices, triangles, origin_ids, face_ids, flat):
    """One pass of flips of the long edges of flat triangles. A flat
    triangle whose neighbour across its long edge is flat too, with another
    long edge, waits for that neighbour's flip (else the two flips only
    move the flat triangles along the line)."""
    corners = np.unique(triangles[flat])
    near = np.flatnonzero(np.isin(triangles, corners).any(axis=1))
    tris = {int(i): tuple(triangles[i].tolist()) for i in near}
    owner = {}
    for i, (a, b, c) in tris.items():
        owner[(a, b)] = owner[(b, c)] = owner[(c, a)] = i
    origin = origin_ids.copy()
    face = face_ids.copy()
    todo = [int(i) for i in np.flatnonzero(flat)]
    point = vertices
    deferred, waiting = 0, set()
    for _ in range(4 * len(todo) + 16):
        if not todo:
            break
        i = todo.pop()
        t = tris.get(i)
        if t is None or not flat_triangles(point, np.array([t]))[0]:
            continue  # (a flip since it was found may have made it whole)
        p = point[list(t)]
        lengths = [float(np.dot(p[(k + 1) % 3] - p[k], p[(k + 1) % 3] - p[k])) for k in range(3)]
        k = int(np.argmax(lengths))
        u, w, m = t[k], t[(k + 1) % 3], t[(k + 2) % 3]  # long edge u->w, m between them
        n = owner.get((w, u))
        if n is None or n == i:
            continue
        a, b, c = tris[n]
        x = ({a, b, c} - {u, w}).pop() if len({a, b, c} - {u, w}) == 1 else None
        if x is None or x == m:
            continue
        if deferred < len(todo) + 16 and n not in waiting and _long_edge_elsewhere(
                point, tris[n], u, w):
            # the neighbour is flat with its long edge elsewhere: it goes first
            deferred += 1
            waiting.add(i)
            todo.insert(0, i)
            todo.append(n)
            continue
        first, second = (m, u, x), (w, m, x)
        if _turns_over(point, tris[n], first, second):
            continue
        waiting.discard(i)
        for tri in (t, tris[n]):
            for e in ((tri[0], tri[1]), (tri[1], tri[2]), (tri[2], tri[0])):
                owner.pop(e, None)
        tris[i], tris[n] = first, second
        origin[i], face[i] = origin[n], face[n]
        for j, tri in ((i, first), (n, second)):
            for e in ((tri[0], tri[1]), (tri[1], tri[2]), (tri[2], tri[0])):
                owner[e] = j
            if flat_triangles(point, np.array([tri]))[0]:
                todo.append(j)
    rows = np.array(list(tris.keys()), np.int64)
    triangles = triangles.copy()
    triangles[rows] = np.array([tris[r] for r in rows.tolist()], np.int64)
    return triangles, origin, face


def _turns_over(point, neighbour, first, second) -> bool:
    """Whether a flip would turn a triangle over: the flat triangle's area
    is none, so the two triangles it makes with its neighbour face as the
    neighbour does, unless its middle corner is off the line by more than
    the neighbour can take (across an edge of the solid, a corner a little
    off it puts a new triangle on its other side)."""
    if flat_triangles(point, np.array([neighbour]))[0]:
        return False  # (a run of flat triangles along one line: no side to keep)
    p = point[list(neighbour)]
    facing = np.cross(p[1] - p[0], p[2] - p[0])
    for tri in (first, second):
        q = point[list(tri)]
        if float(np.cross(q[1] - q[0], q[2] - q[0]) @ facing) <= 0:
            return True
    return False


def _long_edge_elsewhere(point, tri, u, w) -> bool:
    """Whether the triangle ``tri``, which has the edge (w, u), is flat and
    its longest edge is another."""
    if not flat_triangles(point, np.array([tri]))[0]:
        return False
    p = point[list(tri)]
    lengths = [float(np.dot(p[(k + 1) % 3] - p[k], p[(k + 1) % 3] - p[k])) for k in range(3)]
    k = int(np.argmax(lengths))
    return {tri[k], tri[(k + 1) % 3]} != {u, w}

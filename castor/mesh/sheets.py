"""Sheets cut out of a solid's triangles: where triangles of one plane turned
one way overlap triangles turned the other way (a fold, or an inner sheet the
engine left where faces only touch), the overlap is taken out of both, with a
2D clipper of convex pieces in that plane.
"""

from __future__ import annotations

import heapq
import math

import numpy as np

from castor.mesh.arrays import cross, digest, largest_of_each, norm, plane_sign
from castor.mesh.broadphase import meeting_boxes
from castor.mesh.caches import PROCESS
from castor.mesh.seams import keys_in, welded_seams, without_t_junctions


def without_sheets(vertices: np.ndarray, triangles: np.ndarray, origin_ids: np.ndarray,
                   face_ids: np.ndarray):
    """The same solid with no sheet: where triangles of one plane turned one way
    overlap triangles turned the other way (a fold or an inner sheet that the
    engine left where faces only touch), the overlap is taken out of both, as
    regularization requires (LANGUAGE.md §7).

    In each such plane, each triangle keeps what the opposite triangles do not
    cover (convex pieces, cut along their edges); the points where the cuts
    meet the edges are put into every triangle along those edges, so that no
    T-junction is left. Returns the arrays unchanged when there is no sheet,
    which is found with a few array passes.
    """
    if len(triangles) < 2:
        return vertices, triangles, origin_ids, face_ids
    planes = _opposed_planes(vertices, triangles, face_ids)
    if not planes:
        return vertices, triangles, origin_ids, face_ids
    return _Resolver(vertices, triangles, origin_ids, face_ids).resolve(planes)


def _opposed_planes(vertices, triangles, face_ids,
                    chunk: int = 1 << 20) -> list[tuple[np.ndarray, np.ndarray, np.ndarray]]:
    """Groups of triangles in one plane with both orientations: (plane's unit
    normal, triangle numbers, which of them face along the normal).

    The triangles of one face number lie on one flat face of a primitive, so
    a plane is found per face, from its largest triangle (a sliver's normal is
    mostly rounding). Faces whose planes agree to 1e-7 (of the scene's size)
    are one plane: faces that coincide on paper but differ by rounding."""
    scale = max(1.0, float(np.abs(vertices).max()))
    normals, areas = [], []
    for start in range(0, len(triangles), chunk):
        t = triangles[start:start + chunk]
        p0 = vertices[t[:, 0]]
        n = cross(vertices[t[:, 1]] - p0, vertices[t[:, 2]] - p0)
        normals.append(n)
        areas.append(norm(n))
    n = np.concatenate(normals) if len(normals) > 1 else normals[0]
    area = np.concatenate(areas) if len(areas) > 1 else areas[0]
    _, face = np.unique(face_ids, return_inverse=True)
    face = face.ravel()
    first = largest_of_each(area, face)  # each face's largest triangle (every face has one)
    big_area = area[first]
    u = n[first] / np.where(big_area > 0, big_area, 1.0)[:, None]
    d = np.einsum("ij,ij->i", u, vertices[triangles[first]].mean(axis=1))
    sign = plane_sign(u)
    u = u * sign[:, None]
    d = d * sign
    key = np.column_stack([np.round(u * 1e7), np.round(d / scale * 1e7)]).astype(np.int64)
    solid_face = big_area > 1e-14 * scale * scale  # a face of only flat triangles has no plane
    key_order = np.lexsort(key.T[::-1])
    key_order = key_order[solid_face[key_order]]
    if len(key_order) < 2:
        return []
    k = key[key_order]
    starts = np.flatnonzero(np.r_[True, np.any(k[1:] != k[:-1], axis=1)])
    ends = np.r_[starts[1:], len(k)]
    # each triangle's own side: one face number can hold both (two uses of one
    # primitive at one place, inside results of the engine; or a fold of the
    # engine's, whose small triangles lie turned against their face's large
    # one). A triangle is turned if its own normal points against the face's
    # (by more than 60 degrees): measured against its own area, not the face's
    # largest triangle's, so that a small one of 1e-7 is told as surely as a
    # large one (flat triangles, whose normal is rounding, are gone before)
    facing = np.einsum("ij,ij->i", n, u[face]) * sign[face]
    turned = facing < -0.5 * area
    face_turns = np.zeros(len(first), bool)
    face_turns[face[turned]] = True
    positive = np.add.reduceat((sign[key_order] > 0).astype(np.int64), starts)
    both = np.add.reduceat(face_turns[key_order].astype(np.int64), starts) > 0
    mixed = np.flatnonzero(((positive > 0) & (positive < ends - starts)) | both)
    if not len(mixed):
        return []
    # the triangles of each mixed plane's faces
    plane_of_face = np.full(len(first), -1, np.int64)
    for g in mixed.tolist():
        plane_of_face[key_order[starts[g]:ends[g]]] = g
    plane = plane_of_face[face]
    members = np.flatnonzero(plane >= 0)
    members = members[np.argsort(plane[members], kind="stable")]
    bounds = np.flatnonzero(np.diff(plane[members])) + 1
    out = []
    for group in np.split(members, bounds):
        g = int(plane[group[0]])
        normal = u[key_order[starts[g]]]
        up = (sign[face[group]] > 0) != turned[group]
        out.append((normal, group, up))
    return out


class _Resolver:
    """Takes the overlaps of opposite triangles out of their planes (see without_sheets)."""

    def __init__(self, vertices, triangles, origin_ids, face_ids):
        self.vertices = vertices
        self.triangles = triangles
        self.origin_ids = origin_ids
        self.face_ids = face_ids
        self.scale = max(1.0, float(np.abs(vertices).max()))
        self.eps = 1e-12 * self.scale
        self.new_points: list[np.ndarray] = []
        self.crossings: dict[tuple, int] = {}
        self.on_edge: dict[tuple[int, int], set[int]] = {}
        self.log: _Log | None = None  # what the plane being resolved did (_Log)
        self.flat: dict[int, tuple[float, float]] = {}
        self.lines: dict | None = None  # _lines

    # points: original vertices keep their numbers; new ones follow
    def point(self, v: int) -> np.ndarray:
        n = len(self.vertices)
        if v < n:
            return self.vertices[v]
        if self.log is not None and v < self.log.first:
            self.log.foreign = True  # a point of another plane
        return self.new_points[v - n]

    def resolve(self, planes):
        replaced: dict[int, list[list[int]]] = {}
        for normal, members, up in planes:
            self._plane_again(normal, members, up, replaced)
        if not replaced:
            return self.vertices, self.triangles, self.origin_ids, self.face_ids
        # every triangle along an edge that gained points gets them too
        touched = set(replaced)
        if self.on_edge:
            t = self.triangles
            a = np.minimum(t, np.roll(t, -1, axis=1))
            b = np.maximum(t, np.roll(t, -1, axis=1))
            n = len(self.vertices) + len(self.new_points) + 1
            keys = np.array([i * n + j for i, j in self.on_edge], dtype=np.int64)
            hit = keys_in(a * n + b, keys).any(axis=1)
            touched |= set(np.flatnonzero(hit).tolist())
        rows, origin, face = [], [], []
        for i in sorted(touched):
            outlines = replaced.get(i, [self.triangles[i].tolist()])
            for outline in outlines:
                for tri in self._fan(self._with_edge_points(outline)):
                    rows.append(tri)
                    origin.append(self.origin_ids[i])
                    face.append(self.face_ids[i])
        keep = np.ones(len(self.triangles), bool)
        keep[sorted(touched)] = False
        vertices = (np.vstack([self.vertices, np.array(self.new_points).reshape(-1, 3)])
                    if self.new_points else self.vertices)
        triangles = np.vstack([self.triangles[keep], np.array(rows, np.int64).reshape(-1, 3)])
        triangles = welded_seams(vertices, triangles, self.eps)
        origin_ids = np.concatenate([self.origin_ids[keep], np.array(origin, np.int64)])
        face_ids = np.concatenate([self.face_ids[keep], np.array(face, np.int64)])
        return without_t_junctions(vertices, triangles, origin_ids, face_ids, self.eps)

    # --- a plane resolved in an earlier frame, as it was (caches.PROCESS.planes)

    def _plane_again(self, normal, members, up, replaced):
        """``_plane``, or what it did to a plane with the same triangles (their
        points and numbering, their turn), in the same frame of the same size,
        in an earlier frame: the surfaces a change did not touch are not
        resolved again. What it did is kept only if it did not use what
        another plane had made (a crossing, a point), and given again only if
        it would not have found any made so far (a point within eps, a
        crossing of the same edges); else the plane is resolved here."""
        ids, local = np.unique(self.triangles[members], return_inverse=True)
        key = digest(np.asarray(normal, np.float64), np.asarray(up, bool),
                      local.astype(np.int64), self.vertices[ids],
                      np.array([self.scale], np.float64))
        known = PROCESS.planes.get(key)
        if known is not None and self._replayed(known, ids, members, replaced):
            return
        self.log = _Log(len(self.vertices) + len(self.new_points))
        try:
            self._plane(normal, members, up, replaced)
            done = self.log.record(self, ids, members, replaced)
        finally:
            self.log = None
        if done is not None:
            PROCESS.planes.put(key, done, len(members))

    def _replayed(self, done: "_Done", ids, members, replaced) -> bool:
        first = len(self.vertices) + len(self.new_points)

        def number(v: int) -> int:
            return int(ids[v]) if v >= 0 else first - 1 - v

        crossings = [((tuple(map(number, a)), tuple(map(number, b))), number(v))
                     for (a, b), v in done.crossings]
        if any(key in self.crossings for key, _ in crossings):
            return False
        if len(done.probes) and self.new_points:
            made = np.array(self.new_points).reshape(-1, 3)
            for point in done.probes:
                if (np.abs(made - point).max(axis=1) <= self.eps).any():
                    return False
        self.new_points.extend(done.points)
        for key, vertex in crossings:
            self.crossings[key] = vertex
        for (a, b), vertex in done.on_edge:
            self.on_edge.setdefault((number(a), number(b)), set()).add(number(vertex))
        for k, outlines in done.replaced:
            replaced[int(members[k])] = [[number(v) for v in outline] for outline in outlines]
        return True

    def _plane(self, normal, members, up, replaced):
        # a 2D frame in the plane, turned so that x, y, normal is right-handed
        axis = np.eye(3)[int(np.argmin(np.abs(normal)))]
        e1 = np.cross(normal, axis)
        e1 /= np.linalg.norm(e1)
        e2 = np.cross(normal, e1)
        self.e1, self.e2 = e1, e2
        self.flat: dict[int, tuple[float, float]] = {}  # point -> its (x, y) in this plane
        tiny = 1e-12 * self.scale ** 2
        # every triangle as a convex piece, counter-clockwise in the plane's
        # frame: (vertex, support of the edge that leaves it), and its triangle
        pieces = []  # [piece, triangle, facing up]
        for k, i in enumerate(members.tolist()):
            tri = self.triangles[i].tolist()
            outline = tri if up[k] else tri[::-1]
            pieces.append([[(outline[j], _edge(outline[j], outline[(j + 1) % 3])) for j in range(3)],
                           i, bool(up[k])])
        # Cancel overlaps one up against one down, until no up piece overlaps a
        # down piece: each cancellation takes the common part out of both, once,
        # so where the engine left a face twice over one place and one face
        # of the other side, one layer stays (what is left is the net cover).
        changed_triangles = set()
        cancels = _Cancels(self, pieces, tiny)
        for _ in range(4 * len(pieces) + 16):
            pair = cancels.best()
            if pair is None:
                break
            a, b = cancels.pieces[pair[0]], cancels.pieces[pair[1]]
            cut_a = self._subtract(a[0], b[0])
            cut_b = self._subtract(b[0], a[0])
            changed_triangles.update((a[1], b[1]))
            cancels.remove(pair)
            for q in cut_a:
                cancels.add([q, a[1], a[2]])
            for q in cut_b:
                cancels.add([q, b[1], b[2]])
        # each changed triangle's pieces, in the order they were made (one
        # pass over the pieces, not one per triangle), back to its own turn
        kept: dict[int, list] = {i: [] for i in changed_triangles}
        for piece, triangle, facing in cancels.pieces.values():
            if triangle in kept:
                kept[triangle].append([v for v, _ in (piece if facing else piece[::-1])])
        for i in changed_triangles:
            replaced[i] = kept[i]

    def _xy(self, v):
        """The point's coordinates in the plane's frame, computed once per plane."""
        known = self.flat.get(v)
        if known is None:
            q = self.point(v)
            known = self.flat[v] = (float(q @ self.e1), float(q @ self.e2))
        return known

    def _subtract(self, piece, cutter):
        """Convex pieces of ``piece`` outside the convex piece ``cutter`` (both
        counter-clockwise, as (vertex, support of the edge that leaves it))."""
        out = []
        rest = piece
        for k in range(len(cutter)):
            (a, line), (b, _) = cutter[k], cutter[(k + 1) % len(cutter)]
            outside = self._clip(rest, a, b, keep_left=False, line=line)
            if outside is not None:
                out.append(outside)
            rest = self._clip(rest, a, b, keep_left=True, line=line)
            if rest is None:
                break
        return out

    def _clip(self, poly, a, b, keep_left, line=None):
        """The part of a convex polygon ((vertex, support of the edge that
        leaves it), ...) on one side of the line a->b (whose support is
        ``line``, the edge a-b if None); None if it has no area."""
        ax, ay = self._xy(a)
        bx, by = self._xy(b)
        dx, dy = bx - ax, by - ay
        size = math.hypot(dx, dy)

        def side(v):
            x, y = self._xy(v)
            s = (dx * (y - ay) - dy * (x - ax)) / size
            s = s if keep_left else -s
            return 0.0 if abs(s) <= self.eps else s

        line = _edge(a, b) if line is None else line
        out = []
        n = len(poly)
        sides = [side(v) for v, _ in poly]
        for k in range(n):
            (u, su), (v, _) = poly[k], poly[(k + 1) % n]
            du, dv = sides[k], sides[(k + 1) % n]
            if du >= 0:
                out.append([u, line if (du == 0 and dv < 0) else su])
            if (du > 0 > dv) or (du < 0 < dv):
                x = self._crossing(su, line)
                out.append([x, line if du > 0 else su])
        if len(out) < 3:
            return None
        pts = [self._xy(v) for v, _ in out]
        area = sum(pts[k][0] * pts[(k + 1) % len(pts)][1] - pts[(k + 1) % len(pts)][0] * pts[k][1]
                   for k in range(len(pts))) / 2
        if area <= 1e-12 * self.scale ** 2:
            return None
        # drop a repeated vertex (a crossing at a corner)
        cleaned = []
        for v, s in out:
            if cleaned and cleaned[-1][0] == v:
                cleaned[-1][1] = s
                continue
            cleaned.append([v, s])
        if len(cleaned) > 1 and cleaned[0][0] == cleaned[-1][0]:
            cleaned.pop()
        return [tuple(x) for x in cleaned] if len(cleaned) >= 3 else None

    def _crossing(self, s1, s2) -> int:
        """The point where the edges s1 and s2 (as lines) cross, numbered once."""
        key = (s1, s2) if s1 <= s2 else (s2, s1)
        known = self.crossings.get(key)
        log = self.log
        if known is not None:
            if log is not None and key not in log.mine:
                log.foreign = True  # found by another plane
            return known
        (i, j), (k, l) = key
        p, q = self.point(i), self.point(j)
        (px, py), (qx, qy) = self._xy(i), self._xy(j)
        (kx, ky), (lx, ly) = self._xy(k), self._xy(l)
        rx, ry, sx, sy = qx - px, qy - py, lx - kx, ly - ky
        den = rx * sy - ry * sx
        t = ((kx - px) * sy - (ky - py) * sx) / den if den != 0 else 0.0
        point = p + t * (q - p)
        vertex = None
        for candidate in (i, j, k, l):
            if np.abs(self.point(candidate) - point).max() <= self.eps:
                vertex = candidate
                break
        if vertex is None:  # three lines through one point: one point
            if log is not None:
                log.probes.append(point)
            for k, known_point in enumerate(self.new_points):
                if np.abs(known_point - point).max() <= self.eps:
                    vertex = len(self.vertices) + k
                    break
        if vertex is None:
            vertex = len(self.vertices) + len(self.new_points)
            self.new_points.append(point)
        self.crossings[key] = vertex
        if log is not None:
            log.mine.add(key)
            log.crossings.append((key, vertex))
        for s in key:
            if vertex not in s:
                self.on_edge.setdefault(s, set()).add(vertex)
                if log is not None:
                    log.on_edge.append((s, vertex))
        return vertex

    def _with_edge_points(self, outline: list[int]) -> list[int]:
        """The outline with the points that lie on its edges put in, in order."""
        lines = self._lines()
        out = []
        n = len(outline)
        for k in range(n):
            u, v = outline[k], outline[(k + 1) % n]
            out.append(u)
            points = self.on_edge.get(_edge(u, v))
            if not points:
                # an edge of a piece may lie along an original edge without
                # being one: look along every edge that holds points, its
                # ends included, that holds u
                points = set()
                for line in lines.get(u, ()):
                    if v in line:
                        points |= line
            if points:
                pu, pv = self.point(u), self.point(v)
                d = pv - pu
                length = float(d @ d)
                inside = []
                for w in points - {u, v}:
                    t = float((self.point(w) - pu) @ d) / length
                    off = self.point(w) - (pu + t * d)
                    if self.eps < t * math.sqrt(length) < math.sqrt(length) - self.eps \
                            and np.abs(off).max() <= 1e3 * self.eps:
                        inside.append((t, w))
                out.extend(w for _, w in sorted(inside))
        return out

    def _lines(self) -> dict[int, list[set[int]]]:
        """Every edge that holds points, as the set of its ends and points,
        under each of them (made once, when the planes are done)."""
        if self.lines is None:
            self.lines = {}
            for (i, j), extra in self.on_edge.items():
                line = {i, j} | extra
                for w in line:
                    self.lines.setdefault(w, []).append(line)
        return self.lines

    def _fan(self, outline: list[int]) -> list[list[int]]:
        """Triangles of a convex outline; with points on its sides, a fan from
        a new point at its centre (a fan from a corner would give flat ones)."""
        if len(outline) == 3:
            return [outline]
        centre = np.mean([self.point(v) for v in outline], axis=0)
        c = len(self.vertices) + len(self.new_points)
        self.new_points.append(centre)
        return [[outline[k], outline[(k + 1) % len(outline)], c] for k in range(len(outline))]


class _Done(tuple):
    """What resolving a plane did, its vertices numbered within the plane
    (0, 1, … its triangles' vertices in order; -1, -2, … the points it made):
    points, probes (points it looked for among those made before),
    crossings, points put on edges, and its triangles' new outlines."""

    __slots__ = ()
    points = property(lambda self: self[0])
    probes = property(lambda self: self[1])
    crossings = property(lambda self: self[2])
    on_edge = property(lambda self: self[3])
    replaced = property(lambda self: self[4])


class _Log:
    """What ``_Resolver._plane`` does, noted as it does it."""

    def __init__(self, first: int):
        self.first = first  # the number of the first point this plane makes
        self.foreign = False  # it used a crossing or a point of another plane
        self.mine: set = set()
        self.probes: list = []
        self.crossings: list = []
        self.on_edge: list = []

    def record(self, resolver, ids: np.ndarray, members, replaced) -> _Done | None:
        if self.foreign:
            return None
        count = len(resolver.vertices)
        made = len(resolver.vertices) + len(resolver.new_points) - self.first
        where = {int(v): k for k, v in enumerate(ids.tolist())}

        def local(v: int) -> int:
            if v < count:
                return where[v]  # (a KeyError: a vertex of no triangle of the plane)
            if not self.first <= v < self.first + made:
                raise KeyError(v)
            return self.first - 1 - v

        try:
            crossings = tuple(((tuple(map(local, a)), tuple(map(local, b))), local(v))
                              for (a, b), v in self.crossings)
            on_edge = tuple((tuple(map(local, s)), local(v)) for s, v in self.on_edge)
            outlines = tuple((k, tuple(tuple(local(v) for v in outline)
                                       for outline in replaced[i]))
                             for k, i in enumerate(members.tolist()) if i in replaced)
        except KeyError:
            return None
        points = tuple(resolver.new_points[self.first - count:])
        return _Done((points, tuple(self.probes), crossings, on_edge, outlines))


class _Cancels:
    """The pieces of one plane and which up piece overlaps which down piece.

    Each cancellation takes the pair that overlaps with the closest areas
    (then the larger common area, then the earlier pieces): the pairs are
    found once and kept in a heap, and a new piece is compared only with the
    pieces alive, so a plane of n pieces costs about n² tests in all, not n²
    per cancellation. Pieces are numbered in the order they are made, which
    is their order in the list the cancellations once rebuilt each time, so
    the same pairs are taken in the same order."""

    def __init__(self, resolver, pieces, tiny):
        self.resolver = resolver
        self.tiny = tiny
        self.pieces: dict[int, list] = {}  # number -> [piece, triangle, facing up], in order
        self.flat: dict[int, list] = {}
        self.boxes: dict[int, tuple] = {}
        self.areas: dict[int, float] = {}
        self.heap: list = []
        self.count = 0
        for piece in pieces:
            self._describe(self.count, piece)
            self.pieces[self.count] = piece
            self.count += 1
        up = [k for k, p in self.pieces.items() if p[2]]
        down = [k for k, p in self.pieces.items() if not p[2]]
        if up and down:
            eps = resolver.eps
            box = np.array([self.boxes[k] for k in range(self.count)]).reshape(-1, 4)
            for a, b in meeting_boxes(box[up], box[down], eps).tolist():
                self._pair(up[a], down[b])
        heapq.heapify(self.heap)

    def _describe(self, k, piece):
        flat = [self.resolver._xy(v) for v, _ in piece[0]]
        self.flat[k] = flat
        self.boxes[k] = (min(x for x, _ in flat), min(y for _, y in flat),
                         max(x for x, _ in flat), max(y for _, y in flat))
        self.areas[k] = _area(flat)

    def _pair(self, i, j, push=False):
        """Note the up piece i and the down piece j if they overlap."""
        common = _overlap_area(self.flat[i], self.flat[j])
        if common > self.tiny:
            entry = (abs(self.areas[i] - self.areas[j]), -common, i, j)
            if push:
                heapq.heappush(self.heap, entry)
            else:
                self.heap.append(entry)

    def best(self):
        """The up and down pieces to cancel next (their numbers), or None."""
        while self.heap:
            _, _, i, j = self.heap[0]
            if i in self.pieces and j in self.pieces:
                return i, j
            heapq.heappop(self.heap)
        return None

    def remove(self, pair):
        for k in pair:
            del self.pieces[k], self.flat[k], self.boxes[k], self.areas[k]

    def add(self, piece):
        k = self.count
        self.count += 1
        self._describe(k, piece)
        eps, box = self.resolver.eps, self.boxes[k]
        for other, (_, _, up) in self.pieces.items():
            if up != piece[2] and _boxes_meet(box, self.boxes[other], eps):
                self._pair(k, other, True) if piece[2] else self._pair(other, k, True)
        self.pieces[k] = piece


def _edge(a: int, b: int) -> tuple[int, int]:
    return (a, b) if a < b else (b, a)


def _boxes_meet(a, b, eps) -> bool:
    return a[0] < b[2] - eps and b[0] < a[2] - eps and a[1] < b[3] - eps and b[1] < a[3] - eps


def _area(p: list) -> float:
    return sum(p[k][0] * p[(k + 1) % len(p)][1] - p[(k + 1) % len(p)][0] * p[k][1]
               for k in range(len(p))) / 2


def _overlap_area(p: list, q: list) -> float:
    """Area common to two counter-clockwise convex polygons in 2D."""
    out = p
    for k in range(len(q)):
        (ax, ay), (bx, by) = q[k], q[(k + 1) % len(q)]
        dx, dy = bx - ax, by - ay
        sides = [dx * (y - ay) - dy * (x - ax) for x, y in out]
        points, n = [], len(out)
        for m in range(n):
            (ux, uy), (vx, vy) = out[m], out[(m + 1) % n]
            su, sv = sides[m], sides[(m + 1) % n]
            if su >= 0:
                points.append((ux, uy))
            if (su > 0 > sv) or (su < 0 < sv):
                t = su / (su - sv)
                points.append((ux + t * (vx - ux), uy + t * (vy - uy)))
        out = points
        if len(out) < 3:
            return 0.0
    return sum(out[k][0] * out[(k + 1) % len(out)][1] - out[(k + 1) % len(out)][0] * out[k][1]
               for k in range(len(out))) / 2

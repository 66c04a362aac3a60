"""A plain-Python Catmull–Clark subdivision with sharp creases, written apart
from castor.mesh.subdivide (dicts of faces and edges, one vertex at a time,
no numpy), to check its positions and the oracle's smooth solids.

A mesh is (points, faces): a list of (x, y, z) tuples and a list of tuples of
point numbers, counter-clockwise from outside. ``sharp`` is a set of
frozensets {a, b}: the crease edges.
"""

from __future__ import annotations

import math


def _add(p, q):
    return (p[0] + q[0], p[1] + q[1], p[2] + q[2])


def _scale(p, k):
    return (p[0] * k, p[1] * k, p[2] * k)


def _mean(points):
    total = (0.0, 0.0, 0.0)
    for p in points:
        total = _add(total, p)
    return _scale(total, 1.0 / len(points))


def _normal(points, face):
    """Newell's normal of one face, of unit length."""
    n = [0.0, 0.0, 0.0]
    for i, a in enumerate(face):
        p, q = points[a], points[face[(i + 1) % len(face)]]
        n[0] += (p[1] - q[1]) * (p[2] + q[2])
        n[1] += (p[2] - q[2]) * (p[0] + q[0])
        n[2] += (p[0] - q[0]) * (p[1] + q[1])
    length = math.sqrt(sum(c * c for c in n)) or 1.0
    return [c / length for c in n]


def sharp_edges(points, faces, angle):
    """The edges whose faces' normals turn by more than ``angle`` degrees."""
    around = {}
    for f, face in enumerate(faces):
        for i, a in enumerate(face):
            around.setdefault(frozenset((a, face[(i + 1) % len(face)])), []).append(f)
    sharp = set()
    for edge, fs in around.items():
        if len(fs) != 2:
            sharp.add(edge)
            continue
        n1, n2 = _normal(points, faces[fs[0]]), _normal(points, faces[fs[1]])
        dot = max(-1.0, min(1.0, sum(x * y for x, y in zip(n1, n2))))
        if math.degrees(math.acos(dot)) > angle:
            sharp.add(edge)
    return sharp


def subdivide(points, faces, sharp):
    """One step: (points, faces, sharp) of the next level."""
    face_point = [_mean([points[a] for a in face]) for face in faces]
    edge_faces = {}
    vertex_faces = {}
    vertex_edges = {}
    for f, face in enumerate(faces):
        for i, a in enumerate(face):
            edge = frozenset((a, face[(i + 1) % len(face)]))
            edge_faces.setdefault(edge, []).append(f)
            vertex_faces.setdefault(a, []).append(f)
            for end in edge:
                vertex_edges.setdefault(end, set()).add(edge)
    new_points = []
    vertex_number = {}
    for v, p in enumerate(points):
        edges = vertex_edges.get(v, set())
        creased = [e for e in edges if e in sharp]
        if len(creased) >= 3:
            q = p
        elif len(creased) == 2:
            others = [points[next(iter(e - {v}))] for e in creased]
            q = _scale(_add(_add(others[0], others[1]), _scale(p, 6)), 1 / 8)
        else:
            n = len(vertex_faces[v])
            f = _mean([face_point[f] for f in vertex_faces[v]])
            r = _mean([_mean([points[a] for a in e]) for e in edges])
            q = _scale(_add(_add(f, _scale(r, 2)), _scale(p, n - 3)), 1 / n)
        vertex_number[v] = len(new_points)
        new_points.append(q)
    edge_number = {}
    for edge, fs in edge_faces.items():
        ends = [points[a] for a in edge]
        if edge in sharp:
            q = _mean(ends)
        else:
            q = _mean(ends + [face_point[f] for f in fs])
        edge_number[edge] = len(new_points)
        new_points.append(q)
    new_faces = []
    new_sharp = set()
    for f, face in enumerate(faces):
        centre = len(new_points)
        new_points.append(face_point[f])
        for i, a in enumerate(face):
            after = frozenset((a, face[(i + 1) % len(face)]))
            before = frozenset((face[i - 1], a))
            new_faces.append((vertex_number[a], edge_number[after], centre, edge_number[before]))
    for edge in sharp:
        for end in edge:
            new_sharp.add(frozenset((vertex_number[end], edge_number[edge])))
    return new_points, new_faces, new_sharp


def limit(points, faces, sharp):
    """The limit position of every point of a quad mesh."""
    neighbours = {}
    diagonals = {}
    for face in faces:
        for i, a in enumerate(face):
            neighbours.setdefault(a, set()).update((face[(i + 1) % 4], face[i - 1]))
            diagonals.setdefault(a, []).append(face[(i + 2) % 4])
    out = []
    for v, p in enumerate(points):
        creased = [b for b in neighbours[v] if frozenset((v, b)) in sharp]
        if len(creased) >= 3:
            out.append(p)
        elif len(creased) == 2:
            q = _add(_add(points[creased[0]], points[creased[1]]), _scale(p, 4))
            out.append(_scale(q, 1 / 6))
        else:
            n = len(neighbours[v])
            total = _scale(p, n * n)
            for b in neighbours[v]:
                total = _add(total, _scale(points[b], 4))
            for d in diagonals[v]:
                total = _add(total, points[d])
            out.append(_scale(total, 1 / (n * (n + 5))))
    return out


def smooth(points, faces, angle, levels):
    """``levels`` steps from a control mesh, the points at their limit."""
    sharp = sharp_edges(points, faces, angle)
    for _ in range(levels):
        points, faces, sharp = subdivide(points, faces, sharp)
    return limit(points, faces, sharp), faces

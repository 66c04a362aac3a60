"""The oracle's own primitives and matrices, written apart from castor's
modules: each primitive's faces and its manifold3d solid, a use of a
primitive in place (its faces with outward normals) and how many times a
path cuts it away."""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

import manifold3d
import numpy as np

from .scene import Param, Prim


# --- the oracle's own evaluation ---------------------------------------------

def _value(v, env) -> float:
    return v.coefficient * env[v.name] + v.constant if isinstance(v, Param) else v


def _rotation(axis, degrees) -> np.ndarray:
    """castor's README: a rotation by a multiple of 90 degrees is exact (so
    that faces meant to meet meet); any other is cos and sin of the radians."""
    x, y, z = np.asarray(axis, float) / np.linalg.norm(axis)
    if degrees % 90 == 0:
        c, s = [(1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0)][int(degrees // 90) % 4]
    else:
        a = math.radians(degrees)
        c, s = math.cos(a), math.sin(a)
    t = 1 - c
    m = np.eye(4)
    m[:3, :3] = [[t * x * x + c, t * x * y - s * z, t * x * z + s * y],
                 [t * x * y + s * z, t * y * y + c, t * y * z - s * x],
                 [t * x * z - s * y, t * y * z + s * x, t * z * z + c]]
    return m


def step_matrix(kind: str, v: list) -> np.ndarray:
    m = np.eye(4)
    if kind == "t":
        m[:3, 3] = v
    elif kind in ("rx", "ry", "rz"):
        m = _rotation({"rx": (1, 0, 0), "ry": (0, 1, 0), "rz": (0, 0, 1)}[kind], v[0])
    elif kind == "r":
        m = _rotation(v[:3], v[3])
    elif kind == "h":
        m[0, 0], m[1, 1], m[2, 2] = v if len(v) == 3 else v * 3
    elif kind == "m":
        m[:3, :] = np.array(v).reshape(3, 4)
    return m


def polygon_points(n: int) -> np.ndarray:
    a = 2 * np.pi * np.arange(n) / n
    return np.column_stack([np.cos(a), np.sin(a)])


# the wedge (LANGUAGE.md §4.1): the triangle (0, 0), (1, 0), (0, 1) of the xz
# plane at y = 0 and at y = 1
_WEDGE = np.array([[0, 0, 0], [1, 0, 0], [0, 0, 1], [0, 1, 0], [1, 1, 0], [0, 1, 1]], float)


def primitive_faces(prim: Prim) -> list[np.ndarray]:
    """The flat faces of a primitive in its own coordinates, each an (n, 3) loop."""
    if prim.kind == "we":
        return [_WEDGE[list(loop)] for loop in
                ((0, 1, 2), (3, 5, 4), (0, 3, 4, 1), (0, 2, 5, 3), (1, 4, 5, 2))]
    if prim.kind == "cu":
        base = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float)
        return _prism_faces(base)
    if prim.kind == "pr":
        return _prism_faces(polygon_points(int(prim.args[0])))
    if prim.kind == "ex":
        return _prism_faces(np.array(prim.args, float).reshape(-1, 2))
    base = polygon_points(int(prim.args[0]))
    apex = np.array([0.0, 0.0, 1.0])
    faces = [np.column_stack([base, np.zeros(len(base))])]
    for k in range(len(base)):
        a, b = base[k], base[(k + 1) % len(base)]
        faces.append(np.array([[*a, 0], [*b, 0], apex]))
    return faces


def _prism_faces(base: np.ndarray) -> list[np.ndarray]:
    n = len(base)
    faces = [np.column_stack([base, np.zeros(n)]), np.column_stack([base, np.ones(n)])]
    for k in range(n):
        a, b = base[k], base[(k + 1) % n]
        faces.append(np.array([[*a, 0], [*b, 0], [*b, 1], [*a, 1]]))
    return faces


def primitive_solid(prim: Prim) -> manifold3d.Manifold:
    """The primitive as a manifold, from its own vertices (no rounding: the
    engine's 2D sections work on a grid, so they are not used)."""
    if prim.kind == "py":
        base = polygon_points(int(prim.args[0]))
        points = np.vstack([np.column_stack([base, np.zeros(len(base))]), [[0, 0, 1]]])
        return manifold3d.Manifold.hull_points(points)
    if prim.kind == "we":
        return manifold3d.Manifold.hull_points(_WEDGE)
    if prim.kind == "cu":
        base = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float)
    elif prim.kind == "pr":
        base = polygon_points(int(prim.args[0]))
    else:
        base = np.array(prim.args, float).reshape(-1, 2)
    x, y = base[:, 0], base[:, 1]
    if (x * np.roll(y, -1) - np.roll(x, -1) * y).sum() < 0:
        base = base[::-1]  # counter-clockwise
    n = len(base)
    cap = np.array(manifold3d.triangulate([base]), dtype=np.int64).reshape(-1, 3)
    triangles = [cap[:, ::-1], cap + n]
    k = np.arange(n)
    following = (k + 1) % n
    triangles.append(np.column_stack([k, following, following + n]))
    triangles.append(np.column_stack([k, following + n, k + n]))
    vertices = np.vstack([np.column_stack([base, np.zeros(n)]), np.column_stack([base, np.ones(n)])])
    mesh = manifold3d.Mesh64(vert_properties=np.ascontiguousarray(vertices, dtype=np.float64),
                             tri_verts=np.ascontiguousarray(np.vstack(triangles), dtype=np.uint64))
    solid = manifold3d.Manifold(mesh)
    assert solid.status() == manifold3d.Error.NoError, solid.status()
    return solid


def _distinct(solids: list) -> list:
    kept, seen = [], set()
    for solid in solids:
        gl = solid.to_mesh64()
        key = (np.asarray(gl.vert_properties)[:, :3].tobytes(), np.asarray(gl.tri_verts).tobytes())
        if key not in seen:
            seen.add(key)
            kept.append(solid)
    return kept


def without_thin_shells(solid: manifold3d.Manifold) -> manifold3d.Manifold:
    """The solid without its shells of (about) zero volume: what touches only
    leaves a sheet in manifold3d, which regularization removes."""
    parts = solid.decompose()
    kept = [p for p in parts if abs(p.volume()) > 1e-9 * p.surface_area()]  # cavities stay
    if len(kept) == len(parts):
        return solid
    return manifold3d.Manifold.compose(kept) if kept else manifold3d.Manifold()


@dataclass
class Use:
    """One use of a primitive in a frame: its path, colour and faces in place."""
    path: str
    colour: tuple
    faces: list | None  # (normal, offset, loop (n, 3), 2D axes); None: a smooth solid's


def _use(path: str, prim: Prim, matrix: np.ndarray) -> Use:
    """The use's faces in place, each with its outward normal (moved by the
    inverse transpose of the matrix, so a mirror keeps it outward)."""
    faces = []
    normals = np.linalg.inv(matrix[:3, :3]).T
    for loop, outward in zip(primitive_faces(prim), outward_normals(prim)):
        points = loop @ matrix[:3, :3].T + matrix[:3, 3]
        normal = normals @ outward
        normal /= np.linalg.norm(normal)
        faces.append((normal, float(normal @ points[0]), points))
    return Use(path, tuple(prim.colour), faces)


def outward_normals(prim: Prim) -> list[np.ndarray]:
    """The outward normal of each face of ``primitive_faces(prim)``, in the
    primitive's own coordinates (its base may turn either way)."""
    faces = primitive_faces(prim)
    if prim.kind == "we":  # its loops are written turning outward
        return [np.cross(loop[1] - loop[0], loop[2] - loop[0]) for loop in faces]
    base = faces[0][:, :2]
    turn = 1.0 if float(np.sum(base[:, 0] * np.roll(base[:, 1], -1)
                               - np.roll(base[:, 0], -1) * base[:, 1])) > 0 else -1.0
    normals = [np.array([0.0, 0.0, -1.0])]
    if prim.kind == "py":
        for loop in faces[1:]:
            normals.append(turn * np.cross(loop[1] - loop[0], loop[2] - loop[0]))
        return normals
    normals.append(np.array([0.0, 0.0, 1.0]))
    for loop in faces[2:]:
        d = loop[1] - loop[0]
        normals.append(turn * np.array([d[1], -d[0], 0.0]))
    return normals


def cut_parity(path: str) -> int:
    """How many times a use is cut away on its path (the second or a later
    operand of a difference): each turns its faces inside out."""
    return sum(1 for k in re.findall(r"(?:^|[.)])D(\d+)", path) if int(k) >= 2) % 2

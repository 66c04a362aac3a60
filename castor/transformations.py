"""The transformations of the language, each declared once with its matrix
(LANGUAGE.md §4.2): @t @rx @ry @rz @r @h @m, and @f (the facet tolerance,
which has no matrix: the evaluator handles it), and @s (a smooth solid,
LANGUAGE.md §7.1: no matrix either, the evaluator makes a ``tree.Smooth``).

A transformation's ``matrix(values, location, path)`` takes the evaluated
arguments and returns its affine matrix, 3x4 row by row as the evaluated tree
holds it (castor.csg.tree.Matrix), and the largest factor by which it
stretches lengths (used to choose facet counts). They are made with plain
floats, the numbers numpy made before, so that reading and checking a scene
needs no numpy (issue 18); ``@m`` alone asks numpy for its determinant and
norm. Rotations by multiples of 90 degrees are exact, so that ``@rz(90) !cu``
has corners on whole numbers.

One module, not a package as the primitives are: a transformation is a
declaration and a matrix of a few lines, and the nine read best side by side.
"""

from __future__ import annotations

import math
from typing import Callable, NamedTuple

from castor.diagnostics import GeometryError, Location

# A 3x4 affine matrix, row by row (castor.csg.tree.Matrix)
Matrix = tuple[float, ...]


class Transformation(NamedTuple):
    name: str  # as written after '@'
    title: str
    counts: tuple[int, ...]  # allowed numbers of arguments
    form: str
    meaning: str
    # matrix(values, location, path) -> (3x4 matrix, stretch); None for '@f' and '@s'
    matrix: Callable[[list, Location, object], tuple[Matrix, float]] | None


def _cos_sin(degrees: float) -> tuple[float, float]:
    quarter = degrees / 90.0
    if quarter == round(quarter):
        return ((1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0))[int(round(quarter)) % 4]
    radians = math.radians(degrees)
    return math.cos(radians), math.sin(radians)


def translation(x: float, y: float, z: float) -> Matrix:
    return (1.0, 0.0, 0.0, float(x), 0.0, 1.0, 0.0, float(y), 0.0, 0.0, 1.0, float(z))


def rotation(axis: tuple[float, float, float], degrees: float, location: Location) -> Matrix:
    """Right-hand rotation by ``degrees`` about ``axis`` through the origin."""
    x, y, z = axis
    length = math.sqrt(x * x + y * y + z * z)
    if length == 0 or not math.isfinite(length):
        raise GeometryError("the rotation axis of '@r' is the zero vector; give a direction", location)
    x, y, z = x / length, y / length, z / length
    c, s = _cos_sin(degrees)
    t = 1.0 - c
    return (t * x * x + c, t * x * y - s * z, t * x * z + s * y, 0.0,
            t * x * y + s * z, t * y * y + c, t * y * z - s * x, 0.0,
            t * x * z - s * y, t * y * z + s * x, t * z * z + c, 0.0)


def _axis_rotation(axis: int, degrees: float) -> Matrix:
    c, s = _cos_sin(degrees)
    i, j = [(1, 2), (2, 0), (0, 1)][axis]
    m = [1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0]
    m[4 * i + i], m[4 * i + j], m[4 * j + i], m[4 * j + j] = c, -s, s, c
    return tuple(m)


def _scaling(values, location, path):
    factors = values * 3 if len(values) == 1 else values
    for axis, k in zip("xyz", factors):
        if k == 0:
            raise GeometryError(
                f"zero scale factor for {axis} in '@h' (flattens {path} to nothing); "
                "use a small positive factor, or leave the object out", location)
    kx, ky, kz = (float(k) for k in factors)
    return (kx, 0.0, 0.0, 0.0, 0.0, ky, 0.0, 0.0, 0.0, 0.0, kz, 0.0), max(abs(k) for k in factors)


def _affine(values, location, path):
    import numpy as np

    m = np.eye(4)
    m[:3, :] = np.array(values, dtype=float).reshape(3, 4)
    linear = m[:3, :3]
    if abs(np.linalg.det(linear)) <= 1e-12 * max(1.0, float(np.abs(linear).max()) ** 3):
        raise GeometryError(f"the matrix of '@m' is not invertible (it flattens {path})", location)
    return tuple(float(x) for x in m[:3, :].ravel()), float(np.linalg.norm(linear, 2))


def _about(axis: int):
    return lambda values, location, path: (_axis_rotation(axis, values[0]), 1.0)


TRANSFORMS: dict[str, Transformation] = {t.name: t for t in (
    Transformation("t", "translation", (3,), "X, Y, Z", "move by (X, Y, Z)",
                   lambda values, location, path: (translation(*values), 1.0)),
    Transformation("rx", "rotation about x", (1,), "A", "turn by A degrees about the x axis",
                   _about(0)),
    Transformation("ry", "rotation about y", (1,), "A", "turn by A degrees about the y axis",
                   _about(1)),
    Transformation("rz", "rotation about z", (1,), "A", "turn by A degrees about the z axis",
                   _about(2)),
    Transformation("r", "rotation", (4,), "X, Y, Z, A",
                   "turn by A degrees about the axis (X, Y, Z) through the origin",
                   lambda values, location, path: (
                       rotation(tuple(values[:3]), values[3], location), 1.0)),
    Transformation("h", "scaling", (1, 3), "K or KX, KY, KZ",
                   "scale by K, or by KX, KY, KZ along the axes (negative: a mirror)", _scaling),
    Transformation("m", "matrix", (12,), "a, b, c, d, e, f, g, h, i, j, k, l",
                   "the affine map whose 3x4 matrix has these rows", _affine),
    Transformation("f", "facet tolerance", (1,), "T",
                   "facet the object with the tolerance T (scene units)", None),
    Transformation("s", "smooth", (1,), "A",
                   "make the object a smooth solid, keeping as creases the edges whose "
                   "faces turn by more than A degrees (0..180)", None),
)}


def step_matrix(kind: str, values: list[float], location: Location,
                path: object) -> tuple[Matrix, float]:
    """The matrix and stretch factor of one transformation step."""
    return TRANSFORMS[kind].matrix(values, location, path)

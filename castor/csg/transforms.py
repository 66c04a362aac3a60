"""The matrices of the transformations @t @rx @ry @rz @r @h @m (LANGUAGE.md §4.2).

Each function takes the evaluated arguments and returns a 4x4 affine matrix and
the largest factor by which it stretches lengths (used to choose facet counts).
Rotations by multiples of 90 degrees are exact, so that ``@rz(90) !cu`` has
corners on whole numbers.
"""

from __future__ import annotations

import math

import numpy as np

from castor.diagnostics import GeometryError, Location


def _cos_sin(degrees: float) -> tuple[float, float]:
    quarter = degrees / 90.0
    if quarter == round(quarter):
        return ((1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0))[int(round(quarter)) % 4]
    radians = math.radians(degrees)
    return math.cos(radians), math.sin(radians)


def translation(x: float, y: float, z: float) -> np.ndarray:
    m = np.eye(4)
    m[:3, 3] = (x, y, z)
    return m


def rotation(axis: tuple[float, float, float], degrees: float, location: Location) -> np.ndarray:
    """Right-hand rotation by ``degrees`` about ``axis`` through the origin."""
    x, y, z = axis
    length = math.sqrt(x * x + y * y + z * z)
    if length == 0 or not math.isfinite(length):
        raise GeometryError("the rotation axis of '@r' is the zero vector; give a direction", location)
    x, y, z = x / length, y / length, z / length
    c, s = _cos_sin(degrees)
    t = 1.0 - c
    m = np.eye(4)
    m[:3, :3] = [
        [t * x * x + c, t * x * y - s * z, t * x * z + s * y],
        [t * x * y + s * z, t * y * y + c, t * y * z - s * x],
        [t * x * z - s * y, t * y * z + s * x, t * z * z + c],
    ]
    return m


def _axis_rotation(axis: int, degrees: float) -> np.ndarray:
    c, s = _cos_sin(degrees)
    i, j = [(1, 2), (2, 0), (0, 1)][axis]
    m = np.eye(4)
    m[i, i], m[i, j], m[j, i], m[j, j] = c, -s, s, c
    return m


def _scaling(values, location, path):
    factors = values * 3 if len(values) == 1 else values
    for axis, k in zip("xyz", factors):
        if k == 0:
            raise GeometryError(
                f"zero scale factor for {axis} in '@h' (flattens {path} to nothing); "
                "use a small positive factor, or leave the object out", location)
    return np.diag([*factors, 1.0]), max(abs(k) for k in factors)


def _affine(values, location, path):
    m = np.eye(4)
    m[:3, :] = np.array(values, dtype=float).reshape(3, 4)
    linear = m[:3, :3]
    if abs(np.linalg.det(linear)) <= 1e-12 * max(1.0, float(np.abs(linear).max()) ** 3):
        raise GeometryError(f"the matrix of '@m' is not invertible (it flattens {path})", location)
    return m, float(np.linalg.norm(linear, 2))


# transformation (castor.language.vocabulary.TRANSFORMS) -> its matrix and stretch;
# '@f' has none: it sets the facet tolerance, which the evaluator handles
MATRICES = {
    "t": lambda values, location, path: (translation(*values), 1.0),
    "rx": lambda values, location, path: (_axis_rotation(0, values[0]), 1.0),
    "ry": lambda values, location, path: (_axis_rotation(1, values[0]), 1.0),
    "rz": lambda values, location, path: (_axis_rotation(2, values[0]), 1.0),
    "r": lambda values, location, path: (rotation(tuple(values[:3]), values[3], location), 1.0),
    "h": _scaling,
    "m": _affine,
}


def step_matrix(kind: str, values: list[float], location: Location, path: object) -> tuple[np.ndarray, float]:
    """The matrix and stretch factor of one transformation step."""
    return MATRICES[kind](values, location, path)

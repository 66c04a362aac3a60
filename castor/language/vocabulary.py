"""The vocabulary of the language, declared once: every primitive and transformation.

A primitive (``!cy``) or a transformation (``@rz``) is declared here with its
name, its arguments and what they mean, and how its values are checked. The
parser (argument counts), the evaluator (checks), the facetizer
(``castor.mesh.primitives.BUILDERS``), the ray tracer, the matrices
(``castor.csg.transforms.MATRICES``) and the vim syntax file read this table;
each of those keeps only its own half of the work, keyed by these names, and
a test checks that every name here has its entry there.
"""

from __future__ import annotations

from typing import Callable, NamedTuple

from castor.diagnostics import GeometryError, Location


class Argument(NamedTuple):
    name: str
    meaning: str


class PrimitiveKind(NamedTuple):
    name: str  # as written after '!'
    title: str
    solid: str  # what the unit solid is (LANGUAGE.md §4.1)
    arguments: tuple[Argument, ...]  # after the colour R, G, B
    pairs: bool  # then any number of coordinate pairs (at least three)
    curved: bool  # facets depend on the tolerance
    check: Callable | None  # check(shape, location, path): raise GeometryError

    @property
    def form(self) -> str:
        names = ["R", "G", "B"] + [a.name for a in self.arguments]
        if self.pairs:
            first, second = self.arguments_of_pairs
            names += [f"{first}1", f"{second}1", f"{first}2", f"{second}2", f"{first}3",
                      f"{second}3", "..."]
        return ", ".join(names)

    @property
    def arguments_of_pairs(self) -> tuple[str, str]:
        return ("r", "z") if self.name == "rv" else ("x", "y")

    @property
    def count(self) -> int:
        """Arguments before any coordinate pairs, the colour included."""
        return 3 + len(self.arguments)


class TransformKind(NamedTuple):
    name: str  # as written after '@'
    title: str
    counts: tuple[int, ...]  # allowed numbers of arguments
    form: str
    meaning: str


# --- checks of a primitive's evaluated shape arguments ---------------------


def _check_tube(shape: tuple, location: Location, path: object) -> None:
    k = shape[0]
    if not 0 < k < 1:
        raise GeometryError(f"the tube radius K of {path} must lie strictly between 0 and 1, "
                            f"not {k:g}", location)


MAX_SIDES = 10_000_000


def _check_sides(shape: tuple, location: Location, path: object) -> None:
    n = shape[0]
    if n != int(n) or n < 3:
        raise GeometryError(f"the number of sides N of {path} must be a whole number >= 3, "
                            f"not {n:g}", location)
    if n > MAX_SIDES:
        raise GeometryError(f"the number of sides N of {path} is too large ({n:g})", location)


def _check_polygon(shape: tuple, location: Location, path: object) -> None:
    from castor.language.outline import polygon

    polygon(shape, "polygon", location, path)


def _check_profile(shape: tuple, location: Location, path: object) -> None:
    from castor.language.outline import profile

    profile(shape, location, path)


_COLOUR = "R, G, B: the colour, each 0..1"

PRIMITIVES: dict[str, PrimitiveKind] = {p.name: p for p in (
    PrimitiveKind("cu", "cube", "the unit cube [0,1]^3", (), False, False, None),
    PrimitiveKind("sp", "sphere", "the sphere of radius 1 centred at the origin", (), False,
                  True, None),
    PrimitiveKind("cy", "cylinder", "radius 1 about the z axis, from z = 0 to z = 1", (),
                  False, True, None),
    PrimitiveKind("co", "cone", "base of radius 1 in z = 0, apex (0, 0, 1)", (), False, True,
                  None),
    PrimitiveKind("to", "torus", "centre circle of radius 1 in z = 0, tube radius K",
                  (Argument("K", "the tube radius, 0 < K < 1"),), False, True, _check_tube),
    PrimitiveKind("pr", "prism", "a regular N-gon of circumradius 1 swept from z = 0 to 1",
                  (Argument("N", "the number of sides, a whole number >= 3"),), False, False,
                  _check_sides),
    PrimitiveKind("py", "pyramid", "a regular N-gon base of circumradius 1, apex (0, 0, 1)",
                  (Argument("N", "the number of sides, a whole number >= 3"),), False, False,
                  _check_sides),
    PrimitiveKind("ex", "extrusion", "a simple polygon in z = 0 swept to z = 1", (), True,
                  False, _check_polygon),
    PrimitiveKind("rv", "revolution", "a simple profile (r, z), r >= 0, turned about z", (),
                  True, True, _check_profile),
)}

TRANSFORMS: dict[str, TransformKind] = {t.name: t for t in (
    TransformKind("t", "translation", (3,), "X, Y, Z", "move by (X, Y, Z)"),
    TransformKind("rx", "rotation about x", (1,), "A", "turn by A degrees about the x axis"),
    TransformKind("ry", "rotation about y", (1,), "A", "turn by A degrees about the y axis"),
    TransformKind("rz", "rotation about z", (1,), "A", "turn by A degrees about the z axis"),
    TransformKind("r", "rotation", (4,), "X, Y, Z, A",
                  "turn by A degrees about the axis (X, Y, Z) through the origin"),
    TransformKind("h", "scaling", (1, 3), "K or KX, KY, KZ",
                  "scale by K, or by KX, KY, KZ along the axes (negative: a mirror)"),
    TransformKind("m", "matrix", (12,), "a, b, c, d, e, f, g, h, i, j, k, l",
                  "the affine map whose 3x4 matrix has these rows"),
    TransformKind("f", "facet tolerance", (1,), "T",
                  "facet the object with the tolerance T (scene units)"),
    TransformKind("s", "smooth", (1,), "A",
                  "make the object a smooth solid, keeping as creases the edges whose "
                  "faces turn by more than A degrees (0..180)"),
)}

BOOLEANS = {"U": "union", "I": "intersection", "D": "difference"}

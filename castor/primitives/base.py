"""What a primitive is, declared once: the class every primitive module fills in.

One ``PrimitiveKind`` holds everything a stage needs to know about one kind of
solid (LANGUAGE.md §4.1): how it is written (name, arguments, coordinate
pairs), how its values are checked, its unit box (the evaluator's reach
check, the ray tracer's boxes), whether its facets depend on the tolerance,
how many facets it needs under a given transformation and tolerance, how it
becomes triangles (and which of its faces are flat, which facets of a
curved surface), how many triangles that will be, and how a ray meets it.
The parser, the evaluator, the facetizer, the ray tracer and the editor files
read it; none keeps a list of its own.
"""

from __future__ import annotations

from typing import Callable, NamedTuple

FLAT = -1  # the surface number of a flat face


class Argument(NamedTuple):
    name: str
    meaning: str


class Mesh(NamedTuple):
    """A unit primitive as triangles: vertices in double precision, triangles
    counter-clockwise seen from outside, for each triangle the number of the
    flat face it belongs to (the two triangles of a side quad of a cylinder
    share one), and for each face number the smooth surface it is a facet of:
    ``FLAT`` (-1) for a face that is flat in the solid itself, k >= 0 for a
    facet of the primitive's curved surface k (a cylinder's side is one
    surface; each band a profile segment of ``!rv`` sweeps is one)."""

    vertices: object  # (V, 3) float64
    triangles: object  # (T, 3) int64
    faces: object  # (T,) int64
    surfaces: object  # (F,) int64, indexed by face number


Box = tuple[tuple[float, float, float], tuple[float, float, float]]


class PrimitiveKind(NamedTuple):
    """One kind of primitive, as every stage reads it.

    ``shape`` below is the tuple of its evaluated arguments after the colour,
    already checked; ``facets`` the tuple of facet counts ``facets(...)``
    chose (empty for a primitive without curved faces)."""

    place: int  # its row in LANGUAGE.md's table of primitives (§4.1), to list them in order
    name: str  # as written after '!'
    title: str
    solid: str  # what the unit solid is (LANGUAGE.md §4.1)
    arguments: tuple[Argument, ...]  # after the colour R, G, B
    pair_names: tuple[str, str] | None  # then coordinate pairs (at least three), or None
    curved: bool  # it has curved faces, so its facets depend on the tolerance
    check: Callable | None  # check(shape, location, path): raise GeometryError
    box: Callable[[tuple], Box]  # box(shape): the unit primitive's (low, high)
    mesh: Callable[[tuple, tuple], Mesh]  # mesh(shape, facets)
    triangles: Callable[[tuple, tuple], int]  # triangles(shape, facets), before building
    spans: Callable  # spans(shape, o, d) -> (t, face): pictures/trace.py's spans of rays
    normal: Callable  # normal(shape, p, face) -> (n, 3) outward normals, unnormalised
    # facets(shape, linear, tolerance) -> tuple of ints: the facet counts that
    # keep every point of the surface within ``tolerance`` of the facets after
    # the linear map ``linear`` (3x3, row by row: facets.Linear) from its unit
    # space to the tolerance's units; None for a primitive without curved faces
    facets: Callable[[tuple, tuple, float], tuple[int, ...]] | None = None

    def facet_counts(self, shape: tuple, linear: tuple, tolerance: float) -> tuple[int, ...]:
        """The facet counts its mesh is built with (what its template is keyed by)."""
        return () if self.facets is None else self.facets(shape, linear, tolerance)

    @property
    def pairs(self) -> bool:
        """Whether coordinate pairs follow the arguments."""
        return self.pair_names is not None

    @property
    def form(self) -> str:
        names = ["R", "G", "B"] + [a.name for a in self.arguments]
        if self.pair_names is not None:
            first, second = self.pair_names
            names += [f"{first}1", f"{second}1", f"{first}2", f"{second}2", f"{first}3",
                      f"{second}3", "..."]
        return ", ".join(names)

    @property
    def count(self) -> int:
        """Arguments before any coordinate pairs, the colour included."""
        return 3 + len(self.arguments)

    def extent(self, shape: tuple) -> float:
        """The largest coordinate of the unit primitive's box, at least 2: how
        far its corners reach, for the evaluator's check of the coordinates."""
        low, high = self.box(shape)
        return max(2.0, *(abs(v) for v in low), *(abs(v) for v in high))

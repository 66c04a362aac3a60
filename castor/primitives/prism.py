"""``!pr``: the prism on the regular N-gon inscribed in the unit circle (first
vertex at (1, 0)), from z = 0 to z = 1: every face flat, N whole and >= 3; a
ray meets it as N + 2 half-spaces."""

from __future__ import annotations

from castor.diagnostics import GeometryError, Location
from castor.primitives import rays
from castor.primitives.base import Argument, PrimitiveKind
from castor.primitives.cylinder import ROUND
from castor.primitives.facets import column

MAX_SIDES = 10_000_000
SIDES = Argument("N", "the number of sides, a whole number >= 3")


def check_sides(shape: tuple, location: Location, path: object) -> None:
    n = shape[0]
    if n != int(n) or n < 3:
        raise GeometryError(f"the number of sides N of {path} must be a whole number >= 3, "
                            f"not {n:g}", location)
    if n > MAX_SIDES:
        raise GeometryError(f"the number of sides N of {path} is too large ({n:g})", location)


PRIMITIVE = PrimitiveKind(
    place=60, name="pr", title="prism", solid="a regular N-gon of circumradius 1 swept from z = 0 to 1",
    arguments=(SIDES,), pair_names=None, curved=False, check=check_sides,
    box=lambda shape: ROUND, mesh=lambda shape, facets: column(int(shape[0])),
    triangles=lambda shape, facets: 4 * int(shape[0]),
    spans=rays.polygon_spans(False), normal=rays.polygon_normal(False))

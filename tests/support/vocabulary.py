"""castor's vocabulary as the tests walk it: every primitive's name, in the
order of LANGUAGE.md's table, and a shape (its arguments after the colour)
that its own check accepts, found from its declaration, so that a new
primitive is tested without a test naming it."""

from __future__ import annotations

from itertools import product

from castor.diagnostics import CastorError, Location
from castor.primitives import PRIMITIVES
from castor.transformations import TRANSFORMS

# tried in order for each argument after the colour, and for the coordinate pairs
VALUES = (0.3, 5.0, 6.0, 0.5, 2.0)
PAIRS = ((0.0, 0.0, 1.0, 0.0, 0.0, 1.0), (0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0))


def primitive_names() -> list[str]:
    """Every primitive's name, in the order of LANGUAGE.md's table."""
    return sorted(PRIMITIVES, key=lambda name: PRIMITIVES[name].place)


def transformation_names() -> list[str]:
    return list(TRANSFORMS)


def example_shape(name: str) -> tuple:
    """The first shape the primitive's check accepts (arguments from VALUES, then
    pairs from PAIRS if it takes them)."""
    primitive = PRIMITIVES[name]
    pairs = PAIRS if primitive.pairs else ((),)
    for values in product(VALUES, repeat=len(primitive.arguments)):
        for tail in pairs:
            shape = tuple(values) + tuple(tail)
            try:
                if primitive.check is not None:
                    primitive.check(shape, Location("<test>", 1, 1), f"!{name}")
            except CastorError:
                continue
            return shape
    raise AssertionError(f"no example shape for !{name}: add values to tests/support/vocabulary.py")


def arguments_text(shape: tuple) -> str:
    """The shape as written after the colour: ', 0.3, 5' (empty for none)."""
    return "".join(f", {v:g}" for v in shape)

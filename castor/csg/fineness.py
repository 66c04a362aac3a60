"""A warning, before a frame is made, for a curved primitive whose facets are
so fine that its booleans will be slow (issue 29: ``-t 1e-8`` on the car).

The boolean engine's time grows with the square of a curved primitive's
segments around where it meets a flat face (a box united with a cylinder of
n segments: 4,000, 1.0 s; 8,000, 5.1 s; benchmarks/fine_tolerance.py): past
``SLOW_SEGMENTS`` segments around, the evaluator says so at the primitive as
written, once a run, with a coarser tolerance that is still finer than a
printer or a screen shows (about ``SUGGESTED_SEGMENTS`` around: n grows as
1/√t). The tolerance warned of is the one the user chose (``-t``,
``TOLERANCE`` or ``@f``), never the screen's (``--pixel-error`` only ever
coarsens it, castor.mesh.screen).
"""

from __future__ import annotations

import math

from castor.language.expressions import format_number
from castor.primitives.facets import linear_part, product

SLOW_SEGMENTS = 6_000  # about 2 s for one boolean with a flat face (4,000: 1.0 s; 8,000: 5.1 s)
SUGGESTED_SEGMENTS = 500
# past this a boolean may take minutes rather than seconds (about 50 s at 25,000;
# the car: 10 s at -t 1e-8, 14,033 segments; 77 s at 1e-9, 43,283)
MINUTES_SEGMENTS = 25_000

# A curved primitive's segments around stay below SLOW_SEGMENTS while its
# tolerance over its size is above this (a circle: n ≈ π/√(2t/R); a sphere's
# segments around are √2 times as many, a torus halves its tolerance, and it
# is rounded down by up to 2^(1/4)): 16 times the bound of a circle, as margin
_SAFE_RATIO = 16 * (math.pi / SLOW_SEGMENTS) ** 2 / 2


def slow_segments(declared, shape: tuple, matrix: tuple, metric, tolerance: float,
                  extent: float) -> int | None:
    """The segments around of a curved primitive (``declared``, a
    castor.primitives.PrimitiveKind) when more than SLOW_SEGMENTS, else None.
    ``extent`` (the largest coordinate of its unit box) times the sum of the
    squares of its matrix's linear part bounds its radius after the map, so
    the commonest primitives cost a few multiplications."""
    a, b, c, _, d, e, f, _, g, h, i, _ = matrix
    size2 = (a * a + b * b + c * c + d * d + e * e + f * f + g * g + h * h + i * i) * extent * extent
    if tolerance * tolerance > _SAFE_RATIO * _SAFE_RATIO * size2:
        return None
    linear = linear_part(matrix)
    if metric is not None:
        linear = product(metric, linear)
    counts = declared.facets(shape, linear, tolerance)
    return counts[0] if counts and counts[0] > SLOW_SEGMENTS else None


def slow_message(kind: str, segments: int, chosen: float | None) -> str:
    """The warning for ``'!kind'`` with ``segments`` around at the tolerance
    ``chosen`` (the frame's, set by -t or TOLERANCE; None where an '@f' may
    have chosen it)."""
    coarser = (SUGGESTED_SEGMENTS / segments) ** -2  # how many times coarser
    if chosen is None:
        at, fix = "at its tolerance", f"a tolerance {format_number(_rounded(coarser))} times coarser (-t or '@f')"
    else:
        at = f"at tolerance {format_number(chosen)}"
        fix = f"a coarser -t (such as {format_number(_rounded(chosen * coarser))})"
    takes = "minutes" if segments >= MINUTES_SEGMENTS else "several seconds"
    return (f"'!{kind}' gets {segments:,} segments around {at}: a boolean with it may take "
            f"{takes} (the time grows as the square of the segments); {fix} is still finer "
            "than a printer or a screen shows")


def _rounded(value: float) -> float:
    """The power of ten nearest ``value`` (on a log scale)."""
    return 10.0 ** round(math.log10(value))

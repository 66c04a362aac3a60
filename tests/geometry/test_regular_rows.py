"""Rows of cubes turned about slanted axes (issue 18, item 5; LANGUAGE.md §7):
the engine leaves needles in them, triangles a few 1e-11 high whose plane
the coordinates cannot tell (found by the oracle's wide generator). No
polygon of the frame may be one."""

import numpy as np

from meshcheck import _newell, check_closed, check_convex_planar, frames_of, polygon_defects, \
    regularity_defects


def _thinness(polygon) -> float:
    """Twice the polygon's area over the square of its extent: about zero for
    a needle, 1 for a square."""
    size = float(np.ptp(polygon.points, axis=0).max())
    return float(np.linalg.norm(_newell(polygon.points))) / size ** 2


def test_a_turned_row_of_overlapping_cubes_has_no_needle():
    """Eleven unit cubes 0.1 apart turned by 13° about (1, 1, -1): the
    engine's union holds a triangle of U2's face with two corners 9e-9
    apart and a height of 5e-11 (twice its area 8e-10 of its extent
    squared), written as a polygon of its own that is not planar to its
    own coordinates. Its corners stand for one point: welded, it is gone."""
    (frame,) = frames_of("> @r(1.0, 1.0, -1.0, 13.0) $U[W = 0, 10](@t(0.1 * W, 0, 0) "
                         "!cu(0.0, 0.0, 0.5));\n")
    check_closed(frame)
    check_convex_planar(frame)
    assert abs(frame.volume() - 2.0) < 1e-9
    assert regularity_defects(frame) == []
    assert [i for i, p in enumerate(frame.polygons) if polygon_defects(p)] == []
    assert min(_thinness(p) for p in frame.polygons) > 1e-8

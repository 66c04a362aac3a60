"""A smooth solid's thin walls that Catmull–Clark turns inside out
(castor.mesh.crossings): the grid that pairs triangles, the exact crossing
test, and the corners put back; the smooth oracle's scene where it happened."""

from __future__ import annotations

import numpy as np
import pytest

from castor.mesh import crossings
from tests.support.cli import frames_of
from tests.support.regularity import regularity_defects


def test_the_grid_pairs_every_two_boxes_that_meet():
    # small boxes, and a few long ones over many of the grid's cells (a flat
    # face's triangles beside a curved surface's), against every pair
    rng = np.random.default_rng(7)
    lo = rng.uniform(0, 10, (2000, 3))
    hi = lo + rng.uniform(0, 0.2, (2000, 3))
    hi[:20] = lo[:20] + rng.uniform(2, 6, (20, 3))
    meet = np.all((lo[:, None] <= hi[None]) & (lo[None] <= hi[:, None]), axis=2)
    want = {(a, b) for a, b in zip(*np.nonzero(np.triu(meet, 1)))}
    got = {tuple(p) for p in crossings.near_pairs(lo, hi).tolist()}
    assert len(want) > 100 and got == want


def test_the_grid_copes_with_flat_boxes_and_long_ones():
    # triangles in two horizontal planes (no height: the median height is 0),
    # long slivers of a fan among small ones, and a few tilted: the grid of
    # the long ones once took cells of 1e-12 in height and asked for
    # terabytes (the review's case)
    points, triangles = [], []

    def add(a, b, c):
        triangles.append([len(points), len(points) + 1, len(points) + 2])
        points.extend([a, b, c])

    for i in range(60):
        x, y = i % 10 * 0.1, i // 10 * 0.1
        add([x, y, 0], [x + 0.1, y, 0], [x, y + 0.1, 0])
    for i in range(30):
        add([0, 0, 1], [5, i * 0.2, 1], [5, i * 0.2 + 0.2, 1])
    for i in range(10):
        add([i * 0.1, 2, 0], [i * 0.1 + 0.1, 2, 0.05], [i * 0.1, 2.1, 0.1])
    corners = np.array(points)[np.array(triangles)]
    lo, hi = corners.min(axis=1), corners.max(axis=1)
    meet = np.all((lo[:, None] <= hi[None]) & (lo[None] <= hi[:, None]), axis=2)
    want = {(a, b) for a, b in zip(*np.nonzero(np.triu(meet, 1)))}
    assert {tuple(p) for p in crossings.near_pairs(lo, hi).tolist()} == want
    assert crossings.crossing_pairs(np.array(points), np.array(triangles)).tolist() == []


def test_triangles_that_cross_and_triangles_that_only_touch():
    positions = np.array([[0, 0, 0], [2, 0, 0], [0, 2, 0],          # flat, z = 0
                          [0.5, 0.5, -1], [0.5, 0.5, 1], [1.5, 0.5, 1],  # through it
                          [0.5, 0.5, 0], [0.6, 0.5, 1], [0.5, 0.6, 1]],  # only touching it
                         float)
    triangles = np.array([[0, 1, 2], [3, 4, 5], [6, 7, 8]])
    assert crossings.crossing_pairs(positions, triangles).tolist() == [[0, 1]]
    # around a corner they share, the far side of one through the other: the
    # ring of triangles around it folds over (the smooth oracle's seed 80,
    # winding 2 after @s(170) over a union); sharing a side, they never cross
    positions = np.array([[0, 0, 0], [2, 0, 0], [0, 2, 0], [1, 0.2, -1], [0.2, 1, 1]], float)
    assert crossings.crossing_pairs(positions, np.array([[0, 1, 2], [0, 3, 4]])).tolist() == [[0, 1]]
    assert crossings.crossing_pairs(positions, np.array([[0, 1, 2], [0, 1, 4]])).tolist() == []


def box(low, high, fan_bottom_at=None):
    """A closed box [low, high] of triangles, outward; with ``fan_bottom_at``,
    its bottom is fanned from a centre point at that height (the last vertex)."""
    (x0, y0, z0), (x1, y1, z1) = low, high
    top = [[x0, y0, z1], [x1, y0, z1], [x1, y1, z1], [x0, y1, z1]]
    bottom = [[x0, y0, z0], [x1, y0, z0], [x1, y1, z0], [x0, y1, z0]]
    triangles = [[0, 1, 2], [0, 2, 3]]
    for i in range(4):
        j = (i + 1) % 4
        triangles += [[i, 4 + i, 4 + j], [i, 4 + j, j]]
    points = top + bottom
    if fan_bottom_at is None:
        triangles += [[4, 6, 5], [4, 7, 6]]
    else:
        points.append([(x0 + x1) / 2, (y0 + y1) / 2, fan_bottom_at])
        triangles += [[8, 5, 4], [8, 6, 5], [8, 7, 6], [8, 4, 7]]
    return np.array(points, float), np.array(triangles)


def test_a_thin_wall_turned_inside_out_is_put_back():
    # a plate 0.01 thick whose bottom's centre went 0.002 up through its top:
    # winding -1 between them. The centre goes back behind the top by a hair;
    # the corners, which may not move, stay
    positions, triangles = box((0, 0, -0.01), (4, 4, 0), fan_bottom_at=0.002)
    assert crossings.winding(positions, triangles, np.array([[2, 2, 0.001]])).round().tolist() == [-1]
    assert len(crossings.crossing_pairs(positions, triangles)) == 4
    movable = np.arange(9) == 8
    put = crossings.uncrossed(positions, triangles, movable, reach=0.01)
    assert put[8].tolist() == pytest.approx([2, 2, -1e-5], abs=1e-12)
    assert np.array_equal(put[:8], positions[:8])
    assert len(crossings.crossing_pairs(put, triangles)) == 0
    # deeper than the reach, or not movable: left as it is
    assert np.array_equal(crossings.uncrossed(positions, triangles, movable, reach=0.001), positions)
    assert np.array_equal(crossings.uncrossed(positions, triangles, ~movable, reach=0.01), positions)


def test_crossings_that_cannot_be_put_back_hide_none_that_can():
    # 30 pairs of tetrahedra pushed deep into each other (beyond the reach:
    # about 90 crossings), numbered first, then the plate turned inside out:
    # its centre still goes back
    tetrahedron = np.array([[0, 2, 1], [0, 3, 2], [0, 1, 3], [1, 2, 3]])
    corner = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1.0]])
    points, triangles = [], []
    for i in range(30):
        for shift in (0.0, 0.3):
            triangles.append(tetrahedron + 4 * len(triangles))
            points.append(corner + [10 + 3 * i + shift, shift, shift])
    first = 4 * len(points)
    plate, fan = box((0, 0, -0.01), (4, 4, 0), fan_bottom_at=0.002)
    positions = np.concatenate(points + [plate])
    triangles = np.concatenate(triangles + [fan + first])
    movable = np.arange(len(positions)) == first + 8
    assert len(crossings.crossing_pairs(positions, triangles)) > 64
    put = crossings.uncrossed(positions, triangles, movable, reach=0.01)
    assert put[first + 8].tolist() == pytest.approx([2, 2, -1e-5], abs=1e-12)


def test_two_parts_pushed_into_each_other_are_put_back():
    # a tetrahedron whose lowest corner went 0.002 down into a box: winding 2
    # there. The corner goes back in front of the box's top by a hair
    positions, triangles = box((0, 0, -1), (4, 4, 0))
    tip = np.array([[2, 2, -0.002], [1, 1, 1], [3, 1, 1], [2, 3, 1]])
    tetrahedron = np.array([[0, 2, 1], [0, 3, 2], [0, 1, 3], [1, 2, 3]]) + 8
    positions, triangles = np.concatenate([positions, tip]), np.concatenate([triangles, tetrahedron])
    assert crossings.winding(positions, triangles, np.array([[2, 2, -0.001]])).round().tolist() == [2]
    movable = np.arange(12) == 8
    put = crossings.uncrossed(positions, triangles, movable, reach=0.01)
    assert put[8].tolist() == pytest.approx([2, 2, 1e-5], abs=1e-12)
    assert len(crossings.crossing_pairs(put, triangles)) == 0


def test_the_smooth_oracles_thin_wedge_is_no_pocket():
    # the smooth oracle's seed 11 (batch 50, scene 9): @s(30) over a smooth
    # difference whose cut left a wedge 14 degrees thin between a flat face
    # and a curved one; smoothing again moved the curved side 0.0005 through
    # the flat one near the tip: a pocket of winding -1
    text = """
s9o0 = @s(30.0) $D(@s(180.0) @rz(30.0) @rz((-96.16)) @rz(45.0) !pr(1.0, 1.0, 1.0, 8.0), $U(@rx(45.0) !cu(0.0, 0.0, 1.0), @h(0.5) @rz(180.0) !ex(1.0, 1.0, 1.0, 0.0, 0.0, 2.0, 0.0, 2.0, 2.0, 1.5, 2.0, 1.5, 0.5, 0.5, 0.5, 0.5, 2.0, 0.0, 2.0), @rx(30.0) @t(0.5, 1.0, (-0.5)) @t(0.973, (-0.5), 1.0) !cu(1.0, 0.0, 1.0), !cu(0.5, 0.5, 1.0)));
> @s(30.0) s9o0;
"""
    frame = frames_of(text)[0]
    assert regularity_defects(frame) == []
    assert abs(frame.volume() - 0.66261) < 1e-4

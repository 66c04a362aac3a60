"""Rows of cubes turned about slanted axes (issue 18, item 5; LANGUAGE.md §7):
the engine leaves needles in them, triangles a few 1e-11 high whose plane
the coordinates cannot tell (found by the oracle's wide generator). No
polygon of the frame may be one."""

import subprocess
import sys

import numpy as np

from tests.support.checks import check_closed, check_convex_planar
from tests.support.cli import frames_of
from tests.support.regularity import polygon_defects, regularity_defects
from tests.support.stream import newell


def _thinness(polygon) -> float:
    """Twice the polygon's area over the square of its extent: about zero for
    a needle, 1 for a square."""
    size = float(np.ptp(polygon.points, axis=0).max())
    return float(np.linalg.norm(newell(polygon.points))) / size ** 2


def test_a_turned_row_of_overlapping_cubes_has_no_needle():
    """Eleven unit cubes 0.1 apart turned by 13° about (1, 1, -1): the
    engine's union holds a triangle of U2's face with two corners 9e-9
    apart and a height of 5e-11 (twice its area 8e-10 of its extent
    squared), written as a polygon of its own that is not planar to its
    own coordinates. Flat by its height (under 1e-9 of its length), it is
    flipped away."""
    (frame,) = frames_of("> @r(1.0, 1.0, -1.0, 13.0) $U[W = 0, 10](@t(0.1 * W, 0, 0) "
                         "!cu(0.0, 0.0, 0.5));\n")
    check_closed(frame)
    check_convex_planar(frame)
    assert abs(frame.volume() - 2.0) < 1e-9
    assert regularity_defects(frame) == []
    assert [i for i, p in enumerate(frame.polygons) if polygon_defects(p)] == []
    assert min(_thinness(p) for p in frame.polygons) > 1e-9



# castor run with each batch's regularized triangles counted for flat ones
_FLAT_LEFT = """
import sys
from castor.mesh import facetize, flat
from castor.mesh.regularize import regular_triangles
left = []
def counted(tri, parts):
    out = regular_triangles(tri, parts)
    left.append(int(flat.flat_triangles(out.vertices, out.triangles).sum()))
    return out
facetize.regular_triangles = counted
from castor.cli import main
sys.argv = ['castor', '-q', '-o', sys.argv[1], sys.argv[2]]
main()
print('flat left', left, file=sys.stderr)
"""


def test_no_flat_triangle_is_left_inside_a_face(tmp_path):
    """In the same row, four corners inside U2's top face: two of them
    1.6e-5 apart, each in line with a third corner, so either diagonal of
    the four leaves a flat triangle and flips only trade one for the other.
    The vertex inside a plane of triangles is collapsed onto its neighbour
    instead: no flat triangle is left for merging to hide (or to write as a
    polygon of zero area where no neighbour takes it in)."""
    scene = tmp_path / "row.cas"
    scene.write_text("> @r(1.0, 1.0, -1.0, 13.0) $U[W = 0, 10](@t(0.1 * W, 0, 0) "
                     "!cu(0.0, 0.0, 0.5));\n")
    done = subprocess.run([sys.executable, "-c", _FLAT_LEFT, str(tmp_path / "row.off"),
                           str(scene)], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    line = [x for x in done.stderr.splitlines() if x.startswith("flat left")][-1]
    counts = [int(c) for c in line[len("flat left ["):-1].split(",")]
    assert counts and max(counts) == 0


def test_a_flip_across_an_edge_of_the_solid_turns_nothing_over():
    """Eleven cubes 0.25 apart, mirrored and turned by 356.731° about
    (1, 1, 1) (wide oracle, seed 20): a triangle nearly flat on one face
    beside an edge, flipped with its neighbour on the other face, put a
    triangle of U2 on the wrong side (a polygon facing inward). A flip whose
    triangles would not face as the neighbour does is not made."""
    (frame,) = frames_of("> @h(-1.0, 1.0, 0.5) @r(1.0, 1.0, 1.0, 356.731) $U[W = 0, 10]"
                         "(@t(0.25 * W, 0.0, 0.0) !cu(0.5, 1.0, 0.5));\n")
    check_closed(frame)
    check_convex_planar(frame)
    assert abs(frame.volume() - 1.75) < 1e-9
    assert regularity_defects(frame) == []
    assert min(_thinness(p) for p in frame.polygons) > 1e-9


def test_a_run_of_flat_triangles_along_one_line_is_flipped_away():
    """Nine cubes 0.1 apart turned by 33.173° about (-1, 1, 0.3) (wide
    oracle, seed 20): flat triangles side by side along one line, each the
    other's neighbour. A flat neighbour faces no way, so the flips are
    made (a check against turning over refused them: polygons of zero
    area were written)."""
    (frame,) = frames_of("> @r(-1.0, 1.0, 0.3, 33.173) $U[W = 0, 8](@t(0.1 * W, 0.0, 0.0) "
                         "!cu(1.0, 0.5, 0.5));\n")
    check_closed(frame)
    check_convex_planar(frame)
    assert abs(frame.volume() - 1.8) < 1e-9
    assert regularity_defects(frame) == []
    assert min(_thinness(p) for p in frame.polygons) > 1e-9

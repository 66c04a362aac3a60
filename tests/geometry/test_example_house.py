"""The example house is drawn as a house is built: no opening runs into another.

Issue 18, item 14: the middle south window (x 3.8-5.0) ran into the door
(x 4.0-5.0), leaving a 20 cm slot beside it in every picture and drawing.
The openings are the cutting boxes (the blue `!cu`) of the house; their boxes
in the scene, from the evaluated CSG tree, must be pairwise disjoint.
"""

from itertools import combinations
from pathlib import Path

from castor.csg import tree
from castor.run import evaluated_frames

HOUSE = Path(__file__).resolve().parents[2] / "examples" / "house.cas"
VITRE = (0.25, 0.45, 0.85)  # the cutting boxes' colour in house.cas


def _box(matrix):
    """The scene box of the unit cube placed by a 3x4 matrix."""
    corners = [(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)]
    points = [[matrix[4 * r] * x + matrix[4 * r + 1] * y + matrix[4 * r + 2] * z + matrix[4 * r + 3]
               for r in range(3)] for x, y, z in corners]
    return [min(p[i] for p in points) for i in range(3)], [max(p[i] for p in points) for i in range(3)]


def openings():
    [frame] = evaluated_frames(HOUSE.read_text(), str(HOUSE))[0]
    [house] = frame.objects
    return [(path, _box(matrix)) for primitive, matrix, path in tree.leaves(house.root)
            if primitive.kind == "cu" and primitive.colour == VITRE]


def test_the_house_has_its_openings():
    found = openings()
    assert len(found) >= 8
    assert any("porte_trou" in path for path, _ in found)


def test_no_opening_runs_into_another():
    overlapping = []
    for (a, (lo_a, hi_a)), (b, (lo_b, hi_b)) in combinations(openings(), 2):
        if all(lo_a[i] < hi_b[i] - 1e-9 and lo_b[i] < hi_a[i] - 1e-9 for i in range(3)):
            overlapping.append((a, [round(v, 3) for v in lo_a + hi_a],
                                b, [round(v, 3) for v in lo_b + hi_b]))
    assert overlapping == []


def test_each_opening_leaves_a_pier_of_wall_beside_the_next():
    """Not only disjoint: at least 40 cm of wall between neighbouring openings of
    one wall at the same height (a slot of 20 cm is what the issue saw)."""
    found = openings()
    for (a, (lo_a, hi_a)), (b, (lo_b, hi_b)) in combinations(found, 2):
        same_wall_y = lo_a[1] < hi_b[1] and lo_b[1] < hi_a[1] and hi_a[1] - lo_a[1] < 1
        overlap_z = lo_a[2] < hi_b[2] and lo_b[2] < hi_a[2]
        if same_wall_y and overlap_z:
            gap = max(lo_b[0] - hi_a[0], lo_a[0] - hi_b[0])
            assert gap >= 0.4, (a, b, gap)

"""Snapping beside an outline (CLI.md, "Editing on screen"): a ray that passes a
few pixels outside an object meets the ground or a face behind it, yet snaps to
the object's corner or edge within the radius, as a CAD program does; never to
one the camera cannot see, never to one further than the radius."""

from __future__ import annotations

import math

import numpy as np
import pytest

from castor.editing.document import Document, path_to_uri
from castor.editing.snap import snap

PIXEL = 0.001  # radians
EYE = (10.0, 12.0, 8.0)
BOX = "@t(1, 2, 0) @h(2, 3, 1.5) !cu(0.8, 0.8, 0.8)"  # x 1..3, y 2..5, z 0..1.5
CENTRE = np.array([2.0, 3.5, 0.75])
# the six corners on the cube's outline seen from EYE
OUTLINE = [(1, 5, 1.5), (3, 2, 1.5), (1, 5, 0), (3, 2, 0), (1, 2, 1.5), (3, 5, 0)]


def prepared(text: str, tmp_path):
    path = tmp_path / "scene.cas"
    path.write_text(text)
    document = Document(path_to_uri(str(path)), text).evaluate()
    assert not document.errors, document.errors
    return document.prepared(1)


def outside(target, pixels: float, away=CENTRE, eye=EYE):
    """The ray from ``eye`` passing ``pixels`` pixels off ``target``, on the screen
    away from ``away``."""
    eye, target = np.asarray(eye, float), np.asarray(target, float)
    d = (target - eye) / np.linalg.norm(target - eye)
    side = target - np.asarray(away, float)
    side -= (side @ d) * d
    side /= np.linalg.norm(side)
    return eye, d + math.tan(pixels * PIXEL) * side


def misses(scene, origin, direction) -> bool:
    t, _ = scene.solids.traced.first_hit(np.asarray(origin)[None], np.asarray(direction)[None])
    return not np.isfinite(t[0])


@pytest.mark.parametrize("corner", OUTLINE)
def test_three_pixels_outside_a_cube_corner_snaps_to_it_exactly(tmp_path, corner):
    scene = prepared(f"> {BOX};\n", tmp_path)
    origin, direction = outside(corner, 3)
    assert misses(scene, origin, direction)  # the ray passes beside the cube
    found = snap(scene, origin, direction, pixel=PIXEL)
    assert found.feature == "corner"
    assert found.point == tuple(float(v) for v in corner)
    assert found.path == "!cu"


def test_thirty_pixels_outside_is_the_ground(tmp_path):
    scene = prepared(f"> {BOX};\n", tmp_path)
    for corner in OUTLINE:
        found = snap(scene, *outside(corner, 30), pixel=PIXEL)
        assert found.feature == "grid" and found.point[2] == 0.0


def test_the_corner_before_a_face_behind(tmp_path):
    """The cube stands on a slab: the ray beside it meets the slab's top."""
    scene = prepared(f"> $U({BOX}, @t(-5, -5, -0.2) @h(20, 20, 0.2) !cu(0.5, 0.5, 0.5));\n",
                     tmp_path)
    origin, direction = outside((1, 5, 1.5), 3)
    assert not misses(scene, origin, direction)
    found = snap(scene, origin, direction, pixel=PIXEL)
    assert (found.feature, found.point, found.path) == ("corner", (1.0, 5.0, 1.5), "U1!cu")
    far = snap(scene, *outside((1, 5, 1.5), 30), pixel=PIXEL)
    assert far.feature == "face" and far.path == "U2!cu"


def test_an_edge_and_its_middle_beside_the_outline(tmp_path):
    scene = prepared(f"> {BOX};\n", tmp_path)
    # the upright edge x = 1, y = 5 from z = 0 to 1.5 is on the outline
    found = snap(scene, *outside((1, 5, 0.4), 3, away=(2, 4, 0.4)), pixel=PIXEL)
    assert found.feature == "edge"
    x, y, z = found.point
    assert (x, y) == (1.0, 5.0) and 0.38 < z < 0.42
    found = snap(scene, *outside((1, 5, 0.75), 3, away=(2, 4, 0.75)), pixel=PIXEL)
    assert found.feature == "midpoint" and found.point == pytest.approx((1, 5, 0.75), abs=1e-12)


def test_a_hidden_corner_is_not_taken(tmp_path):
    """The far bottom corner (1, 2, 0) is drawn inside the outline, behind the cube."""
    scene = prepared(f"> {BOX};\n", tmp_path)
    found = snap(scene, *outside((1, 2, 0), 2, away=(3, 5, 1.5)), pixel=PIXEL)
    assert found.feature == "face" and found.point[2] == 1.5  # the top face, in front


def test_orthographic_beside_the_outline(tmp_path):
    scene = prepared(f"> {BOX};\n", tmp_path)
    size = 0.002  # metres per pixel
    direction = np.array([-7.0, -7.0, -6.5])
    direction /= np.linalg.norm(direction)
    corner = np.array([1.0, 5.0, 1.5])
    side = corner - CENTRE
    side -= (side @ direction) * direction
    side /= np.linalg.norm(side)
    near = snap(scene, corner - 30 * direction + 3 * size * side, direction, pixel_size=size)
    assert (near.feature, near.point) == ("corner", (1.0, 5.0, 1.5))
    far = snap(scene, corner - 30 * direction + 30 * size * side, direction, pixel_size=size)
    assert far.feature == "grid"


def test_in_a_plan_the_top_corner_before_the_bottom_one(tmp_path):
    """Looking straight down, the top and bottom corners are drawn at one place:
    the one in front (on top) is taken."""
    scene = prepared(f"> {BOX};\n", tmp_path)
    size = 0.005
    down = (0.0, math.cos(math.radians(90)), -1.0)  # as the page's plan sends it: y 6e-17
    for pixels in (0, 0.2, 3):
        for corner in ((3.0, 5.0), (3.0, 2.0), (1.0, 2.0)):
            away = np.sign(np.subtract(corner, (2.0, 3.5)))
            origin = (*(corner + away * (pixels * size + 7e-8)), 14.0)
            found = snap(scene, origin, down, pixel_size=size)
            assert (found.feature, found.point) == ("corner", (*corner, 1.5))


@pytest.mark.parametrize("angle", [90, 150, 200])
def test_the_rim_of_a_column_beside_its_top(tmp_path, angle):
    """A ray 3 pixels beyond a column's top rim (seen from above) snaps to the rim."""
    scene = prepared("> @t(1, 2, 0) @h(0.3, 0.3, 2.5) !cy(0.8, 0.8, 0.8);\n", tmp_path)
    eye = (8.0, -6.0, 5.0)
    a = math.radians(angle)
    rim = (1 + 0.3 * math.cos(a), 2 + 0.3 * math.sin(a), 2.5)
    origin, direction = outside(rim, 3, away=(1, 2, 2.5), eye=eye)
    assert misses(scene, origin, direction)
    found = snap(scene, origin, direction, pixel=PIXEL)
    assert found.feature == "edge" and found.path == "!cy"
    x, y, z = found.point
    assert z == pytest.approx(2.5, abs=1e-12)
    assert math.hypot(x - 1, y - 2) == pytest.approx(0.3, abs=1e-9)
    assert math.dist(found.point, rim) < 0.01  # the rim's point beside the pointer
    far = snap(scene, *outside(rim, 30, away=(1, 2, 2.5), eye=eye), pixel=PIXEL)
    assert far.feature == "grid"

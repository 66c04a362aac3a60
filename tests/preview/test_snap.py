"""Snapping on the exact solids (CLI.md, "Editing on screen"): scenes whose
corners, edges, centres and surfaces are known, rays a few pixels off them."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from castor.editing.document import Document, path_to_uri
from castor.editing.snap import snap

PIXEL = 0.001  # radians


def prepared(text: str, tmp_path, frame: int = 1):
    path = tmp_path / "scene.cas"
    path.write_text(text)
    document = Document(path_to_uri(str(path)), text).evaluate()
    assert not document.errors, document.errors
    return document.prepared(frame), str(path)


def ray(eye, target, pixels: float = 0.0, towards=None):
    """The ray from ``eye`` that passes ``pixels`` pixels off ``target``, on the side of
    ``towards`` (on the screen)."""
    eye, target = np.asarray(eye, float), np.asarray(target, float)
    d = (target - eye) / np.linalg.norm(target - eye)
    if pixels:
        side = np.asarray(towards, float) - target
        side -= (side @ d) * d
        side /= np.linalg.norm(side)
        d = d + math.tan(pixels * PIXEL) * side
    return eye, d


CUBE = "> @t(1, 2, 0) @h(2, 3, 1.5) !cu(0.8, 0.8, 0.8);\n"
EYE = (10.0, 12.0, 8.0)


def test_a_cube_corner_from_a_ray_three_pixels_off(tmp_path):
    scene, path = prepared(CUBE, tmp_path)
    found = snap(scene, *ray(EYE, (3, 5, 1.5), 3, towards=(2, 3.5, 0.75)), pixel=PIXEL)
    assert found.feature == "corner"
    assert found.point == (3.0, 5.0, 1.5)
    assert found.source == f"{path}:1:29" and found.path == "!cu"


def test_a_corner_further_than_ten_pixels_is_not_taken(tmp_path):
    scene, _ = prepared(CUBE, tmp_path)
    found = snap(scene, *ray(EYE, (3, 5, 1.5), 14, towards=(2, 3.5, 0.75)), pixel=PIXEL)
    assert found.feature != "corner"


def test_where_a_wall_meets_the_roof_is_a_corner(tmp_path):
    """The roof slab, tilted 10 degrees, meets the wall's top (z = 2.5) and front
    (y = 0) at a point no primitive has as a corner."""
    scene, path = prepared(
        "mur = @h(4, 0.2, 2.5) !cu(0.9, 0.9, 0.9);\n"
        "toit = @t(-0.5, -0.5, 2.3) @ry(-10) @h(5, 1.2, 0.2) !cu(0.7, 0.3, 0.2);\n"
        "> $U(mur, toit);\n", tmp_path)
    x = -0.5 + 0.2 / math.tan(math.radians(10))
    eye = (10.0, -20.0, 1.0)
    found = snap(scene, *ray(eye, (x, 0, 2.5), 4, towards=(2, 0, 1)), pixel=PIXEL)
    assert found.feature == "corner"
    assert found.point == pytest.approx((x, 0.0, 2.5), abs=1e-9)
    assert found.path == "U1(mur)!cu" and found.source == f"{path}:1:23"


def test_a_sphere_point_lies_on_the_sphere(tmp_path):
    scene, path = prepared("> @t(1, 2, 3) @h(2) !sp(0.2, 0.5, 0.8);\n", tmp_path)
    eye = np.array([12.0, -9.0, 7.0])
    origin, direction = ray(eye, (1.3, 1.6, 3.4))
    found = snap(scene, origin, direction, pixel=PIXEL)
    assert found.feature == "face" and found.path == "!sp"
    point = np.array(found.point)
    assert abs(np.linalg.norm(point - [1, 2, 3]) - 2) < 1e-9
    rel = point - origin
    assert np.linalg.norm(rel - (rel @ direction) * direction) < 1e-9  # on the ray too


def test_the_middle_of_an_edge(tmp_path):
    scene, _ = prepared(CUBE, tmp_path)
    # the top edge x = 3, z = 1.5 runs from y = 2 to y = 5: its middle is y = 3.5
    found = snap(scene, *ray(EYE, (3, 3.5, 1.5), 3, towards=(2, 3.5, 0.75)), pixel=PIXEL)
    assert found.feature == "midpoint"
    assert found.point == pytest.approx((3.0, 3.5, 1.5), abs=1e-12)


def test_an_edge_away_from_its_middle_and_its_ends(tmp_path):
    scene, _ = prepared(CUBE, tmp_path)
    found = snap(scene, *ray(EYE, (3, 2.7, 1.5), 4, towards=(2, 3.5, 0.75)), pixel=PIXEL)
    assert found.feature == "edge"
    x, y, z = found.point
    assert (x, z) == pytest.approx((3.0, 1.5), abs=1e-12) and 2.6 < y < 2.8


def test_the_centre_of_a_flat_face(tmp_path):
    scene, _ = prepared(CUBE, tmp_path)
    found = snap(scene, *ray(EYE, (2, 3.5, 1.5), 5, towards=(3, 5, 1.5)), pixel=PIXEL)
    assert found.feature == "centre"
    assert found.point == pytest.approx((2.0, 3.5, 1.5), abs=1e-12)


def test_a_seam_inside_a_union_is_no_edge(tmp_path):
    scene, _ = prepared("> $U(@h(4, 2, 1) !cu(1, 1, 1), @t(4, 0, 0) @h(4, 2, 1) !cu(1, 1, 1));\n",
                        tmp_path)
    found = snap(scene, *ray((4.0, -6.0, 9.0), (4.0, 0.7, 1.0)), pixel=PIXEL)
    assert found.feature == "face"  # on the one top face, as if it were one block


def test_a_flat_face_point_on_the_grid(tmp_path):
    scene, _ = prepared(CUBE, tmp_path)
    found = snap(scene, *ray(EYE, (2.37, 5, 0.62)), pixel=PIXEL)
    assert found.feature == "face"
    assert found.point == pytest.approx((2.35, 5.0, 0.6), abs=1e-12)


def test_the_axes_from_the_previous_point(tmp_path):
    scene, _ = prepared(CUBE, tmp_path)
    previous = (3.0, 5.0, 0.0)
    # towards (3, 7.3, 0), above the ground beside the cube: the y axis
    found = snap(scene, *ray(EYE, (3.0, 7.3, 0.0), 4, towards=(6, 7.3, 0)), pixel=PIXEL,
                 previous=previous)
    assert found.feature == "axis y"
    x, y, z = found.point
    assert (x, z) == (3.0, 0.0) and 7.2 < y < 7.4


def test_a_typed_distance_is_exact(tmp_path):
    scene, _ = prepared(CUBE, tmp_path)
    previous = (3.0, 5.0, 0.0)
    found = snap(scene, *ray(EYE, (3.0, 7.3, 0.0), 4, towards=(6, 7.3, 0)), pixel=PIXEL,
                 previous=previous, distance=2.35)
    assert found.point == (3.0, 7.35, 0.0)


def test_nothing_hit_snaps_to_the_ground_grid(tmp_path):
    scene, _ = prepared(CUBE, tmp_path)
    found = snap(scene, *ray(EYE, (7.33, -2.61, 0)), pixel=PIXEL)
    assert found.feature == "grid" and found.source is None and found.path is None
    assert found.point == pytest.approx((7.35, -2.6, 0.0), abs=1e-12)


def test_a_ray_into_the_sky_snaps_to_nothing(tmp_path):
    scene, _ = prepared(CUBE, tmp_path)
    assert snap(scene, EYE, (0.1, 0.2, 1.0), pixel=PIXEL) is None


def test_an_orthographic_view_counts_pixels_in_metres(tmp_path):
    scene, _ = prepared(CUBE, tmp_path)
    # looking straight down; the corner (3, 5, 1.5) from 0.02 m away: 2 pixels of 0.01 m
    found = snap(scene, (2.985, 4.985, 50.0), (0, 0, -1), pixel_size=0.01)
    assert found.feature == "corner" and found.point == (3.0, 5.0, 1.5)
    found = snap(scene, (2.8, 4.8, 50.0), (0, 0, -1), pixel_size=0.01)
    assert found.feature != "corner"


def test_the_snap_command_answers_as_the_table_says(tmp_path):
    from castor.editing.commands import Cache, execute

    path = tmp_path / "scene.cas"
    path.write_text(CUBE)
    origin, direction = ray(EYE, (3, 5, 1.5), 3, towards=(2, 3.5, 0.75))
    answer = execute("castor.snap", [{"uri": path_to_uri(str(path)), "frame": 1,
                                      "origin": list(origin), "direction": list(direction),
                                      "pixel": PIXEL}], Cache())
    assert answer == {"point": [3.0, 5.0, 1.5], "feature": "corner",
                      "source": f"{path}:1:29", "path": "!cu"}
    assert execute("castor.snap", {"uri": path_to_uri(str(path)), "origin": list(EYE),
                                   "direction": [0, 0, 1], "pixel": PIXEL}, Cache()) is None


@pytest.mark.parametrize("arguments, message", [
    ({"origin": [0, 0, 5], "direction": [0, 0, 0], "pixel": PIXEL}, "zero length"),
    ({"origin": [0, 0, 5], "direction": [0, 0, -1]}, "'pixel'"),
    ({"origin": [0, 0, 5], "direction": [0, 0, -1], "pixel": -1}, "more than 0"),
    ({"origin": [0, 0, "5"], "direction": [0, 0, -1], "pixel": PIXEL}, "must be a number"),
    ({"origin": [0, 0, 5], "direction": [0, 0, -1], "pixel": PIXEL, "distance": 2},
     "needs the previous point"),
    ({"origin": [0, 0, 5], "direction": [0, 0, -1], "pixel": PIXEL, "frame": 2}, "frame 2"),
])
def test_bad_snaps_are_refused(tmp_path, arguments, message):
    from castor.editing.commands import Cache, CommandError, snap as command

    path = tmp_path / "scene.cas"
    path.write_text(CUBE)
    with pytest.raises(CommandError, match=message):
        command({"uri": path_to_uri(str(path)), **arguments}, Cache())


def test_parallels_and_perpendiculars_of_the_edges_from_the_previous_point(tmp_path):
    scene, _ = prepared("> @rz(30) @h(2, 1, 1) !cu(1, 1, 1);\n", tmp_path)
    along = np.array([math.cos(math.radians(30)), math.sin(math.radians(30)), 0.0])
    across = np.array([-along[1], along[0], 0.0])
    eye = (1.0, -8.0, 6.0)
    found = snap(scene, *ray(eye, 3.2 * along, 3, towards=(5, 5, 0)), pixel=PIXEL,
                 previous=(0, 0, 0))
    assert found.feature == "parallel"
    assert np.linalg.norm(np.cross(found.point, along)) < 1e-9
    # from the middle of the front edge, square to it in the ground
    middle = 1.0 * along
    found = snap(scene, *ray(eye, middle - 2.4 * across, 3, towards=(5, -5, 0)), pixel=PIXEL,
                 previous=tuple(middle))
    assert found.feature == "perpendicular"
    assert np.linalg.norm(np.cross(found.point - middle, across)) < 1e-9


HOUSE_PREPARED: dict = {}


@settings(max_examples=60, deadline=None)
@given(st.floats(-0.45, 0.45), st.floats(-0.35, 0.25), st.booleans())
def test_a_snap_is_never_more_than_ten_pixels_off_the_ray(right, up, with_previous):
    """On the house (a roof cut from two extrusions, walls with openings, a chimney
    through a slope): whatever the ray, the point snapped is within 10 pixels
    of it, and a corner, an edge or a centre lies on the solid's surface."""
    from pathlib import Path

    if not HOUSE_PREPARED:
        path = Path(__file__).resolve().parents[2] / "examples" / "house.cas"
        document = Document(path_to_uri(str(path)), path.read_text()).evaluate()
        HOUSE_PREPARED["scene"] = document.prepared(1)
    scene = HOUSE_PREPARED["scene"]
    eye = np.array([-9.0, -12.0, 9.0])
    forward = np.array([13.5, 15.25, -6.0]) / np.linalg.norm([13.5, 15.25, -6.0])
    side = np.cross(forward, [0, 0, 1.0])
    side /= np.linalg.norm(side)
    direction = forward + right * side + up * np.cross(side, forward)
    direction /= np.linalg.norm(direction)
    previous = (4.5, 0.0, 2.9) if with_previous else None
    found = snap(scene, eye, direction, pixel=0.002, previous=previous)
    if found is None:
        return
    rel = np.array(found.point) - eye
    depth = rel @ direction
    assert depth > 0
    assert np.linalg.norm(rel - depth * direction) <= 10 * 0.002 * depth * (1 + 1e-9)
    if found.feature in ("corner", "edge", "midpoint", "centre"):
        solids = scene.solids
        k = np.arange(400) + 0.5  # directions spread over the sphere (a thin eave is a wedge)
        z = 1 - 2 * k / 400
        turn = np.pi * (1 + 5 ** 0.5) * k
        ring = np.sqrt(1 - z * z)
        directions = np.column_stack([ring * np.cos(turn), ring * np.sin(turn), z])
        inside = solids.inside(np.array(found.point) + solids.step * directions)
        assert inside.any() and not inside.all()  # on the boundary of the solid


def test_the_rim_of_a_column_is_an_edge(tmp_path):
    scene, _ = prepared("> @t(2, 3, 0) @h(0.5, 0.5, 3) !cy(0.5, 0.5, 0.5);\n", tmp_path)
    # looking down at the top, 4 pixels inside the rim
    rim = np.array([2 + 0.5 * math.cos(0.7), 3 + 0.5 * math.sin(0.7), 3.0])
    found = snap(scene, *ray((12.0, 11.0, 14.0), rim, 4, towards=(2, 3, 3)), pixel=PIXEL)
    assert found.feature == "edge"
    x, y, z = found.point
    assert z == pytest.approx(3.0, abs=1e-12)
    assert math.hypot(x - 2, y - 3) == pytest.approx(0.5, abs=1e-9)

"""Pictures of the exact solids (OUTPUT.md "Pictures"), checked from their pixels."""

from __future__ import annotations

import io
import os
import subprocess
import sys

import numpy as np
import pytest

from castor.primitives import PRIMITIVES
from castor.settings import View
from castor.pictures.camera import make_camera
from castor.pictures.spans import SPANS
from castor.pictures.trace import compile_frame
from tests.support.pictures import camera_of, covered, draw, scene_frames, WHITE
from tests.support.vocabulary import arguments_text, example_shape, primitive_names


def test_every_primitive_has_its_spans():
    assert set(SPANS) == set(PRIMITIVES) | {"smooth"}  # smooth solids: castor.pictures.mesh_rays


# shapes chosen for these; every other primitive with a shape its check accepts
SHAPES = {"to": ", 0.3", "pr": ", 6", "py": ", 5", "ex": ", 0, 0, 1, 0, 1, 1, 0.5, 0.4, 0, 1",
          "rv": ", 0, 0, 1, 0, 1, 0.3, 0.4, 0.5, 0.4, 1, 0, 1"}


@pytest.mark.parametrize("kind, shape", [
    (kind, SHAPES.get(kind, arguments_text(example_shape(kind)))) for kind in primitive_names()
])
def test_every_primitive_is_drawn_where_its_box_projects(kind, shape):
    """Seen from above, each unit primitive covers pixels, all inside its box."""
    text = f"> !{kind}(0.2, 0.5, 0.3{shape});"
    image = draw(text, view=View("top", 0, 0))
    cover = covered(image)
    assert cover.sum() > 200
    camera = camera_of(text, view=View("top", 0, 0))
    low, high = compile_frame(scene_frames(text)[0]).box
    (x0, y1), (x1, y0) = camera.project(np.array([low, high]))[0]
    ys, xs = np.nonzero(cover)
    assert xs.min() >= np.floor(x0) - 1 and xs.max() <= np.ceil(x1) + 1
    assert ys.min() >= np.floor(y0) - 1 and ys.max() <= np.ceil(y1) + 1


@pytest.mark.parametrize("tolerance", [0.5, 0.01])
def test_a_sphere_from_above_is_a_true_circle(tolerance):
    """The disc's edge lies within half a pixel of the true circle, whatever the
    facet tolerance: a 16-sided polygon (what TOLERANCE = 0.5 gives the
    facets) would stray by more than a pixel at this size."""
    text = f"TOLERANCE = {tolerance}; > @h(2) !sp(0.8, 0.1, 0.1);"
    options = {"view": View("top", 0, 0), "size": (240, 240)}
    image = draw(text, **options)
    camera = camera_of(text, **options)
    (cx, cy), = camera.project(np.zeros((1, 3)))[0]
    radius = 2 * camera.scale
    assert radius > 100
    ys, xs = np.mgrid[0:240, 0:240]
    distance = np.hypot(xs + 0.5 - cx, ys + 0.5 - cy)
    cover = covered(image)
    assert np.all(cover[distance < radius - 0.5])
    assert not np.any(cover[distance > radius + 0.5])
    assert np.any(cover[(distance > radius - 0.5) & (distance < radius + 0.5)])


def test_the_picture_does_not_depend_on_the_tolerance():
    coarse = draw("TOLERANCE = 0.5; > $D(@h(2) !cy(0.5, 0.5, 0.5), @t(1, 0, 1) !sp(1, 0, 0));")
    fine = draw("TOLERANCE = 0.001; > $D(@h(2) !cy(0.5, 0.5, 0.5), @t(1, 0, 1) !sp(1, 0, 0));")
    assert np.array_equal(coarse, fine)


@pytest.mark.parametrize("view", [View("front", 0, 0), View(None, -90, 0)])
def test_a_cylinder_seen_side_on_has_straight_silhouettes(view):
    image = draw("> @h(1, 1, 3) !cy(0.2, 0.3, 0.8);", view=view, size=(200, 200))
    cover = covered(image)
    rows = np.flatnonzero(cover.any(axis=1))
    middle = rows[len(rows) // 4: 3 * len(rows) // 4]
    # the edge of each row, to a fraction of a pixel, from the partly covered pixel
    darkness = (WHITE - image[..., 0].astype(float))
    edges = []
    for row in middle:
        inside = np.flatnonzero(cover[row])
        first = inside[0]
        full = darkness[row, first + 2]
        edges.append(first + 1 - darkness[row, first] / full)
    assert len(middle) > 40
    assert np.ptp(edges) < 0.1


def test_a_cut_shows_the_cutters_colour():
    """$D of a box by a sphere: the cut corner is the sphere's colour."""
    text = "> $D(@h(2) !cu(0.9, 0.9, 0.9), @t(2, 2, 2) @h(1.2) !sp(0.9, 0.1, 0.1));"
    options = {"view": View(None, 45, 35), "size": (200, 150)}
    image = draw(text, **options)
    camera = camera_of(text, **options)
    (x, y), = camera.project(np.array([[2.0, 2.0, 2.0]]))[0]
    r, g, b = image[int(y), int(x)].astype(int)
    assert r > 2 * g and r > 2 * b  # red: the sphere's inside
    # beside the cut, the box's own grey
    (x, y), = camera.project(np.array([[2.0, 0.3, 1.0]]))[0]
    r, g, b = image[int(y), int(x)].astype(int)
    assert abs(r - g) < 8 and abs(g - b) < 8


TABLE = ("> $U(@t(0, 0, 1) @h(4, 4, 0.2) !cu(0.6, 0.6, 0.6),"
         " @t(1.9, 1.9, 0) @h(0.2, 0.2, 1) !cu(0.6, 0.6, 0.6));")


@pytest.mark.parametrize("sun", [(0.0, 90.0), None])
def test_the_sun_shades_the_ground_under_a_raised_slab(sun):
    options = {"eye": (2.0, -12.0, 1.5), "look": (2.0, 2.0, 0.5), "size": (200, 150)}
    image = draw(TABLE, sun=sun, **options).astype(int)
    camera = camera_of(TABLE, **options)
    (xu, yu), (xb, yb) = camera.project(np.array([[3.0, 1.0, 0.0], [6.5, 1.0, 0.0]]))[0]
    under = image[int(yu), int(xu)].sum()
    beside = image[int(yb), int(xb)].sum()
    if sun is None:
        assert abs(under - beside) <= 3
    else:
        assert under < beside - 60


def test_castor_and_castor_view_cover_the_same_pixels():
    """The exact picture and castor-view's facets differ only along edges."""
    from scipy import ndimage

    from castor.view.render import render
    from castor.formats.cps import load

    text = ("> $U($D(@h(3, 2, 1.5) !cu(0.8, 0.7, 0.5), @t(1.5, 1, 1.5) @h(0.8) !sp(0.2, 0.3, 0.9)),"
            " @t(4, 1, 0) @h(0.7, 0.7, 2) !cy(0.3, 0.6, 0.3));")
    for options in ({"eye": (9.0, -7.0, 5.0), "look": (2.0, 1.0, 0.5)},
                    {"view": View("front", 0, 0)}):
        exact = covered(draw(text, **options, size=(320, 240)))
        stream = subprocess.run([sys.executable, "-m", "castor", "-t", "0.002"],
                                input=text.encode(), capture_output=True, check=True).stdout
        frame = next(load(iter(io.StringIO(stream.decode()).readline, "")))
        camera = camera_of(text, **options, size=(320, 240))
        facets = covered(render(frame, camera, 320, 240))
        differ = exact ^ facets
        border = exact ^ ndimage.binary_erosion(exact)
        near_border = ndimage.binary_dilation(border, iterations=2)
        assert exact.sum() > 5000
        assert not np.any(differ & ~near_border)


def _castor(args, cwd, stdin=None):
    env = dict(os.environ)
    return subprocess.run([sys.executable, "-m", "castor", *args], cwd=cwd, input=stdin,
                          capture_output=True, env=env)


ANIMATION = b">[T = 0, 2] @t(T, 0, 0) @rz(20 * T) !cu(0.8, 0.3, 0.2);\n"


def test_png_gif_and_patterns_from_the_command_line(tmp_path):
    from PIL import Image

    (tmp_path / "s.cas").write_bytes(ANIMATION)
    small = ["--size", "64x48", "--samples", "1"]
    (tmp_path / "one.cas").write_bytes(b"> !cu(0.8, 0.3, 0.2);")
    done = _castor(["-o", "one.png", *small, "one.cas"], tmp_path)
    assert done.returncode == 0, done.stderr
    with Image.open(tmp_path / "one.png") as image:
        assert image.size == (64, 48) and image.format == "PNG"
    done = _castor(["-f", "png", *small, "-"], tmp_path, stdin=b"> !sp(0.5, 0.5, 0.9);")
    assert done.returncode == 0 and done.stdout.startswith(b"\x89PNG\r\n\x1a\n")
    with Image.open(io.BytesIO(done.stdout)) as image:
        assert image.size == (64, 48)
        assert covered(np.asarray(image.convert("RGB"))).sum() > 100
    done = _castor(["-o", "x-%02d.png", *small, "s.cas"], tmp_path)
    assert done.returncode == 0, done.stderr
    assert sorted(p.name for p in tmp_path.glob("x-*.png")) == ["x-01.png", "x-02.png",
                                                                  "x-03.png"]
    done = _castor(["-o", "all.gif", *small, "s.cas"], tmp_path)
    assert done.returncode == 0, done.stderr
    with Image.open(tmp_path / "all.gif") as image:
        assert image.format == "GIF" and image.n_frames == 3


# --- castor-view: outlines only, anti-aliased, castor's camera ---------------

FRAME_WITH_A_HOLE = ("> $D(@h(4, 4, 1) !cu(0.8, 0.8, 0.8),"
                     " @t(1, 1, -1) @h(2, 2, 3) !cu(0.8, 0.8, 0.8));")


def _view(text: str, mode: str, view: View, size=(200, 200)) -> tuple[np.ndarray, object]:
    from castor.view.render import render
    from castor.formats.cps import load

    stream = subprocess.run([sys.executable, "-m", "castor"], input=text.encode(),
                            capture_output=True, check=True).stdout
    frame = next(load(iter(io.StringIO(stream.decode()).readline, "")))
    low, high = frame.points.min(axis=0), frame.points.max(axis=0)
    camera = make_camera(low, high, size, view)
    return render(frame, camera, size[0], size[1], mode), camera


@pytest.mark.parametrize("mode", ["wire", "edges"])
def test_castor_view_draws_outlines_not_the_pieces_of_a_flat_face(mode):
    """The top of a square frame is cut into convex polygons; seen from above,
    only the outer and inner squares are drawn."""
    image, camera = _view(FRAME_WITH_A_HOLE, mode, View("top", 0, 0))
    xy = camera.project(np.array([[0.0, 0.0, 1.0], [1.0, 1.0, 1.0], [3.0, 3.0, 1.0],
                                  [4.0, 4.0, 1.0]]))[0]
    lines_x, lines_y = xy[:, 0], xy[:, 1]
    dark = image.min(axis=2) < 200  # lines, anti-aliased
    ys, xs = np.nonzero(dark)
    assert len(xs) > 400  # the outlines are there
    near_x = np.min(np.abs(xs[:, None] + 0.5 - lines_x[None, :]), axis=1) <= 1.5
    near_y = np.min(np.abs(ys[:, None] + 0.5 - lines_y[None, :]), axis=1) <= 1.5
    assert np.all(near_x | near_y)


def test_castor_view_is_anti_aliased_and_lit_as_castor():
    image, _ = _view("> @rz(30) @h(2, 2, 1) !cu(0.2, 0.4, 0.9);", "shaded", View("top", 0, 0))
    blue = image[..., 2].astype(int)
    red = image[..., 0].astype(int)
    face = red[100, 100]
    partial = (red > face + 10) & (red < WHITE - 10)
    assert partial.sum() > 100  # the silhouette's pixels are blended
    assert blue[100, 100] > 0.75 * 0.9 * 255  # a face turned to the viewer: near its colour


def test_a_cutter_flush_with_a_face_leaves_no_speckle():
    """A door cut by a box flush with the wall's foot: the doorway's floor has
    no face (the meshes have none), so no pixel of the cutter's colour shows
    there from above, with or without the sun."""
    scene = ("> $D(@h(3, 0.2, 2.6) !cu(1, 1, 1), "
             "@t(1, -0.1, 0) @h(1, 0.4, 2.1) !cu(0.2, 0.4, 0.9));")
    for sun in (None, (0.0, 90.0)):
        image = draw(scene, sun=sun, size=(400, 300)).astype(int)
        blue = image[..., 2] > image[..., 0] + 40
        # the blue jamb is one solid region; a speckled floor is blue pixels
        # with hardly a blue neighbour
        neighbours = (np.roll(blue, 1, 0).astype(int) + np.roll(blue, -1, 0)
                      + np.roll(blue, 1, 1) + np.roll(blue, -1, 1))
        assert blue.sum() > 100  # the jamb is seen
        assert (blue & (neighbours <= 1)).sum() <= 5

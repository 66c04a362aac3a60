"""castor-view on smooth solids (LANGUAGE.md §7.1: drawings show a smooth
solid's creases and silhouette, never the lines between its facets) and its
help, which names the views from the one table (castor.options)."""

from __future__ import annotations

import numpy as np

from tests.support.cli import run


def pictures(scene: str, mode: str, view=(-60.0, 25.0)):
    """castor's stream of ``scene``, drawn by castor-view's renderer: one
    image per frame, 240 x 180."""
    from castor.formats.cps import load
    from castor.settings import View
    from castor.pictures.camera import make_camera
    from castor.view.render import render

    status, stream, err = run("--no-cpp", "-q", stdin=scene)
    assert status == 0, err
    images = []
    for picture in load(iter(stream.splitlines(keepends=True))):
        camera = make_camera(picture.points.min(axis=0), picture.points.max(axis=0), (240, 180),
                             View(None, *view), None, None)
        images.append(render(picture, camera, 240, 180, mode))
    return images


def lines_inside(scene: str) -> list[float]:
    """For each frame: the share of the pixels well inside the outline that
    ``--edges`` darkens (lines drawn across the surface)."""
    shares = []
    for plain, edged in zip(pictures(scene, "shaded"), pictures(scene, "edges")):
        covered = np.any(plain != 255, axis=2)
        # the outline and a band of 6 pixels inside it left out
        inside = covered.copy()
        for _ in range(6):
            inside[1:-1, 1:-1] &= inside[:-2, 1:-1] & inside[2:, 1:-1] & inside[1:-1, :-2] \
                & inside[1:-1, 2:]
        darker = plain.astype(int).sum(axis=2) - edged.astype(int).sum(axis=2) > 60
        shares.append(float(darker[inside].mean()))
    return shares


def test_a_smooth_solid_is_drawn_without_its_facets_lines():
    smooth, sphere, blob = lines_inside(
        "> @s(120) @h(2, 2, 1) !cu(0.8, 0.6, 0.4);\n> !sp(0.8, 0.6, 0.4);\n"
        "> @s(180) $U(@h(2, 1, 1) !cu(0.8, 0.6, 0.4), @t(0.5, 0.5, 0.5) @h(0.5, 0.5, 1) "
        "!cy(0.2, 0.4, 0.9));")
    # (lines between the facets darkened 42 % of the smooth cube, 52 % of the blob)
    assert smooth < 0.005 and sphere < 0.005
    # the union smoothed: its two colours meet along a seam (drawn, as the
    # edge between two solids is), its facets draw nothing
    assert blob < 0.03


def test_a_surface_curved_one_way_is_drawn_without_its_facets_lines():
    # @s(65) on a hexagonal prism: the rims stay creases, the side is curved
    # around only; its facets, in vertical strips, are never merged by castor
    # as a flat face's pieces are (10 % of the picture was lines before; the
    # 1.4 % left is the front rim, a crease, inside the outline)
    side, = lines_inside("> @s(65) @h(1, 1, 1.5) !pr(0.6, 0.8, 0.4, 6);")
    assert side < 0.025
    # a prism of 24 sides keeps its 24 edges (test_flat_solids_keep_their_edges)


def test_flat_solids_keep_their_edges():
    # a cube's edges, and the hips of a pyramid of 32 sides (turning by a
    # few degrees: the apex, where 32 edges meet, is one such vertex, a
    # smooth solid has hundreds), a prism of 24 sides
    cube, pyramid, prism = lines_inside("> !cu(0.8, 0.6, 0.4);\n> !py(0.8, 0.6, 0.4, 32);\n"
                                        "> !pr(0.8, 0.6, 0.4, 24);")
    assert cube > 0.01 and pyramid > 0.05 and prism > 0.05


def _interior(image: np.ndarray, band: int = 3) -> np.ndarray:
    """The pixels the solids cover, less a band of ``band`` pixels inside the outline."""
    inside = np.any(image != 255, axis=2)
    for _ in range(band):
        inside[1:-1, 1:-1] &= inside[:-2, 1:-1] & inside[2:, 1:-1] & inside[1:-1, :-2] \
            & inside[1:-1, 2:]
    return inside


def brightness_steps(image: np.ndarray) -> np.ndarray:
    """How much brighter or darker (the three channels' sum, 0..765) each pixel
    inside the solids is than its neighbour to the right and below."""
    brightness = image.astype(int).sum(axis=2)
    inside = _interior(image)
    across = (inside[:, :-1] & inside[:, 1:], brightness[:, :-1] - brightness[:, 1:])
    down = (inside[:-1] & inside[1:], brightness[:-1] - brightness[1:])
    return np.abs(np.concatenate([step[both] for both, step in (across, down)]))


def test_the_facets_of_a_smooth_solid_are_shaded_smoothly():
    # (issue 19 item 5) shaded flat, each facet of one colour, the brightness
    # stepped by 108 and 79 between neighbouring pixels at the facets' edges
    box, sphere = pictures("> @s(120) @h(2, 2, 1) !cu(0.8, 0.6, 0.4);\n> !sp(0.8, 0.6, 0.4);\n",
                           "shaded")
    assert brightness_steps(box).max() < 40 and brightness_steps(sphere).max() < 40
    # and shaded: not one colour (the steps are small, the range is not)
    for image in (box, sphere):
        brightness = image.astype(int).sum(axis=2)[_interior(image)]
        assert brightness.max() - brightness.min() > 100


def test_flat_faces_stay_flat_and_creases_sharp():
    cube, prism = pictures("> !cu(0.8, 0.6, 0.4);\n> @s(65) @h(1, 1, 1.5) !pr(0.6, 0.8, 0.4, 6);\n",
                           "shaded")
    # the cube: three faces of one colour each, and a step where two meet
    inside = _interior(cube)
    _, counts = np.unique(cube[inside], axis=0, return_counts=True)
    assert np.sort(counts)[-3:].sum() > 0.97 * inside.sum()
    assert brightness_steps(cube).max() > 40
    # the smoothed prism's rims stay creases between its caps and its side
    assert brightness_steps(prism).max() > 100


def test_the_help_names_every_view_of_the_table():
    from castor.settings import VIEW_NAMES

    status, out, _ = run_view("--help")
    assert status == 0
    text = " ".join(out.split())
    assert f"or {', '.join(VIEW_NAMES)} (orthographic)" in text


def run_view(*args):
    import subprocess
    import sys

    result = subprocess.run([sys.executable, "-m", "castor.view.cli", *args], capture_output=True,
                            text=True, timeout=60)
    return result.returncode, result.stdout, result.stderr

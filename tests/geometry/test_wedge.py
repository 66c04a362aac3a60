"""The wedge ``!we`` (LANGUAGE.md §4.1): half the unit cube below x + z = 1,
in every output a primitive has."""

from __future__ import annotations

import numpy as np
import pytest

from castor.settings import View
from tests.support.checks import check_closed, check_convex_planar
from tests.support.cli import frames_of, run
from tests.support.drawings import Drawn, draw_svg
from tests.support.pictures import camera_of, covered, draw

WEDGE = "> !we(0.8, 0.4, 0.2);\n"


def test_the_wedge_is_half_the_unit_cube_in_five_faces():
    frame, = frames_of(WEDGE)
    check_closed(frame)
    check_convex_planar(frame)
    assert frame.volume() == pytest.approx(0.5, abs=1e-12)
    assert np.array_equal(frame.box(), [[0, 0, 0], [1, 1, 1]])
    assert len(frame.polygons) == 5
    assert sorted(len(p.points) for p in frame.polygons) == [3, 3, 4, 4, 4]
    assert frame.paths() == {"!we"} and frame.colours() == {(0.8, 0.4, 0.2)}
    # the slope: sqrt(2) by 1, facing (1, 0, 1)
    assert frame.area() == pytest.approx(1 + 1 + 0.5 + 0.5 + 2 ** 0.5)


def test_the_wedge_placed_and_cut():
    frame, = frames_of("> $D(@h(2, 3, 4) !we(1, 1, 1), @t(0, 0, 2) @h(1, 3, 2) !cu(1, 1, 1));\n")
    check_closed(frame)
    # the part under z = 2 of the ramp 2 wide and 4 high: 2 by 3 by 4 / 2 less the top 1 x 3 x 2 / 2
    assert frame.volume() == pytest.approx(12 - 3, abs=1e-9)


def test_the_wedge_has_no_arguments_after_its_colour():
    status, out, err = run("--no-cpp", stdin="> !we(1, 0, 0, 2);\n")
    assert status == 1
    assert "'!we' takes 3 arguments (R, G, B), but 4 were given" in err


def test_the_wedge_seen_from_the_front_is_its_triangle():
    image = draw(WEDGE, view=View("front", 0, 0))
    cover = covered(image)
    camera = camera_of(WEDGE, view=View("front", 0, 0))
    (x0, y0), (x1, y1) = camera.project(np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 1.0]]))[0]
    # a quarter and three quarters of the way across, near the foot and near the top
    for fx, fz, inside in ((0.25, 0.25, True), (0.75, 0.75, False), (0.2, 0.7, True),
                           (0.7, 0.2, True), (0.9, 0.6, False)):
        px = int(round(x0 + fx * (x1 - x0)))
        py = int(round(y0 + fz * (y1 - y0)))
        assert cover[py, px] == inside, (fx, fz)
    # about half the square the box projects to
    square = abs((x1 - x0) * (y1 - y0))
    assert cover.sum() == pytest.approx(square / 2, rel=0.1)


def test_the_wedge_in_a_front_elevation_is_a_triangle(tmp_path):
    svg = draw_svg(tmp_path, "rampe = " + WEDGE[2:].replace(";", ";\n> rampe;"), "--view", "front")
    drawn = Drawn(svg, 100)
    assert drawn.covered("rampe", (0, 0), (1, 0)) == pytest.approx(1)
    assert drawn.covered("rampe", (0, 0), (0, 1)) == pytest.approx(1)
    assert drawn.covered("rampe", (1, 0), (0, 1)) == pytest.approx(2 ** 0.5)
    assert drawn.covered("rampe", (0, 1), (1, 1)) == 0


def test_the_wedge_in_the_live_preview(tmp_path, monkeypatch):
    from castor.serve.evaluation import Watched
    from castor.settings import Source
    from castor.serve.server import PreviewServer
    from tests.support.serve import get, triangles, volume, wait_for

    monkeypatch.chdir(tmp_path)
    (tmp_path / "scene.cas").write_text("rampe = @h(2, 1, 1) !we(0.8, 0.4, 0.2);\n> rampe;\n")
    server = PreviewServer(Watched(Source(("scene.cas",))), "127.0.0.1", 0).start()
    try:
        port = server.httpd.server_address[1]
        wait_for(lambda: get(port, "/scene.json")[2].get("evaluated"))
        _, _, scene = get(port, "/scene.json")
        [frame] = scene["frames"]
        assert frame["origins"] == [{"path": "(rampe)!we", "colour": [0.8, 0.4, 0.2],
                                     "source": "scene.cas:1:21: !we", "element": "rampe",
                                     "class": None}]
        assert frame["box"] == [[0, 0, 0], [2, 1, 1]]
        assert frame["triangles"] == 8
        _, _, data = get(port, frame["url"])
        assert volume(triangles(data, 8)) == pytest.approx(1.0)
    finally:
        server.close()

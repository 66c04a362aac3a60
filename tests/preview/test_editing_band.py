"""The rubber band of editing on screen (CLI.md, "Editing on screen"), in
Debian's chromium: once a gesture's first point is taken, a line runs from it
to the snapped point under the pointer, with the running length (Place: the
box's outline and its sides, then its height); it follows the view when the
view turns, and goes when the gesture ends."""

from __future__ import annotations

import re

import numpy as np
import pytest

from castor.serve.evaluation import Watched
from castor.serve.server import PreviewServer
from castor.settings import Source
from tests.support.browser import HEIGHT, WIDTH, picture
from tests.support.preview_page import browser, skip_without_chromium  # noqa: F401

skip_without_chromium()

SCENE = "bloc = @h(2, 2, 1) !cu(0.7, 0.7, 0.7);\n> bloc;\n"
GREEN = (10, 125, 44)  # the band's colour


@pytest.fixture
def page(browser, tmp_path, monkeypatch):  # noqa: F811
    monkeypatch.chdir(tmp_path)
    (tmp_path / "scene.cas").write_text(SCENE)
    server = PreviewServer(Watched(Source(("scene.cas",))), "127.0.0.1", 0).start()
    opened = browser.new_page(viewport={"width": WIDTH, "height": HEIGHT})
    problems = []
    opened.on("pageerror", lambda error: problems.append(str(error)))
    opened.goto(server.url)
    opened.wait_for_selector("body[data-version]", timeout=15000)
    opened.wait_for_selector("body[data-editing=ready]", timeout=15000)
    opened.get_by_role("button", name="top").click()  # a plan: x right, y up
    yield opened
    opened.close()
    server.close()
    assert problems == []


def at(page, point) -> tuple[float, float]:
    """Where a scene point is on the canvas (its own pixels)."""
    return tuple(page.evaluate("(p) => window.castorViewer.project(p)", point))


def point_to(page, point) -> None:
    x, y = at(page, point)
    box = page.locator("#view").bounding_box()
    page.mouse.move(box["x"] + x, box["y"] + y)


def click(page, point) -> None:
    point_to(page, point)
    page.mouse.down()
    page.mouse.up()


def segments(page) -> list[tuple[float, ...]]:
    d = page.get_attribute("#edit-band path", "d") or ""
    return [tuple(map(float, m)) for m in
            re.findall(r"M(-?[\d.]+) (-?[\d.]+)L(-?[\d.]+) (-?[\d.]+)", d)]


def band(page, text: str) -> None:
    page.wait_for_function("(t) => document.body.dataset.band === t", arg=text, timeout=15000)


def test_measure_draws_a_line_from_the_first_point_to_the_pointer(page):
    page.get_by_role("button", name="Measure").click()
    assert segments(page) == []
    click(page, [2, 2, 1])  # the block's corner
    page.wait_for_selector("body[data-points='1']")
    point_to(page, [2, 0, 1])  # the other corner of that side
    band(page, "2 m")
    assert page.inner_text("#edit-length") == "2 m"
    [(x0, y0, x1, y1)] = segments(page)
    for (x, y), (u, v) in (((x0, y0), at(page, [2, 2, 1])), ((x1, y1), at(page, [2, 0, 1]))):
        assert abs(x - u) < 1 and abs(y - v) < 1  # from snapped point to snapped point
    # the line is drawn: its middle, outside the block, is the band's green
    middle = picture(page, "band")[int((y0 + y1) / 2) - 2:int((y0 + y1) / 2) + 3,
                                   int(x0) + 1:int(x0) + 4]
    assert np.any(np.all(np.abs(middle - GREEN) < 40, axis=-1))
    # the view zoomed: the band is drawn again where the points are now
    box = page.locator("#view").bounding_box()
    page.mouse.move(box["x"] + 40, box["y"] + 40)
    page.mouse.wheel(0, 300)
    page.wait_for_function("(x) => { const p = window.castorViewer.project([2, 2, 1]);"
                           " return Math.abs(p[0] - x) > 5; }", arg=x0, timeout=15000)
    page.wait_for_function("([u, v]) => { const d = document.querySelector('#edit-band path')"
                           ".getAttribute('d'); const m = /^M([-\\d.]+) ([-\\d.]+)/.exec(d);"
                           " return m && Math.abs(m[1] - u) < 1 && Math.abs(m[2] - v) < 1; }",
                           arg=list(at(page, [2, 2, 1])), timeout=15000)
    click(page, [2, 0, 1])  # the second point: the gesture ends, so does the band
    page.wait_for_selector("body[data-measured^='distance']")
    page.wait_for_function("() => document.body.dataset.band === undefined", timeout=15000)
    assert segments(page) == [] and not page.is_visible("#edit-length")


def test_place_draws_the_box_outline_and_its_height(page):
    page.get_by_role("button", name="Place").click()
    click(page, [2.5, 0, 0])
    page.wait_for_selector("body[data-points='1']")
    point_to(page, [3, 0.5, 0])
    band(page, "0.5 × 0.5 m")
    corners = [at(page, p) for p in ([2.5, 0, 0], [3, 0, 0], [3, 0.5, 0], [2.5, 0.5, 0])]
    drawn = segments(page)
    assert len(drawn) == 4
    for (x0, y0, x1, y1), start, end in zip(drawn, corners, corners[1:] + corners[:1]):
        assert abs(x0 - start[0]) < 1 and abs(y0 - start[1]) < 1
        assert abs(x1 - end[0]) < 1 and abs(y1 - end[1]) < 1
    click(page, [3, 0.5, 0])
    page.wait_for_selector("body[data-points='2']")
    page.get_by_role("button", name="front").click()  # z up the screen: a height is seen
    x, y = at(page, [3, 0.5, 1.2])
    box = page.locator("#view").bounding_box()
    page.mouse.move(box["x"] + x, box["y"] + y)
    band(page, "0.5 × 0.5 × 1.2 m")
    assert len(segments(page)) == 12  # the box's twelve edges
    page.keyboard.press("Escape")
    page.wait_for_function("() => document.body.dataset.band === undefined", timeout=15000)

"""castor --serve in a real browser: Debian's chromium, driven by playwright,
drawing with software WebGL (SwiftShader). The page draws the house, a save
changes the picture without reloading the page or moving the camera, an error
is listed beside the last good picture, and pointing at a blue reveal names
the primitive it comes from."""

from __future__ import annotations

import os
import shutil

import numpy as np
import pytest

from castor.serve.evaluation import Watched
from castor.settings import Source
from castor.serve.server import PreviewServer
from tests.support.preview_page import browser, house, page, skip_without_chromium  # noqa: F401
from tests.support.browser import (CHROMIUM, FLAGS, GREEN, HEIGHT, REVEAL, ROOF, WIDTH, drawn,
                                   inside_reveal, near, next_version, outline, painted, picture)

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

playwright = skip_without_chromium()


def save(path, old: str, new: str) -> None:
    text = path.read_text()
    assert old in text
    before = os.stat(path).st_mtime_ns
    path.write_text(text.replace(old, new))
    if os.stat(path).st_mtime_ns == before:
        os.utime(path, ns=(before + 1_000_000, before + 1_000_000))


def test_the_page_draws_the_house(page):
    image = picture(page, "house")
    share = drawn(image).mean()
    assert 0.15 < share < 0.9  # the house fills the view without overflowing it
    assert near(image, ROOF).sum() > 5000  # the roof's tiles
    assert near(image, REVEAL).sum() > 300  # the reveals of the openings
    assert page.inner_text("#status").startswith("1 frame · ")
    assert page.is_hidden("#diagnostics")


def test_a_save_changes_the_picture_without_a_reload(page, house):
    path, _ = house
    page.evaluate("window.notReloaded = true")
    # turn the camera, so that a camera set back to its first place would show
    page.mouse.move(450, 400)
    page.mouse.down()
    page.mouse.move(520, 380, steps=5)
    page.mouse.up()
    painted(page)
    before = picture(page, "turned")
    version = page.evaluate("document.body.dataset.version")
    save(path, "#define TUILE    0.70, 0.28, 0.18", "#define TUILE    0.15, 0.65, 0.25")
    next_version(page, version)
    painted(page)
    after = picture(page, "green-roof")
    assert page.evaluate("window.notReloaded") is True
    assert near(before, ROOF).sum() > 5000 and near(after, ROOF).sum() < 50
    assert near(after, GREEN).sum() > 5000 and near(before, GREEN).sum() < 50
    # the same camera: the same outline, only colours changed
    assert (outline(before) != outline(after)).mean() < 0.002


def test_an_error_is_listed_beside_the_last_good_picture(page, house):
    path, _ = house
    good = picture(page, "before-error")
    version = page.evaluate("document.body.dataset.version")
    save(path, "maison = $U(", "maison = $U(((")
    next_version(page, version)
    shown = picture(page, "error")
    listed = page.inner_text("#diagnostics-list")
    assert listed.startswith("house.cas:")
    assert ": error: " in listed.splitlines()[0]
    assert page.inner_text("#status") == "the scene has errors: showing the last good frames"
    # the list of errors covers the bottom of the view
    assert (outline(good, 200) != outline(shown, 200)).mean() < 0.002


def test_pointing_at_a_blue_reveal_names_its_primitive(page):
    page.mouse.move(*inside_reveal(picture(page, "point")))
    page.wait_for_selector("#pointed:not([hidden])", timeout=5000)
    picture(page, "pointed")
    path = page.inner_text("#pointed-path")
    assert path.startswith("(maison)") and path.endswith("!cu")
    assert page.inner_text("#pointed-colour") == "0.25 0.45 0.85"
    with open(os.path.join(ROOT, "examples", "house.cas")) as f:
        lines = f.read().splitlines()
    written = 1 + next(i for i, line in enumerate(lines) if line.startswith("> maison"))
    assert page.inner_text("#pointed-where") == f"frame 1 · house.cas:{written}"


def test_a_face_turned_to_the_viewer_shows_its_own_colour(page):
    page.click("#view-front")
    painted(page)
    image = picture(page, "front")
    render = np.round(np.array([0.93, 0.90, 0.82]) * 255)  # ENDUIT, the walls' colour
    full = np.all(np.abs(image - render) <= 2, axis=2)
    assert full.sum() > 20000  # the south wall, at full strength
    page.click("#view-perspective")
    painted(page)
    turned = picture(page, "perspective")
    walls = np.all(np.abs(turned / turned.max(axis=2, keepdims=True).clip(1)
                          - render / render.max()) < 0.03, axis=2) & (turned.max(axis=2) > 60)
    assert walls.sum() > 20000  # turned away, the walls are darker but of the same hue
    assert np.all(np.abs(turned - render) <= 2, axis=2).sum() < 0.01 * walls.sum()


def test_the_section_plane_shows_a_plan(page):
    page.click("#view-top")
    painted(page)
    roof = picture(page, "top")
    page.fill("#section", "250")
    page.dispatch_event("#section", "input")
    painted(page)
    plan = picture(page, "plan")
    label = page.inner_text("#section-label")
    assert label.startswith("z = ") and 1.3 < float(label[4:]) < 1.5
    assert near(roof, ROOF).mean() > 0.1 and near(plan, ROOF).sum() == 0
    assert near(plan, REVEAL).sum() > 200  # the sills of the windows, seen from above

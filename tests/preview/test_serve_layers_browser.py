"""castor --serve in a real browser (fixtures from tests.support.preview_page): the classes of
the annotated house as layers to hide and show, and pointing at a wall names
its element and class. Every wait is for a state of the page, never a time."""

from __future__ import annotations

import re

import numpy as np
from tests.support.browser import BAR, REVEAL, ROOF, near, picture, well_inside
from tests.support.preview_page import browser, house, page, skip_without_chromium  # noqa: F401

skip_without_chromium()

WALLS = (0.93, 0.90, 0.82)  # ENDUIT, the walls' render


def _shown(page, hidden: str) -> None:
    """Wait until the page has drawn with exactly these layers hidden."""
    page.wait_for_function("(wanted) => document.body.dataset.hidden === wanted", arg=hidden,
                           timeout=10000)


def _inside(mask: np.ndarray) -> tuple[int, int]:
    """A page point well inside the pixels of ``mask`` (a picture below the bar)."""
    return well_inside(mask, 3, 50)


def _without_panel(page, image: np.ndarray) -> np.ndarray:
    """The picture with the place of the panel of layers painted white."""
    panel = page.locator("#layers").bounding_box()
    top, left = int(panel["y"]) - BAR, int(panel["x"])
    image = image.copy()
    image[max(top, 0):top + int(panel["height"]) + 2, left:left + int(panel["width"]) + 2] = 255
    return image


def _walls(image: np.ndarray) -> np.ndarray:
    return near(image, WALLS, 0.03)


def test_the_layers_hide_and_show_the_walls(page):
    page.wait_for_selector("#layers-toggle:not([hidden])", timeout=10000)
    _shown(page, "")
    before = picture(page, "layers-all")
    page.click("#layers-toggle")
    page.wait_for_selector("#layers:not([hidden])")
    names = page.eval_on_selector_all("#layers-list input",
                                      "boxes => boxes.map(b => b.dataset.layer)")
    # the classes of its faces (its windows and door are holes in the walls)
    assert names == ["chimney", "roof", "slab", "wall", "unclassed"]
    page.uncheck("#layer-wall")
    _shown(page, "wall")
    # the pictures compared without the panel of layers (its ticked boxes are blue)
    after = _without_panel(page, picture(page, "layers-no-walls"))
    before = _without_panel(page, before)
    walls = _walls(before)
    assert walls.sum() > 20000 and _walls(after).sum() < 0.01 * walls.sum()
    # where the walls were, the picture changed; the roof is still drawn
    assert (np.abs(after - before).max(axis=2) > 10)[walls].mean() > 0.9
    assert near(after, ROOF).sum() > 0.9 * near(before, ROOF).sum() > 5000
    # the reveals are faces of the walls: gone with them
    assert near(before, REVEAL).sum() > 300 and near(after, REVEAL).sum() < 30
    page.check("#layer-wall")
    _shown(page, "")
    again = _without_panel(page, picture(page, "layers-again"))
    assert (np.abs(again - before).max(axis=2) > 30).mean() < 0.001


def test_pointing_at_a_wall_names_its_element_and_class(page):
    _shown(page, "")
    spot = _inside(_walls(picture(page, "layers-point")))
    page.mouse.move(*spot)
    page.wait_for_function("document.getElementById('pointed-element').textContent"
                           ".endsWith(' · wall')", timeout=10000)
    assert page.inner_text("#pointed-element") == "murs · wall"
    assert page.inner_text("#pointed-path").startswith("(maison).U1.D1.U1(murs)")
    # with the walls hidden, the same point shows what is behind them, not a wall
    page.click("#layers-toggle")
    page.uncheck("#layer-wall")
    _shown(page, "wall")
    page.mouse.move(spot[0] + 1, spot[1])
    page.wait_for_function("document.getElementById('pointed').hidden || !document"
                           ".getElementById('pointed-element').textContent.endsWith(' · wall')",
                           timeout=10000)


def test_a_scene_without_classes_has_no_layers(page, house):
    path, _ = house
    version = page.evaluate("document.body.dataset.version")
    text = path.read_text()
    path.write_text(re.sub(r"//\s*\[[^\]]*\]", "//", text))
    page.wait_for_function("(seen) => document.body.dataset.version !== seen", arg=version,
                           timeout=15000)
    assert page.is_hidden("#layers-toggle")
    assert page.is_hidden("#layers")


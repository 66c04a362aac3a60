"""Editing on screen in a real browser (CLI.md, "Editing on screen"): Debian's
chromium driven by playwright on castor --serve's page. The toolbar's Place,
Move, Measure and Undo (found by their accessible names) make the edits with
clicks on snapped points, the value box sets a height, the page shows the
line each gesture wrote, Undo gives the file's bytes back, snapping is shown
as the pointer moves, and an edit begun on a text that changed on disk is
refused with nothing lost."""

from __future__ import annotations


import pytest

from castor.serve.evaluation import Watched
from castor.serve.server import PreviewServer
from castor.settings import Source
from tests.support.preview_page import browser, opened_page, skip_without_chromium  # noqa: F401

playwright = skip_without_chromium()

SCENE = "/* a block */\nbloc = @h(2, 2, 1) !cu(0.7, 0.7, 0.7);\n> bloc;\n"


@pytest.fixture
def scene(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    path = tmp_path / "scene.cas"
    path.write_bytes(SCENE.encode())
    server = PreviewServer(Watched(Source(("scene.cas",))), "127.0.0.1", 0).start()
    yield path, server.url
    server.close()


@pytest.fixture
def page(browser, scene):
    with opened_page(browser, scene[1]) as opened:
        opened.wait_for_selector("body[data-editing=ready]", timeout=15000)
        opened.get_by_role("button", name="top").click()  # a plan: x right, y up
        yield opened


def at(page, point) -> tuple[float, float]:
    """Where a scene point is on the page."""
    x, y = page.evaluate("(p) => window.castorViewer.project(p)", point)
    box = page.locator("#view").bounding_box()
    return box["x"] + x, box["y"] + y


def click(page, point, offset=(0, 0)) -> None:
    x, y = at(page, point)
    page.mouse.move(x + offset[0], y + offset[1])
    page.mouse.down()
    page.mouse.up()


def written(page, count: int) -> str:
    page.wait_for_function("(count) => document.body.dataset.written === String(count) || "
                           "document.body.dataset.editError", arg=count, timeout=30000)
    assert page.evaluate("document.body.dataset.editError") is None, \
        page.evaluate("document.body.dataset.editError")
    return page.inner_text("#edit-result")


def shows(page, name: str) -> None:
    """The page shows a frame that has the object ``name``."""
    page.wait_for_function("(name) => { const f = window.castorViewer.frame(); return f && "
                           "f.origins.some((o) => o.path === `(${name})!cu`); }", arg=name,
                           timeout=30000)


def test_place_writes_the_object_and_undo_gives_the_bytes_back(page, scene):
    path, _ = scene
    page.get_by_role("button", name="Place").click()
    assert page.get_by_role("button", name="Place").get_attribute("aria-pressed") == "true"
    page.get_by_label("primitive").select_option("!cu")
    click(page, [2.5, 0, 0])
    click(page, [3, 0.5, 0])
    page.get_by_label("value").fill("2")
    page.get_by_label("value").press("Enter")
    line = "bloc1 = @t(2.5, 0, 0) @h(0.5, 0.5, 2) !cu(0.8, 0.8, 0.8); > bloc, bloc1;"
    assert written(page, 1).endswith(f"scene.cas:3  {line}")  # the line, as it is written
    assert path.read_text() == SCENE.replace("> bloc;", line)
    shows(page, "bloc1")  # the new frame
    page.get_by_role("button", name="Undo").click()
    assert written(page, 2).endswith("scene.cas:3  > bloc;")
    assert path.read_bytes() == SCENE.encode()
    page.wait_for_function("() => !window.castorViewer.frame().origins.some("
                           "(o) => o.path === '(bloc1)!cu')", timeout=30000)


def test_move_takes_a_face_and_puts_it_down(page, scene):
    path, _ = scene
    page.get_by_role("button", name="Move").click()
    click(page, [1, 1, 1])  # the centre of the top face
    click(page, [1.5, 1, 1])
    assert "bloc = @t(0.5, 0, 0) @h(2, 2, 1) !cu(0.7, 0.7, 0.7);" in written(page, 1)
    assert path.read_text() == SCENE.replace("bloc = @h", "bloc = @t(0.5, 0, 0) @h")


def test_measure_a_face_an_object_and_a_distance(page, scene):
    path, _ = scene
    page.get_by_role("button", name="Measure").click()
    click(page, [1, 1, 1])
    page.wait_for_selector("body[data-measured]")
    text = page.inner_text("#edit-result")
    assert "face 4 m²" in text and "bloc: volume 4 m³, box 0, 0, 0 to 2, 2, 1" in text
    page.evaluate("delete document.body.dataset.measured")
    click(page, [1, 0, 1])
    page.wait_for_selector("body[data-measured]")
    assert page.inner_text("#edit-result") == "distance 1 m · dx 0 · dy -1 · dz 0"
    assert path.read_bytes() == SCENE.encode()  # measuring never edits


def test_snapping_is_shown_as_the_pointer_moves(page):
    page.get_by_role("button", name="Place").click()
    x, y = at(page, [2, 2, 1])
    page.mouse.move(x - 3, y + 2)  # three pixels off the block's corner, on its top
    page.wait_for_selector("body[data-snapped=corner]", timeout=15000)
    assert page.inner_text("#edit-feature").startswith("corner · ")
    assert "scene.cas:2:" in page.inner_text("#edit-feature")
    assert page.is_visible("#edit-marker")
    marker = page.locator("#edit-marker").bounding_box()
    assert abs(marker["x"] + marker["width"] / 2 - x) < 2  # on the corner, not the pointer
    assert abs(marker["y"] + marker["height"] / 2 - y) < 2


def test_an_edit_begun_on_an_older_text_is_refused(page, scene):
    path, _ = scene
    page.get_by_role("button", name="Place").click()
    click(page, [2.5, 0, 0])
    page.wait_for_selector("body[data-points='1']")  # the first corner taken, on this text
    changed = SCENE.replace("/* a block */", "/* a block, changed in the editor */")
    path.write_text(changed)
    click(page, [3, 0.5, 0])
    page.get_by_label("value").press("Enter")
    page.wait_for_selector("body[data-edit-error]", timeout=30000)
    assert "the text changed since this gesture began" in page.inner_text("#edit-error")
    assert path.read_text() == changed  # nothing lost


def test_place_into_an_object_with_a_chosen_name(page, scene):
    path, _ = scene
    path.write_text(SCENE.replace("bloc = @h(2, 2, 1) !cu(0.7, 0.7, 0.7);",
                                  "bloc = $U(@h(2, 2, 1) !cu(0.7, 0.7, 0.7));"))
    page.wait_for_function("() => window.castorViewer.frame().origins[0].path === '(bloc).U1!cu'",
                           timeout=30000)
    page.get_by_role("button", name="Place").click()
    page.get_by_label("name").fill("borne")
    page.get_by_label("into").fill("bloc")
    click(page, [2.5, 0, 0])
    click(page, [3, 0.5, 0])
    page.get_by_label("value").press("Enter")
    assert "borne = @t(2.5, 0, 0) @h(0.5, 0.5, 1) !cu(0.8, 0.8, 0.8); bloc = $U(" \
        in written(page, 1)
    assert "!cu(0.7, 0.7, 0.7), borne);" in path.read_text()
    page.get_by_label("name").fill("")
    page.get_by_label("into").fill("borne")  # not a $U: refused with the reason
    click(page, [2.5, 1, 0])
    click(page, [3, 1.5, 0])
    page.get_by_label("value").press("Enter")
    page.wait_for_selector("body[data-edit-error]", timeout=30000)
    assert "not a $U" in page.inner_text("#edit-error")


def test_a_typed_distance_moves_exactly(page, scene):
    path, _ = scene
    page.get_by_role("button", name="Move").click()
    click(page, [1, 1, 1])
    x, y = at(page, [1.63, 1, 1])  # towards +x, along the x axis from the first point
    page.mouse.move(x, y)
    page.wait_for_selector("body[data-snapped='axis x']", timeout=15000)
    page.get_by_label("value").fill("0.25")
    page.get_by_label("value").press("Enter")
    assert "bloc = @t(0.25, 0, 0) @h(2, 2, 1)" in written(page, 1)
    assert path.read_text() == SCENE.replace("bloc = @h", "bloc = @t(0.25, 0, 0) @h")


def test_place_with_sides_and_height_typed(page, scene):
    path, _ = scene
    page.get_by_role("button", name="Place").click()
    click(page, [2.5, 0, 0])
    page.get_by_label("value").fill("0.5, 0.25")
    page.get_by_label("value").press("Enter")
    page.get_by_label("value").fill("2.8")
    page.get_by_label("value").press("Enter")
    line = "bloc1 = @t(2.5, 0, 0) @h(0.5, 0.25, 2.8) !cu(0.8, 0.8, 0.8); > bloc, bloc1;"
    assert written(page, 1).endswith(line)
    assert path.read_text() == SCENE.replace("> bloc;", line)


def test_place_with_its_height_dragged(page, scene):
    path, _ = scene
    page.get_by_role("button", name="Place").click()
    click(page, [2.5, 0, 0])
    click(page, [3, 0.5, 0])
    page.get_by_role("button", name="front").click()  # z rises on the screen
    x, y = at(page, [3, 0.5, 1.5])
    page.mouse.move(x, y + 1)
    page.wait_for_selector("body[data-height='1.5']", timeout=15000)
    assert page.inner_text("#edit-feature") == "height 1.5"
    page.mouse.down()
    page.mouse.up()
    line = "bloc1 = @t(2.5, 0, 0) @h(0.5, 0.5, 1.5) !cu(0.8, 0.8, 0.8); > bloc, bloc1;"
    assert written(page, 1).endswith(line)
    assert path.read_text() == SCENE.replace("> bloc;", line)

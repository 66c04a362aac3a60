"""The live preview's facets follow the camera, in a real browser (Debian's
chromium driven by playwright; CLI.md "Live preview", issue 34 item 3): the
page sends its camera once it stops, the server facets the curved surfaces
again for it, and the page shows the new frames without moving its camera;
zoomed towards a ball the page draws more triangles, zoomed out fewer."""

from __future__ import annotations

import time

import pytest

from castor.serve.evaluation import Watched, evaluate
from castor.serve.server import PreviewServer
from castor.settings import Source
from tests.support.browser import HEIGHT, WIDTH, drawn, next_version, painted, picture
from tests.support.preview_page import browser, opened_page, skip_without_chromium  # noqa: F401

playwright = skip_without_chromium()

# a wide flat ground and, at its middle, a ball and a column: seen whole, both
# are small on the screen, and their facets coarse
SCENE = ("ground = @t(-30, -30, -1) @h(60, 60, 1) !cu(0.6, 0.6, 0.6);\n"
         "ball = @t(0, 0, 1) !sp(0.2, 0.4, 0.8);\n"
         "column = @t(3, 0, 0) @h(0.5, 0.5, 3) !cy(0.8, 0.3, 0.2);\n"
         "> ground, ball, column;\n")


@pytest.fixture
def served(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "balls.cas").write_text(SCENE)
    server = PreviewServer(Watched(Source(("balls.cas",))), "127.0.0.1", 0).start()
    yield server
    server.close()


@pytest.fixture
def page(browser, served):
    with opened_page(browser, served.url) as opened:
        yield opened


def _shown(page) -> tuple[str, int]:
    return page.evaluate("[document.body.dataset.version, Number(document.body.dataset.triangles)]")


def _zoom(page, notches: int) -> None:
    """Turn the wheel over the middle of the view (towards the target: the ball)."""
    page.mouse.move(WIDTH / 2, HEIGHT / 2)
    for _ in range(abs(notches)):
        page.mouse.wheel(0, -300 if notches > 0 else 300)


def _settled(page, served, quiet: float = 1.0, seconds: float = 30.0) -> tuple[str, int]:
    """What the page shows once its camera has stopped: every camera it sent
    answered, none for ``quiet`` seconds (a loaded machine spaces the wheel's
    notches past the page's pause, and the page sends a camera midway), and the
    page showing the server's latest version."""
    deadline = time.monotonic() + seconds
    last, since = None, time.monotonic()
    while time.monotonic() < deadline:
        preview = served.preview
        with preview.state:
            now = (preview._looked, preview._looked_done, preview.snapshot.version)
        if now != last:
            last, since = now, time.monotonic()
        elif now[0] == now[1] and time.monotonic() - since >= quiet \
                and _shown(page)[0] == str(now[2]):
            return _shown(page)
        time.sleep(0.05)
    raise AssertionError(f"the page's camera never settled: {last}, page at {_shown(page)}")


def test_the_page_is_shown_with_the_facets_of_its_view(page):
    # the first frames (the scene's tolerance everywhere) were faceted again for
    # the fitted view before the page said it was shown: far fewer triangles
    uniform = evaluate(Watched(Source(text=SCENE, name="balls.cas"), quiet=True))
    _, triangles = _shown(page)
    assert 0 < triangles * 3 < uniform.frames[0].triangles
    assert "faceted for this view" in page.inner_text("#status")


def test_zooming_in_shows_more_triangles_and_out_fewer(page, served):
    version, seen_whole = _shown(page)
    painted(page)
    whole = drawn(picture(page, "refacet-whole")).sum()
    _zoom(page, 6)  # the ball fills much of the view
    next_version(page, version)
    version, close = _settled(page, served)
    assert close > 2 * seen_whole
    painted(page)
    # the camera stayed where the wheel put it: the ball fills the view
    assert drawn(picture(page, "refacet-close")).sum() > whole
    _zoom(page, -9)  # farther than at first
    next_version(page, version)
    _, far = _settled(page, served)
    assert far < close
    assert far <= seen_whole


def test_an_orbit_then_a_zoom_keeps_the_camera_where_it_was_turned(page):
    version = _shown(page)[0]
    page.mouse.move(450, 400)
    page.mouse.down()
    page.mouse.move(560, 330, steps=6)
    page.mouse.up()
    turned = page.evaluate("window.castorViewer.camera()")
    assert turned["azimuth"] != -60
    _zoom(page, 6)
    next_version(page, version)
    shown = page.evaluate("window.castorViewer.camera()")
    assert (shown["azimuth"], shown["elevation"]) == (turned["azimuth"], turned["elevation"])
    assert shown["distance"] < turned["distance"] / 5


def test_while_faceting_for_the_view_the_status_says_so(page, monkeypatch):
    # a refacet evaluates nothing: the status line says "faceting for this
    # view…", never "evaluating…" (the refacet is slowed so that the page sees it)
    from castor.serve import server as served_module

    slow = served_module.refaceted

    def slowed(*args, **kwargs):
        time.sleep(1.0)
        return slow(*args, **kwargs)

    monkeypatch.setattr(served_module, "refaceted", slowed)
    page.evaluate("""() => { window.statuses = [];
        new MutationObserver(() => window.statuses.push(document.getElementById('status').textContent))
          .observe(document.getElementById('status'), {childList: true, characterData: true, subtree: true}); }""")
    version = _shown(page)[0]
    _zoom(page, 6)
    next_version(page, version)
    statuses = page.evaluate("window.statuses")
    assert any(text.endswith(" · faceting for this view…") for text in statuses), statuses
    assert not any("evaluating" in text for text in statuses), statuses
    assert "faceting for this view…" not in page.inner_text("#status")

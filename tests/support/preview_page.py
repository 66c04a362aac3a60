"""Fixtures for the live preview in Debian's chromium: the browser (one per
module), the example house served by castor --serve from a folder of its own,
and the page opened on it, drawn once. A test module imports them by name
(``from tests.support.preview_page import browser, house, page``) after
``skip_without_chromium()``."""

from __future__ import annotations

import os
import shutil
from contextlib import contextmanager

import pytest

from tests.support.browser import CHROMIUM, FLAGS, HEIGHT, WIDTH

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def skip_without_chromium():
    """Skip the calling module where the browser or its driver is missing."""
    if not os.path.exists(CHROMIUM):
        pytest.skip(f"Debian's chromium is not installed ({CHROMIUM} is absent; "
                    "apt-get install chromium): the live preview is not tried in a browser",
                    allow_module_level=True)
    return pytest.importorskip("playwright.sync_api",
                               reason="the playwright package is not installed")


@pytest.fixture(scope="module")
def browser():
    from playwright.sync_api import sync_playwright

    with sync_playwright() as driver:
        launched = driver.chromium.launch(executable_path=CHROMIUM, args=FLAGS)
        yield launched
        launched.close()


@pytest.fixture
def house(tmp_path, monkeypatch):
    from castor.serve.evaluation import Watched
    from castor.serve.server import PreviewServer
    from castor.settings import Source

    monkeypatch.chdir(tmp_path)
    shutil.copy(os.path.join(ROOT, "examples", "house.cas"), tmp_path / "house.cas")
    server = PreviewServer(Watched(Source(("house.cas",))), "127.0.0.1", 0).start()
    yield tmp_path / "house.cas", server.url
    server.close()


@contextmanager
def opened_page(browser, url: str):
    """A page of the browser on ``url``, drawn once (its ``data-version`` set);
    closed after, with no error raised in it."""
    opened = browser.new_page(viewport={"width": WIDTH, "height": HEIGHT})
    problems = []
    opened.on("pageerror", lambda error: problems.append(str(error)))
    opened.goto(url)
    opened.wait_for_selector("body[data-version]", timeout=15000)
    yield opened
    opened.close()
    assert problems == []


@pytest.fixture
def page(browser, house):
    with opened_page(browser, house[1]) as opened:
        yield opened

"""The parameters panel can be trusted (issue 29, item 12): "save" writes what
the panel offers and the user changed, never the values worked out from them
(so a saved set follows H as --set does); an emptied number box, or 1e999
which the browser empties, sends nothing until it holds a number."""

from __future__ import annotations

import http.client
import json
import os
import subprocess
import sys

import pytest

from castor.serve.evaluation import Watched
from castor.serve.server import PreviewServer
from castor.settings import Source

from tests.support.browser import CHROMIUM, FLAGS, HEIGHT, WIDTH

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


@pytest.fixture
def house(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "house.cas").write_text(open(os.path.join(ROOT, "examples", "house.cas")).read())
    server = PreviewServer(Watched(Source(("house.cas",))), "127.0.0.1", 0).start()
    yield tmp_path / "house.cas", server
    server.close()


def _post(server, body: dict):
    host, port = server.httpd.server_address[:2]
    connection = http.client.HTTPConnection(host, port, timeout=30)
    connection.request("POST", "/parameters", body=json.dumps(body),
                       headers={"Content-Type": "application/json"})
    answer = connection.getresponse()
    return answer.status, json.loads(answer.read())


def _frames(folder, *args) -> bytes:
    run = subprocess.run([sys.executable, "-m", "castor", *args, "-f", "off", "house.cas"],
                         cwd=folder, env=dict(os.environ, PYTHONPATH=ROOT), capture_output=True,
                         timeout=120)
    assert run.returncode == 0, run.stderr
    return run.stdout


def test_a_saved_set_holds_what_was_changed_and_follows_the_others(house):
    path, server = house
    offered = {p["name"] for p in _post(server, {"reset": True})[1]["parameters"]}
    assert "PENTE" in offered and "HT" not in offered and "T" not in offered  # worked out
    assert _post(server, {"values": {"PENTE": 45}})[0] == 200
    assert _post(server, {"save": "haute"})[0] == 200
    saved = json.loads((path.parent / "house.json").read_text())["parameterSets"]["haute"]
    assert saved == {"PENTE": "45"}  # not HT, T (the ridge at 35 degrees) nor the others
    # used with another value, the saved set gives what --set gives
    assert _frames(path.parent, "-p", "house.json", "-P", "haute", "--set", "H=3.5") == \
        _frames(path.parent, "--set", "PENTE=45", "--set", "H=3.5")


playwright = pytest.importorskip("playwright.sync_api",
                                 reason="the playwright package is not installed")


@pytest.mark.skipif(not os.path.exists(CHROMIUM), reason=f"{CHROMIUM} is absent")
def test_an_emptied_number_box_sends_nothing(house):
    path, server = house
    with playwright.sync_playwright() as driver:
        browser = driver.chromium.launch(executable_path=CHROMIUM, args=FLAGS)
        page = browser.new_page(viewport={"width": WIDTH, "height": HEIGHT})
        sent = []
        page.on("request", lambda r: sent.append(json.loads(r.post_data))
                if r.method == "POST" and r.url.endswith("/parameters") else None)
        page.goto(server.url)
        page.wait_for_selector("body[data-version]", timeout=15000)
        page.click("#parameters-toggle")
        box = page.wait_for_selector("#parameter-L")
        assert box.get_attribute("type") == "number"
        for text in ("", "1e999"):
            box.fill(text)
            box.dispatch_event("change")
            page.wait_for_function("() => document.getElementById('parameter-L')"
                                   ".closest('.parameter').classList.contains('invalid')")
        box.fill("10")
        box.dispatch_event("change")
        page.wait_for_function(
            "() => document.getElementById('parameters-command').textContent.includes('L=10')")
        browser.close()
    assert [body.get("values") for body in sent] == [{"L": 10}]

"""Gestures on the frame as it is shown (CLI.md, "Editing on screen"): when the
preview's panel (or ``--set``) changes a parameter, snaps, measures and moves
are made on the frames with that value, not on the scene's own."""

from __future__ import annotations

import http.client
import json
import math

import numpy as np
import pytest

from castor.editing.commands import Cache, measure, snap
from castor.editing.document import path_to_uri
from castor.serve.evaluation import Watched
from castor.serve.server import PreviewServer
from castor.settings import EvaluationSettings, Source

from tests.support.serve import wait_for

# a wall L long (x), 0.2 thick (y), 2.5 high; its far top corner is (L, 0, 2.5)
SCENE = "L = 4; // [2:0.5:8]\nmur = @h(L, 0.2, 2.5) !cu(0.9, 0.9, 0.9);\n> mur;\n"
EYE = np.array([9.0, -8.0, 6.0])
PIXEL = 0.001


def towards(corner, pixels: float = 3.0) -> dict:
    """castor.snap's arguments: a ray ``pixels`` pixels inside the top corner
    ``corner`` (towards the wall's middle, so it meets the wall)."""
    corner = np.asarray(corner, float)
    d = corner - EYE
    d /= np.linalg.norm(d)
    side = np.array([corner[0] / 2, 0.1, 1.25]) - corner
    side -= (side @ d) * d
    side /= np.linalg.norm(side)
    direction = d + math.tan(pixels * PIXEL) * side
    return {"frame": 1, "origin": EYE.tolist(), "direction": direction.tolist(), "pixel": PIXEL}


@pytest.fixture
def scene(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    path = tmp_path / "mur.cas"
    path.write_text(SCENE)
    return path


def test_the_cache_evaluates_with_the_values_given(scene):
    uri = path_to_uri(str(scene))
    plain = Cache()
    assert snap(dict(towards((4, 0, 2.5)), uri=uri), plain)["point"] == [4.0, 0.0, 2.5]
    longer = plain.using(EvaluationSettings({"L": 6.0}))
    found = snap(dict(towards((6, 0, 2.5)), uri=uri), longer)
    assert (found["feature"], found["point"]) == ("corner", [6.0, 0.0, 2.5])
    assert measure({"uri": uri, "frame": 1, "object": "mur"}, longer)["volume"] == \
        pytest.approx(6 * 0.2 * 2.5)
    # the scene's own values are still there, evaluated apart
    assert measure({"uri": uri, "frame": 1, "object": "mur"}, plain)["volume"] == \
        pytest.approx(4 * 0.2 * 2.5)


def _post(server, target: str, body: dict) -> tuple[int, dict]:
    host, port = server.httpd.server_address[:2]
    connection = http.client.HTTPConnection(host, port, timeout=60)
    connection.request("POST", target, body=json.dumps(body),
                       headers={"Content-Type": "application/json"})
    answer = connection.getresponse()
    data = json.loads(answer.read())
    connection.close()
    return answer.status, data


def _snapped(server, corner) -> dict:
    status, answer = _post(server, "/gesture", {"command": "castor.snap",
                                                "arguments": towards(corner)})
    assert status == 200, answer
    return answer["result"]


def test_a_snap_after_the_panel_changed_the_length_finds_the_new_corner(scene):
    server = PreviewServer(Watched(Source(("mur.cas",))), "127.0.0.1", 0).start()
    try:
        assert _snapped(server, (4, 0, 2.5))["point"] == [4.0, 0.0, 2.5]
        status, answer = _post(server, "/parameters", {"values": {"L": 6}})
        assert status == 200, answer
        found = _snapped(server, (6, 0, 2.5))
        assert (found["feature"], found["point"]) == ("corner", [6.0, 0.0, 2.5])
        # the old corner is now inside the wall's top face
        assert _snapped(server, (4, 0, 2.5))["feature"] != "corner"
        # back to the scene's own values
        assert _post(server, "/parameters", {"reset": True})[0] == 200
        wait_for(lambda: _snapped(server, (4, 0, 2.5))["point"] == [4.0, 0.0, 2.5])
    finally:
        server.close()


def test_a_set_given_on_the_command_line_is_the_frame_edited(scene):
    job = Watched(Source(("mur.cas",)), evaluation=EvaluationSettings({"L": 7.0}))
    server = PreviewServer(job, "127.0.0.1", 0).start()
    try:
        found = _snapped(server, (7, 0, 2.5))
        assert (found["feature"], found["point"]) == ("corner", [7.0, 0.0, 2.5])
        status, answer = _post(server, "/gesture", {"command": "castor.move", "arguments": {
            "frame": 1, "source": found["source"], "path": found["path"], "by": [0.5, 0, 0],
            "version": _post(server, "/gesture", {"command": "castor.snap",
                                                  "arguments": towards((7, 0, 2.5))})[1]
            ["version"]}})
        assert status == 200, answer
        assert scene.read_text() == SCENE.replace("mur = @h", "mur = @t(0.5, 0, 0) @h")
    finally:
        server.close()


def test_the_gestures_follow_the_settings_as_they_change(scene):
    """castor --lsp --serve hands Gestures the preview's settings the same way."""
    from castor.serve.gestures import Gestures

    shown = {"settings": EvaluationSettings()}
    gestures = Gestures(path_to_uri(str(scene)), Cache(), settings=lambda: shown["settings"])
    request = {"command": "castor.snap", "arguments": towards((6, 0, 2.5))}
    assert gestures.answer(request)["result"]["feature"] != "corner"  # L = 4: nothing there
    shown["settings"] = EvaluationSettings({"L": 6.0})
    found = gestures.answer(request)["result"]
    assert (found["feature"], found["point"]) == ("corner", [6.0, 0.0, 2.5])

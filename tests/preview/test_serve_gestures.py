"""castor --serve's gestures at the HTTP level (CLI.md, "Editing on screen"):
``POST /gesture`` writes the scene file atomically and Undo gives its bytes
back; the preview's rules hold for edits: a request from another origin or
host refused, only the scene's own files written (the page never names one),
an edit on an older text refused with nothing lost, bad arguments answered
with a message and the file untouched."""

from __future__ import annotations

import http.client
import json
import os
import time

import pytest

from castor.serve.evaluation import Watched
from castor.serve.server import PreviewServer
from castor.settings import Source

# CRLF line ends and a letter outside ASCII: Undo gives back these very bytes
SCENE = "/* un abri, côté rue */\r\nabri = @h(4, 2, 0.2) !cu(0.7, 0.7, 0.7);\r\n> abri;\r\n"


@pytest.fixture
def scene(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    path = tmp_path / "scene.cas"
    path.write_bytes(SCENE.encode())
    return path


@pytest.fixture
def port(scene):
    server = PreviewServer(Watched(Source(("scene.cas",))), "127.0.0.1", 0).start()
    yield server.httpd.server_address[1]
    server.close()


def post(port: int, body, headers: dict | None = None) -> tuple[int, dict]:
    data = body if isinstance(body, bytes) else json.dumps(body).encode()
    connection = http.client.HTTPConnection("127.0.0.1", port, timeout=60)
    connection.request("POST", "/gesture", body=data,
                       headers={"Content-Type": "application/json", **(headers or {})})
    answer = connection.getresponse()
    text = answer.read()
    connection.close()
    try:
        return answer.status, json.loads(text)
    except ValueError:
        return answer.status, {"text": text.decode()}


def snap(port: int) -> dict:
    status, answer = post(port, {"command": "castor.snap", "arguments": {
        "frame": 1, "origin": [6, 0.5, 10], "direction": [0, 0, -1], "pixelSize": 0.01}})
    assert status == 200 and answer["result"]["feature"] == "grid", answer
    return answer


def place(port: int, version: str, **more) -> tuple[int, dict]:
    return post(port, {"command": "castor.place", "arguments": {
        "frame": 1, "primitive": "!cu", "at": [6, 0.5, 0], "size": [1, 1, 1],
        "version": version, **more}})


PLACED = "bloc1 = @t(6, 0.5, 0) @h(1, 1, 1) !cu(0.8, 0.8, 0.8); > abri, bloc1;"


def test_place_writes_the_file_and_undo_gives_its_bytes_back(scene, port):
    inode = os.stat(scene).st_ino
    status, answer = place(port, snap(port)["version"])
    assert status == 200, answer
    assert answer["written"] == [{"file": str(scene), "line": 3, "text": PLACED + "\r"}]
    assert scene.read_bytes() == SCENE.replace("> abri;", PLACED).encode()
    assert os.stat(scene).st_ino != inode  # written beside and renamed: never half a file
    status, answer = post(port, {"command": "undo"})
    assert status == 200 and answer["undo"] == 0
    assert scene.read_bytes() == SCENE.encode()
    status, answer = post(port, {"command": "undo"})
    assert status == 400 and answer["error"].startswith("nothing to undo")


def test_the_edit_shows_in_the_next_frames(scene, port):
    place(port, snap(port)["version"])
    end = time.monotonic() + 30
    while True:  # until the preview has evaluated the file as written
        connection = http.client.HTTPConnection("127.0.0.1", port, timeout=10)
        connection.request("GET", "/scene.json")
        shown = json.loads(connection.getresponse().read())
        connection.close()
        paths = [o["path"] for f in shown["frames"] for o in f["origins"]]
        if "(bloc1)!cu" in paths and not shown["evaluating"]:
            break
        assert time.monotonic() < end, paths
        time.sleep(0.05)
    assert shown["frames"][0]["box"] == [[0, 0, 0], [7, 2, 1]]


def test_a_file_changed_on_disk_between_the_snap_and_the_edit(scene, port):
    version = snap(port)["version"]
    changed = SCENE.replace("un abri", "un abri, changé dans l'éditeur")
    scene.write_bytes(changed.encode())
    status, answer = place(port, version)
    assert status == 400
    assert answer["error"].startswith("the text changed since this gesture began")
    assert scene.read_bytes() == changed.encode()  # nothing lost
    status, answer = place(port, snap(port)["version"])  # on the text as it is: done
    assert status == 200 and "changé dans" in scene.read_text()


def test_undo_is_refused_when_the_file_changed_after_the_edit(scene, port):
    place(port, snap(port)["version"])
    edited = scene.read_text().replace("abri =", "abri  =")
    scene.write_text(edited)
    status, answer = post(port, {"command": "undo"})
    assert status == 400 and "changed after the last edit" in answer["error"]
    assert scene.read_text() == edited


def test_an_edit_must_name_the_text_it_was_made_on(scene, port):
    status, answer = post(port, {"command": "castor.place", "arguments": {
        "primitive": "!cu", "at": [6, 0.5, 0], "size": [1, 1, 1]}})
    assert status == 400 and "'version'" in answer["error"]
    assert scene.read_bytes() == SCENE.encode()


def test_the_page_never_chooses_the_file(scene, port, tmp_path):
    other = tmp_path / "other.cas"
    other.write_text("> !cu(1, 1, 1);\n")
    status, answer = place(port, snap(port)["version"], uri=other.as_uri())
    assert status == 200
    assert other.read_text() == "> !cu(1, 1, 1);\n"
    assert list(answer["result"]["changes"]) == [scene.as_uri()]


@pytest.mark.parametrize("headers", [{"Origin": "http://evil.example"},
                                     {"Host": "evil.example"}])
def test_another_origin_or_host_is_refused(scene, port, headers):
    status, answer = post(port, {"command": "castor.place", "arguments": {
        "primitive": "!cu", "at": [6, 0.5, 0], "size": [1, 1, 1],
        "version": snap(port)["version"]}}, headers)
    assert status == 403
    assert scene.read_bytes() == SCENE.encode()


@pytest.mark.parametrize("body, message", [
    (b"{not json", "not JSON"),
    ([1, 2], "one JSON object"),
    ({"command": "castor.explode"}, "unknown command"),
    ({"command": "castor.place", "arguments": "!cu"}, "one JSON object"),
    ({"command": "castor.snap", "arguments": {"origin": [0, 0, 5], "direction": [0, 0, 0],
                                              "pixel": 0.01}}, "zero length"),
    ({"command": "castor.place", "arguments": {"primitive": "!cu; > x", "at": [0, 0, 0],
                                               "size": [1, 1, 1], "version": "x"}},
     "the text changed"),
    ({"command": "castor.move", "arguments": {"source": "scene.cas:2:22", "by": ["1", 0, 0],
                                              "version": "x"}}, "the text changed"),
])
def test_bad_requests_are_answered_with_a_message(scene, port, body, message):
    status, answer = post(port, body if isinstance(body, bytes) else body)
    assert status == 400 and message in answer["error"], answer
    assert scene.read_bytes() == SCENE.encode()


def test_values_are_checked_never_evaluated(scene, port):
    version = snap(port)["version"]
    for primitive in ("!cu; > x", "!pr(N)", "!pr(1+2)"):
        status, answer = place(port, version, primitive=primitive)
        assert status == 400, answer
    status, answer = post(port, {"command": "castor.move", "arguments": {
        "source": f"{scene}:2:22", "by": ["1", 0, 0], "version": version}})
    assert status == 400 and "'by' must be a number" in answer["error"]
    assert scene.read_bytes() == SCENE.encode()


def test_a_scene_of_several_files_offers_no_editing(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "a.cas").write_text("A = 1;\n")
    (tmp_path / "b.cas").write_text("> !cu(1, 1, 1);\n")
    server = PreviewServer(Watched(Source(("a.cas", "b.cas"))), "127.0.0.1", 0).start()
    try:
        port = server.httpd.server_address[1]
        connection = http.client.HTTPConnection("127.0.0.1", port, timeout=10)
        connection.request("GET", "/editing.json")
        offer = json.loads(connection.getresponse().read())
        assert offer["enabled"] is False and "one scene file" in offer["reason"]
        status, answer = post(port, {"command": "castor.snap", "arguments": {}})
        assert status == 404 and "one scene file" in answer["error"]
    finally:
        server.close()

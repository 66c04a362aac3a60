"""castor --serve over HTTP: the page, the frames, the events after a save, the
errors, the paths it refuses, floods, and Ctrl-C (CLI.md "Live preview")."""

from __future__ import annotations

import http.client
import json
import os
import signal
import socket
import struct
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

from castor.settings import Source
from castor.serve import server as server_module
from castor.serve.evaluation import Overtaken, Watched, evaluate
from castor.serve.server import PreviewServer
from tests.support.cli import hear_ctrl_c
from tests.support.serve import get, newer, raw, triangles, volume, wait_for

BOX = "boite = @h({x}, 3, 4) !cu(0.25, 0.45, 0.85);\n> boite;\n"
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def save(path, text: str) -> None:
    """Write as an editor does, and make sure the modification time moves on."""
    before = os.stat(path).st_mtime_ns if os.path.exists(path) else 0
    with open(path, "w") as handle:
        handle.write(text)
    if os.stat(path).st_mtime_ns == before:
        os.utime(path, ns=(before + 1_000_000, before + 1_000_000))


@pytest.fixture
def scene(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    path = tmp_path / "scene.cas"
    save(path, BOX.format(x=2))
    return path


@pytest.fixture
def preview(scene):
    server = PreviewServer(Watched(Source(("scene.cas",))), "127.0.0.1", 0).start()
    port = server.httpd.server_address[1]
    wait_for(lambda: get(port, "/scene.json")[2].get("evaluated"))
    yield server
    server.close()


def port_of(server) -> int:
    return server.httpd.server_address[1]


def test_the_page_and_its_scripts(preview):
    port = port_of(preview)
    status, kind, page = get(port, "/")
    assert status == 200 and kind.startswith("text/html")
    assert b'<canvas id="view"' in page and b'src="/viewer.js"' in page
    status, kind, script = get(port, "/viewer.js")
    assert status == 200 and kind.startswith("text/javascript")
    assert b"EventSource" in script and b"getContext(\"webgl\"" in script
    status, kind, style = get(port, "/style.css")
    assert status == 200 and kind.startswith("text/css") and b"#diagnostics" in style


def test_the_frames_as_triangles(preview):
    port = port_of(preview)
    status, _, scene = get(port, "/scene.json")
    assert status == 200 and scene["diagnostics"] == [] and not scene["stale"]
    [frame] = scene["frames"]
    assert frame["where"] == "scene.cas:2"
    assert frame["origins"] == [{"path": "(boite)!cu", "colour": [0.25, 0.45, 0.85],
                                 "source": "scene.cas:1:21: !cu",
                                 "element": "boite", "class": None}]
    assert frame["box"] == [[0, 0, 0], [2, 3, 4]]
    status, kind, data = get(port, frame["url"])
    assert status == 200 and kind == "application/octet-stream"
    count = frame["triangles"]
    assert count == 12 and len(data) == count * 40
    tris = triangles(data, count)
    assert volume(tris) == pytest.approx(24.0)  # counter-clockwise from outside
    assert np.frombuffer(data[count * 36:], "<u4").tolist() == [0] * count


def read_event(stream) -> dict:
    """The next 'scene' event of a server-sent event stream."""
    event = {}
    while True:
        line = stream.readline().decode()
        assert line, "the event stream ended"
        line = line.rstrip("\n")
        if not line:
            if event.get("event") == "scene":
                return json.loads(event["data"])
            event = {}
        elif not line.startswith(":"):
            name, _, value = line.partition(": ")
            event[name] = value


def open_events(port: int):
    connection = http.client.HTTPConnection("127.0.0.1", port, timeout=10)
    connection.request("GET", "/events")
    answer = connection.getresponse()
    assert answer.status == 200 and answer.getheader("Content-Type") == "text/event-stream"
    return connection, answer


def test_a_save_sends_an_event_and_new_frames(preview, scene):
    port = port_of(preview)
    connection, stream = open_events(port)
    first = read_event(stream)
    assert first == {"server": first["server"], "version": 1, "evaluating": False,
                     "faceting": False}
    assert first["server"] == get(port, "/scene.json")[2]["server"]
    saved = time.monotonic()
    save(scene, BOX.format(x=5))
    while (news := read_event(stream))["version"] == 1 or news["evaluating"]:
        pass
    delay = time.monotonic() - saved
    connection.close()
    _, _, answer = get(port, "/scene.json")
    [frame] = answer["frames"]
    assert answer["version"] == news["version"] and frame["box"] == [[0, 0, 0], [5, 3, 4]]
    _, _, data = get(port, frame["url"])
    assert volume(triangles(data, frame["triangles"])) == pytest.approx(60.0)
    assert delay < 5  # the figure that matters is in benchmarks/serve_reload.py


def test_a_save_by_renaming_a_new_file_over_the_old_one(preview, scene):
    """vi without backupcopy writes a new file and renames it over the scene."""
    port = port_of(preview)
    fresh = scene.parent / "scene.cas~new"
    fresh.write_text(BOX.format(x=6))
    os.replace(fresh, scene)
    answer = newer(port, 1)
    assert answer["frames"][0]["box"] == [[0, 0, 0], [6, 3, 4]]


def test_a_save_in_place_is_read_when_written_not_when_emptied(preview, scene):
    # an editor that writes in place empties the file first; one slow to write
    # the text (a loaded machine) must not have its empty file shown as the scene
    port = port_of(preview)
    _, _, good = get(port, "/scene.json")
    with open(scene, "w") as handle:
        handle.flush()
        time.sleep(0.3)
        handle.write(BOX.format(x=5))
    answer = newer(port, good["version"])
    assert answer["diagnostics"] == []
    assert [frame["box"] for frame in answer["frames"]] == [[[0, 0, 0], [5, 3, 4]]]


def test_a_file_emptied_on_purpose_is_shown_empty(preview, scene):
    port = port_of(preview)
    _, _, good = get(port, "/scene.json")
    save(scene, "")
    answer = newer(port, good["version"])
    assert answer["frames"] == [] and answer["diagnostics"] == []


def test_an_error_keeps_the_last_good_frames_beside_it(preview, scene):
    port = port_of(preview)
    _, _, good = get(port, "/scene.json")
    save(scene, "boite = @h(2, 3, 4) !cu(0.25, 0.45, 0.85);\n> boite + ;\n")
    answer = newer(port, good["version"])
    assert answer["stale"] is True
    assert answer["frames"] == good["frames"]  # the same frames, at the same address
    [error] = answer["diagnostics"]
    assert error["shown"] == "scene.cas:2:9: error: expected ';' or ',', found '+'"
    assert (error["kind"], error["file"], error["line"], error["column"]) == \
        ("error", "scene.cas", 2, 9)
    assert error["text"] == "> boite + ;"
    assert get(port, good["frames"][0]["url"])[0] == 200
    save(scene, BOX.format(x=3))
    fixed = newer(port, answer["version"])
    assert fixed["stale"] is False and fixed["diagnostics"] == []
    assert fixed["frames"][0]["box"] == [[0, 0, 0], [3, 3, 4]]
    assert get(port, good["frames"][0]["url"])[0] == 404  # old frames are gone


def test_warnings_are_listed_and_the_frames_shown(preview, scene):
    port = port_of(preview)
    save(scene, "boite = @h(2, 3, 4) !cu(0.25, 0.45, 0.85);\nboite = @h(1, 1, 1) !cu(1, 0, 0);\n"
         "> boite;\n")
    answer = newer(port, 1)
    assert [d["shown"] for d in answer["diagnostics"]] == [
        "scene.cas:2:1: warning: object 'boite' redefined; objects defined before keep the "
        "old definition"]
    assert answer["stale"] is False and answer["frames"][0]["box"] == [[0, 0, 0], [1, 1, 1]]


def test_an_included_file_is_watched(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    save(tmp_path / "part.cas", "boite = @h(2, 3, 4) !cu(0.25, 0.45, 0.85);\n")
    save(tmp_path / "main.cas", '#include "part.cas"\n> boite;\n')
    server = PreviewServer(Watched(Source(("main.cas",))), "127.0.0.1", 0).start()
    port = port_of(server)
    try:
        first = wait_for(lambda: (a := get(port, "/scene.json")[2])["evaluated"] and a)
        assert first["files"] == ["main.cas", os.path.join(str(tmp_path), "part.cas")]
        assert first["frames"][0]["box"] == [[0, 0, 0], [2, 3, 4]]
        save(tmp_path / "part.cas", "boite = @h(7, 3, 4) !cu(0.25, 0.45, 0.85);\n")
        answer = newer(port, 1)
        assert answer["frames"][0]["box"] == [[0, 0, 0], [7, 3, 4]]
    finally:
        server.close()


def test_the_last_of_quick_saves_wins(preview, scene):
    port = port_of(preview)
    for x in range(2, 9):
        save(scene, BOX.format(x=x))
        time.sleep(0.01)
    # (an evaluation may read a file the next save has just emptied: the save
    # after it overtakes it)
    wait_for(lambda: (a := get(port, "/scene.json")[2])["frames"]
             and a["frames"][0]["box"][1][0] == 8 and not a["evaluating"])
    time.sleep(0.3)
    answer = get(port, "/scene.json")[2]
    assert answer["frames"][0]["box"] == [[0, 0, 0], [8, 3, 4]] and not answer["evaluating"]


def test_an_overtaken_evaluation_stops(scene):
    job = Watched(Source(("scene.cas",)))
    assert len(evaluate(job).frames) == 1
    with pytest.raises(Overtaken):
        evaluate(job, cancelled=lambda: True)
    # overtaken after its first frame: the second is not made
    save(scene, "boite = @h(1, 1, 1) !cu(1, 0, 0);\n>[X = 1, 9] @h(X, 1, 1) !cu(1, 0, 0);\n")
    asked = []

    def cancelled():
        asked.append(1)
        return len(asked) > 3

    with pytest.raises(Overtaken):
        evaluate(job, cancelled)
    assert len(asked) == 4  # two statements, two frames
    assert len(evaluate(job).frames) == 9


@pytest.mark.parametrize("target", [
    "/../../../../etc/passwd", "/%2e%2e/%2e%2e/%2e%2e/etc/passwd", "/%2E%2E%2F%2E%2E%2Fetc%2Fpasswd",
    "/..%2f..%2f..%2fetc%2fpasswd", "/.%2e/.%2e/etc/passwd", "//etc/passwd", "/etc/passwd",
    "http://127.0.0.1/etc/passwd", "/viewer.js/../../../../etc/passwd", "/./viewer.js",
    "/static/viewer.js", "/index.html", "/scene.cas", "/%73cene.cas", "/link", "/link/",
    "/frames/1/../../scene.cas", "/frames/1/0.bin/../../scene.cas", "/frames/1/%2e%2e/0.bin",
    "/frames/-1/0.bin", "/frames/1/0.bin%00", "/C:%5Cwindows", "\\..\\..\\etc\\passwd", "*",
    "/" + str(os.path.abspath(__file__)), "/events/../scene.cas"])
def test_no_path_of_the_disk_is_served(preview, scene, target):
    os.symlink("/etc/passwd", scene.parent / "link")
    status, body = raw(port_of(preview), target)
    assert status in (400, 404)
    assert b"root:" not in body and b"boite" not in body


def test_another_host_name_is_refused_on_loopback(preview):
    status, _ = raw(port_of(preview), "/scene.json", host="attacker.example:80")
    assert status == 403
    assert raw(port_of(preview), "/scene.json", host="localhost:8000")[0] == 200
    assert raw(port_of(preview), "/scene.json", host="[::1]:8000")[0] == 200


def server_threads() -> int:
    return sum(1 for t in threading.enumerate() if t.name.startswith("Thread-"))


def test_a_flood_and_vanished_browsers_leave_no_thread(preview, monkeypatch):
    monkeypatch.setattr(server_module, "HEARTBEAT_SECONDS", 0.05)
    port = port_of(preview)
    wait_for(lambda: server_threads() == 0, 5)  # those of earlier tests have ended
    # more browsers than there may be event streams open at once, each of which
    # vanishes without a word: each stream's thread ends and frees its place
    for _ in range(server_module.MAX_STREAMS + 4):
        s = socket.create_connection(("127.0.0.1", port))
        s.sendall(b"GET /events HTTP/1.0\r\nHost: 127.0.0.1\r\n\r\n")
        assert s.recv(100).startswith(b"HTTP/1.0 200 OK\r\n")
        s.setsockopt(socket.SOL_SOCKET, socket.SO_LINGER, struct.pack("ii", 1, 0))
        s.close()  # a reset, as when a tab is killed
        wait_for(lambda: server_threads() == 0, 5)
    # a flood: many connections at once, some silent, some half a request
    sockets = []
    for i in range(300):
        try:
            s = socket.create_connection(("127.0.0.1", port), timeout=5)
        except OSError:
            continue
        if i % 2:
            s.sendall(b"GET /scene.json HTTP/1.0\r\n")
        sockets.append(s)
    wait_for(lambda: server_threads() == server_module.MAX_REQUESTS, 5)
    time.sleep(0.1)
    assert server_threads() == server_module.MAX_REQUESTS  # and no more
    for s in sockets:
        s.close()
    wait_for(lambda: server_threads() == 0, 5)
    assert get(port, "/")[0] == 200


def test_event_streams_are_bounded(preview, monkeypatch):
    port = port_of(preview)
    streams = [open_events(port) for _ in range(server_module.MAX_STREAMS)]
    assert get(port, "/events")[0] == 503
    assert get(port, "/")[0] == 200
    for connection, _ in streams:
        connection.close()


def start_castor(args: list[str], cwd) -> tuple[subprocess.Popen, str]:
    env = dict(os.environ, PYTHONPATH=ROOT)
    process = subprocess.Popen([sys.executable, "-m", "castor", "--serve", *args], cwd=cwd,
                               stderr=subprocess.PIPE, stdout=subprocess.DEVNULL, env=env,
                               text=True, preexec_fn=hear_ctrl_c)
    line = process.stderr.readline()
    return process, line


def test_ctrl_c_stops_it_and_frees_the_port(scene):
    with socket.socket() as taken:  # the port asked for is taken: the next one is used
        taken.bind(("127.0.0.1", 0))
        taken.listen()
        busy = taken.getsockname()[1]
        process, line = start_castor(["--port", str(busy), "scene.cas"], scene.parent)
        try:
            assert line.startswith("castor: serving scene.cas at http://127.0.0.1:")
            port = int(line.split("http://127.0.0.1:")[1].split("/")[0])
            assert busy < port <= busy + 50
            assert wait_for(lambda: get(port, "/scene.json")[2]["evaluated"])
            connection, stream = open_events(port)  # a browser still watching
            read_event(stream)
            process.send_signal(signal.SIGINT)
            assert process.wait(timeout=10) == 0
            assert process.stderr.read().endswith("castor: stopped\n")
            connection.close()
        finally:
            process.kill()
            process.stderr.close()
    with socket.socket() as again:  # free at once for the next server (as servers
        again.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)  # bind, past TIME_WAIT)
        again.bind(("127.0.0.1", port))
        again.listen()


@pytest.mark.parametrize("args, message", [
    ([], "castor: error: --serve needs a scene file to watch (not standard input)\n"),
    (["-"], "castor: error: --serve needs a scene file to watch (not standard input)\n"),
    (["-o", "x.stl", "scene.cas"], "castor: error: --serve shows the frames in a web browser; "
     "it writes nothing (-o goes without --serve)\n"),
    (["missing.cas"], "castor: error: cannot read 'missing.cas': No such file or directory\n"),
    (["--bind", "192.0.2.1", "scene.cas"], "castor: error: cannot listen on 192.0.2.1 port "
     "8000: Cannot assign requested address\n"),
])
def test_usage_errors(scene, args, message):
    result = subprocess.run([sys.executable, "-m", "castor", "--serve", *args], cwd=scene.parent,
                            capture_output=True, text=True, timeout=20,
                            env=dict(os.environ, PYTHONPATH=ROOT))
    assert (result.returncode, result.stderr) == (2, message)

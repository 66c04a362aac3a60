"""Editing on screen through the language server (CLI.md, "Editing on screen"):
``workspace/executeCommand`` of castor.snap, castor.place, castor.move and
castor.measure on the editor's buffer; Place and Move reach the editor as
``workspace/applyEdit`` (a client of our own that answers it as an editor
does, and sends the buffer back); bad arguments are JSON-RPC errors with the
buffer untouched; ``castor --lsp --serve`` serves the live preview of the
buffer, says its address, follows the buffer, and sends the page's gestures
(and their Undo) to the editor."""

from __future__ import annotations

import json
import os
import queue
import re
import subprocess
import sys
import threading
import time
import urllib.error
import urllib.request
from pathlib import Path

import pytest

from castor.editing.commands import TextEdit
from castor.editing.text import apply
from tests.support.lsp import ROOT, Client

SCENE = """/* a slab and a bench */
L = 4;     // length
dalle = @h(L, 2, 0.2) !cu(0.7, 0.7, 0.7);
banc = @t(1, 0.5, 0.2) @h(2, 0.4, 0.45) !cu(0.5, 0.3, 0.1);
> dalle, banc;
"""


class _Answering(queue.Queue):
    """The messages from the server; ``workspace/applyEdit`` answered on arrival."""

    def __init__(self, editor: "Editor"):
        super().__init__()
        self.editor = editor

    def put(self, message, *args, **kwargs):
        if message and message.get("method") == "workspace/applyEdit":
            self.editor.answer_edit(message)
        super().put(message, *args, **kwargs)


class Editor(Client):
    """A language client that keeps its buffers and applies the server's edits
    to them as an editor does (then says so with didChange)."""

    def __init__(self, cwd: Path, *options: str):
        env = dict(os.environ, PYTHONPATH=str(ROOT))
        self.process = subprocess.Popen([sys.executable, "-m", "castor", "--lsp", *options],
                                        stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                        stderr=subprocess.PIPE, cwd=cwd, env=env)
        self.messages = _Answering(self)
        self.number = 0
        self.lock = threading.Lock()
        self.buffers: dict[str, list] = {}  # uri -> [text, version]
        self.edits: list[dict] = []  # the applyEdit requests received
        self.refuse = False
        threading.Thread(target=self._read, daemon=True).start()

    def raw(self, data: bytes) -> None:
        with self.lock:
            super().raw(data)

    def open(self, path: Path, text: str | None = None, version: int = 1) -> str:
        uri = super().open(path, text, version)
        self.buffers[uri] = [path.read_text() if text is None else text, version]
        return uri

    def change(self, uri: str, text: str, version: int) -> None:
        self.buffers[uri] = [text, version]
        super().change(uri, text, version)

    def answer_edit(self, message: dict) -> None:
        self.edits.append(message["params"])
        if self.refuse:
            self.send({"jsonrpc": "2.0", "id": message["id"],
                       "result": {"applied": False, "failureReason": "read-only buffer"}})
            return
        changes = message["params"]["edit"]["changes"]
        for uri, edits in changes.items():
            text, version = self.buffers[uri]
            self.buffers[uri] = [apply(text, [TextEdit.from_json(e) for e in edits]),
                                 version + 1]
        self.send({"jsonrpc": "2.0", "id": message["id"], "result": {"applied": True}})
        for uri in changes:
            Client.change(self, uri, *self.buffers[uri])

    def command(self, name: str, arguments: dict) -> dict:
        return self.request("workspace/executeCommand",
                            {"command": name, "arguments": [arguments]}, timeout=60)


@pytest.fixture
def workspace(tmp_path: Path) -> Path:
    (tmp_path / "scene.cas").write_text(SCENE)
    return tmp_path


def started(workspace: Path, *options: str):
    editor = Editor(workspace, *options)
    editor.start(workspace)
    yield editor
    if editor.process.poll() is None:
        editor.process.kill()
        editor.process.wait()


@pytest.fixture
def editor(workspace: Path):
    yield from started(workspace)


def test_the_commands_are_offered(workspace: Path):
    editor = Editor(workspace)
    try:
        capabilities = editor.start(workspace)
        assert set(capabilities["executeCommandProvider"]["commands"]) == {
            "castor.snap", "castor.place", "castor.move", "castor.measure"}
        assert editor.stop() == 0
    finally:
        if editor.process.poll() is None:
            editor.process.kill()
            editor.process.wait()


def test_place_reaches_the_buffer_unsaved(editor: Editor, workspace: Path):
    path = workspace / "scene.cas"
    uri = editor.open(path)
    answer = editor.command("castor.place", {"uri": uri, "primitive": "!cy", "at": [5, 0, 0],
                                             "size": [0.3, 0.3, 2.8]})
    line = "poteau1 = @t(5.15, 0.15, 0) @h(0.15, 0.15, 2.8) !cy(0.8, 0.8, 0.8); "
    assert editor.buffers[uri][0] == SCENE.replace("> dalle, banc;",
                                                   line + "> dalle, banc, poteau1;")
    assert [e["edit"] for e in editor.edits] == [answer["result"]]
    assert editor.edits[0]["label"] == "castor: place"
    assert path.read_text() == SCENE  # the buffer changed, not the file


def test_snap_and_move_read_the_unsaved_buffer(editor: Editor, workspace: Path):
    path = workspace / "scene.cas"
    uri = editor.open(path)
    unsaved = SCENE.replace("> dalle, banc;", "haut = @t(0, 0, 5) @h(1, 1, 1) !cu(1, 0, 0);\n"
                                              "> dalle, banc, haut;")
    editor.change(uri, unsaved, 2)
    found = editor.command("castor.snap", {"uri": uri, "origin": [0.5, 0.5, 20],
                                           "direction": [0, 0, -1], "pixelSize": 0.01})["result"]
    assert found["path"] == "(haut)!cu" and found["point"][2] == pytest.approx(6)
    editor.command("castor.move", {"uri": uri, "source": found["source"], "path": found["path"],
                                   "by": [0, 0, -1.5]})
    assert "haut = @t(0, 0, 3.5) @h(1, 1, 1)" in editor.buffers[uri][0]
    measured = editor.command("castor.measure", {"from": [0, 0, 0], "to": [3, 4, 0]})
    assert measured["result"] == {"distance": 5.0, "dx": 3.0, "dy": 4.0, "dz": 0.0}
    assert path.read_text() == SCENE


@pytest.mark.parametrize("name, arguments, message", [
    ("castor.place", {"primitive": "!xx", "at": [0, 0, 0], "size": [1, 1, 1]},
     "unknown primitive '!xx'"),
    ("castor.place", {"primitive": "!cu", "at": [0, 0, 0], "size": [1, 0, 1]}, "size"),
    ("castor.move", {"source": "nowhere", "by": [1, 0, 0]}, "FILE:LINE:COL"),
    ("castor.snap", {"origin": [0, 0, 5], "direction": [0, 0, 0], "pixel": 0.001},
     "zero length"),
    ("castor.place", {"primitive": "!cu", "at": [0, 0, 0], "size": [1, 1, 1], "frame": 4},
     "frame 4"),
])
def test_bad_arguments_are_errors_and_the_buffer_is_untouched(editor: Editor, workspace: Path,
                                                              name, arguments, message):
    uri = editor.open(workspace / "scene.cas")
    answer = editor.command(name, {"uri": uri, **arguments})
    assert message in answer["error"]["message"]
    assert answer["error"]["code"] == -32602
    assert editor.edits == [] and editor.buffers[uri][0] == SCENE


def test_an_unknown_command_and_arguments_that_are_not_an_object(editor: Editor,
                                                                 workspace: Path):
    uri = editor.open(workspace / "scene.cas")
    assert "error" in editor.command("castor.explode", {"uri": uri})
    answer = editor.request("workspace/executeCommand",
                            {"command": "castor.place", "arguments": [1, 2]})
    assert "one JSON object" in answer["error"]["message"]
    assert editor.process.poll() is None and editor.edits == []


def test_an_edit_the_editor_refuses_is_an_error(editor: Editor, workspace: Path):
    uri = editor.open(workspace / "scene.cas")
    editor.refuse = True
    answer = editor.command("castor.place", {"uri": uri, "primitive": "!cu", "at": [0, 0, 0],
                                             "size": [1, 1, 1]})
    assert answer["error"]["message"] == "the editor did not apply the edit: read-only buffer"
    assert editor.buffers[uri][0] == SCENE


# --- castor --lsp --serve

def post(url: str, body: dict) -> tuple[int, dict]:
    request = urllib.request.Request(url + "gesture", data=json.dumps(body).encode(),
                                     headers={"Content-Type": "application/json"})
    try:
        with urllib.request.urlopen(request, timeout=60) as answer:
            return answer.status, json.loads(answer.read())
    except urllib.error.HTTPError as error:
        return error.code, json.loads(error.read())


def scene_json(url: str) -> dict:
    with urllib.request.urlopen(url + "scene.json", timeout=10) as answer:
        return json.loads(answer.read())


def wait_for_scene(url: str, wanted, seconds: float = 60) -> dict:
    """The preview's scene once ``wanted(scene)`` (an evaluation finished),
    asked again until then; a failure after ``seconds``."""
    end = time.monotonic() + seconds
    while True:
        scene = scene_json(url)
        if scene["evaluated"] and not scene["evaluating"] and wanted(scene):
            return scene
        if time.monotonic() > end:
            raise AssertionError(f"the preview never showed it: {paths(scene)}, version "
                                 f"{scene['version']}, evaluating {scene['evaluating']}, "
                                 f"{scene['diagnostics']}")
        time.sleep(0.05)


def paths(scene: dict) -> list[str]:
    return [o["path"] for f in scene["frames"] for o in f["origins"]]


def test_lsp_serve_previews_the_buffer_and_sends_the_pages_gestures(workspace: Path):
    path = workspace / "scene.cas"
    for editor in started(workspace, "--serve", "--port", "0"):
        shown = editor.wait(lambda m: m.get("method") == "window/showMessage")
        url = re.search(r"http://127\.0\.0\.1:\d+/", shown["params"]["message"]).group()
        uri = editor.open(path)
        # the preview follows the buffer, unsaved
        unsaved = SCENE.replace("> dalle, banc;", "haut = @t(0, 0, 5) !cu(1, 0, 0);\n"
                                                  "> dalle, banc, haut;")
        editor.change(uri, unsaved, 2)
        scene = wait_for_scene(url, lambda s: "(haut)!cu" in paths(s))
        assert paths(scene) == ["(dalle)!cu", "(banc)!cu", "(haut)!cu"]
        # a gesture on the page: the edit reaches the editor, not the file
        status, snapped = post(url, {"command": "castor.snap", "arguments": {
            "frame": 1, "origin": [6, 0.5, 10], "direction": [0, 0, -1], "pixelSize": 0.01}})
        assert status == 200 and snapped["result"]["feature"] == "grid"
        status, placed = post(url, {"command": "castor.place", "arguments": {
            "frame": 1, "primitive": "!cu", "at": snapped["result"]["point"],
            "size": [1, 1, 1], "version": snapped["version"]}})
        assert status == 200, placed
        assert placed["written"][0]["text"].startswith("bloc1 = @t(6, 0.5, 0) @h(1, 1, 1) !cu(")
        assert placed["written"][0]["text"].endswith("> dalle, banc, haut, bloc1;")
        assert editor.edits[-1]["edit"] == placed["result"]
        assert "bloc1 = @t(6, 0.5, 0)" in editor.buffers[uri][0]
        wait_for_scene(url, lambda s: "(bloc1)!cu" in paths(s))
        # Undo on the page: the inverse edit goes to the editor too
        status, undone = post(url, {"command": "undo"})
        assert status == 200, undone
        assert editor.buffers[uri][0] == unsaved
        wait_for_scene(url, lambda s: "(bloc1)!cu" not in paths(s))
        assert path.read_text() == SCENE  # nothing was saved
        assert editor.stop() == 0


def test_a_newer_buffer_never_stops_the_preview_mid_statement(monkeypatch, tmp_path: Path):
    """The language server's worker imports and evaluates on its own thread: a
    stop raised inside an import of the preview's thread left importlib's lock
    held, and both threads waited for ever (a preview stuck on "evaluating")."""
    from castor.analysis.worker import Stopper
    from castor.serve.buffers import BufferPreview

    stops = []
    monkeypatch.setattr(Stopper, "stop", lambda self, stale: stops.append(stale) or False)
    preview = BufferPreview()
    preview.follow(str(tmp_path / "scene.cas"), SCENE, {})
    preview.follow(str(tmp_path / "scene.cas"), SCENE + "> dalle;\n", {})
    assert preview._wanted == 3 and stops == []


@pytest.mark.parametrize("options, message", [
    (["--bind", "203.0.113.5"], "castor: error: cannot listen on 203.0.113.5 port 8000"),
    (["a.cas", "b.cas"], "castor: error: --lsp --serve previews one scene"),
])
def test_lsp_serve_usage_errors(workspace: Path, options, message):
    done = subprocess.run([sys.executable, "-m", "castor", "--lsp", "--serve", *options],
                          stdin=subprocess.DEVNULL, capture_output=True, text=True,
                          cwd=workspace, env=dict(os.environ, PYTHONPATH=str(ROOT)), timeout=60)
    assert done.returncode == 2 and done.stdout == ""
    assert done.stderr.startswith(message)

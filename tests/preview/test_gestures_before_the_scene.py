"""A gesture that reaches ``castor --lsp --serve`` before the editor's buffer of
the scene (a page or script that posts as soon as the address is known) waits
for it, within reason, as a hover waits for the first analysis: it was refused
at once ("no scene yet", HTTP 400), one time in several under load."""

from __future__ import annotations

import threading

import pytest

from castor.editing.commands import Cache, CommandError
from castor.editing.document import path_to_uri
from castor.serve import gestures
from castor.serve.gestures import Gestures

SCENE = "mur = @h(4, 0.2, 2.5) !cu(0.9, 0.9, 0.9);\n> mur;\n"
MEASURE = {"command": "castor.measure", "arguments": {"frame": 1, "object": "mur"}}


def test_a_gesture_waits_for_the_editor_to_open_the_scene(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    path = tmp_path / "mur.cas"
    path.write_text(SCENE)
    waiting = Gestures("", Cache())
    opened = threading.Timer(0.3, lambda: setattr(waiting, "uri", path_to_uri(str(path))))
    opened.start()
    try:
        answer = waiting.answer(MEASURE)
    finally:
        opened.cancel()
    assert answer["result"]["volume"] == pytest.approx(4 * 0.2 * 2.5)


def test_without_a_scene_the_gesture_is_refused_after_the_wait(monkeypatch):
    monkeypatch.setattr(gestures, "FIRST_SCENE_WAIT", 0.2)
    with pytest.raises(CommandError, match="^no scene yet: open one in the editor$"):
        Gestures("", Cache()).answer(MEASURE)

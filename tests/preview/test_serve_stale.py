"""The live preview stops a stale evaluation at once, inside a statement too
(as the language server does, issue 29 item 11): a save while one statement of
40,000 cubes is being parsed stops that parse, and the saved text is shown.
Checked by what the parser finished, never by the clock."""

from __future__ import annotations

import threading
import time

from castor.analysis import reuse
from castor.language.parse import Parser
from castor.serve.evaluation import Watched
from castor.serve.server import PreviewServer
from castor.settings import Source

from tests.support.scenes import LONG


def test_a_save_stops_the_evaluation_inside_a_long_statement(monkeypatch, tmp_path):
    parsing = threading.Event()
    parsed: list[int] = []
    original = Parser.parse

    def parse(self, chunk):
        if len(chunk.text) > 100_000:
            parsing.set()
        yield from original(self, chunk)
        parsed.append(len(chunk.text))

    monkeypatch.setattr(Parser, "parse", parse)
    monkeypatch.chdir(tmp_path)
    reuse.forget()
    scene = tmp_path / "scene.cas"
    scene.write_text(LONG)
    server = PreviewServer(Watched(Source(("scene.cas",))), "127.0.0.1", 0).start()
    try:
        assert parsing.wait(120)
        scene.write_text("small = @h(2, 3, 4) !cu(0, 1, 0);\n> small;\n")  # saved meanwhile
        preview = server.preview
        end = time.monotonic() + 120
        while time.monotonic() < end:
            with preview.state:
                snapshot = preview.snapshot
            if snapshot.evaluated and snapshot.frames:
                break
            time.sleep(0.05)
        assert [f.polygons for f in snapshot.frames] == [6]
        assert snapshot.frames[0].box == ((0.0, 0.0, 0.0), (2.0, 3.0, 4.0))
        assert snapshot.version == 1  # the long text's evaluation never finished
    finally:
        server.close()
    assert not [n for n in parsed if n > 100_000]  # never parsed whole

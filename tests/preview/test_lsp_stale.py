"""Stale work stops at once (issue 29, item 11): one statement of 40,000 cubes
is seconds of parsing; a newer text of the document stops its analysis inside
that statement, not after it. Checked by what happened and in which order
(the worker's log, what the parser finished), never by the clock;
benchmarks/lsp_long_statement.py prints the time."""

from __future__ import annotations

import threading

from castor.analysis import reuse
from castor.analysis.scene import analyse_buffers
from castor.analysis.worker import Submission, Worker
from castor.language.parse import Parser
from tests.support.scenes import LONG

SHORT = "small = !cu(0, 1, 0);\n> small;\n"


def test_a_newer_text_stops_the_analysis_inside_a_long_statement(monkeypatch, tmp_path):
    assert len(LONG) > 1_000_000
    parsing = threading.Event()
    parsed: list[int] = []  # the length of each statement the parser went through to the end
    original = Parser.parse

    def parse(self, chunk):
        if len(chunk.text) > 100_000:
            parsing.set()  # the long statement's parse has begun
        yield from original(self, chunk)
        parsed.append(len(chunk.text))

    monkeypatch.setattr(Parser, "parse", parse)
    reuse.forget()
    results: list[tuple[int, object]] = []
    done = threading.Event()

    def finished(submission, analysis, problem):
        results.append((submission.version, analysis, problem))
        done.set()

    name = str(tmp_path / "scene.cas")
    worker = Worker(lambda job, cancelled: analyse_buffers(job.text, job.name, {}, cancelled),
                    finished)
    try:
        worker.submit(Submission("scene", LONG, name, version=1))
        assert parsing.wait(120)
        worker.submit(Submission("scene", SHORT, name, version=2))  # typed meanwhile
        assert done.wait(120)
    finally:
        worker.stop()
    assert [(e[0], e[2]) for e in worker.log] == [("started", 1), ("stopped", 1),
                                                  ("started", 2), ("finished", 2)]
    assert [(version, problem) for version, _, problem in results] == [(2, None)]
    assert [d.name for d in results[0][1].definitions if d.kind == "object"] == ["small"]
    assert not [n for n in parsed if n > 100_000]  # the long statement was never parsed whole
    assert worker.thread.is_alive() or worker.stopped


def test_the_worker_goes_on_after_many_stops(tmp_path):
    """Stops that come at any moment (between jobs, in the last lines of one)
    never kill the worker or lose the newest text."""
    results = []
    done = threading.Event()

    def finished(job, analysis, problem):
        results.append(job.version)
        if job.version == 40:
            done.set()

    name = str(tmp_path / "scene.cas")
    worker = Worker(lambda job, cancelled: analyse_buffers(job.text, job.name, {}, cancelled),
                    finished)
    try:
        for version in range(1, 41):
            worker.submit(Submission("scene", f"a = !cu(1, 0, 0);\n> @h({version}, 1, 1) a;\n",
                                     name, version=version))
        assert done.wait(60)
    finally:
        worker.stop()
    assert results[-1] == 40 and results == sorted(results)


def test_the_last_of_many_quick_edits_is_answered(tmp_path):
    """Thirty edits sent back to back, broken and whole, each stopping the
    analysis of the one before wherever it stood: the server lives on and the
    last text's diagnostics are published, for that version."""
    import shutil

    from tests.support.lsp import EXAMPLES, started_client

    shutil.copy(EXAMPLES / "bus_shelter.cas", tmp_path / "bus_shelter.cas")
    shutil.copytree(EXAMPLES / "bus_shelter", tmp_path / "bus_shelter")
    path = tmp_path / "bus_shelter.cas"
    text = path.read_text()
    for c in started_client(tmp_path):
        uri = c.open(path)
        for version in range(2, 32):
            edited = text.replace("PHASE = 0;", f"PHASE = 0;\nX{version} = {version} +;"
                                  if version % 2 else f"PHASE = 0;\nX{version} = {version};")
            c.change(uri, edited, version)
        found = c.diagnostics(uri, 31, timeout=60)
        assert [d["message"] for d in found] and all("X31" not in d["message"] for d in found)
        assert found[0]["range"]["start"]["line"] == text.split("\n").index("PHASE = 0;") + 1
        hover = c.at("textDocument/hover", uri, text.split("\n").index("PHASE = 0;"), 0)
        assert hover["contents"]["value"].startswith("PHASE = 0")
        assert c.process.poll() is None

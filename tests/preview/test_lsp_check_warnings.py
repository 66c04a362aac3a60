"""The language server publishes the warnings castor --check gives: a frame
its tree shows empty, a scene without '>' (tests/cli/test_check_warnings.py
compares the analysis with --check; here, what an editor is sent)."""

from pathlib import Path

import pytest

from tests.support.lsp import Client, started_client


@pytest.fixture
def client(tmp_path: Path):
    yield from started_client(tmp_path)


def test_the_editor_is_told_of_an_empty_frame_and_of_no_frame(client: Client, tmp_path: Path):
    uri = client.open(tmp_path / "empty.cas", "a = $D(!cu(1,1,1), @s(2) !cu(1,1,1));\n> a;\n")
    found = client.diagnostics(uri, 1)
    assert [(d["message"], d["severity"], d["range"]["start"]) for d in found] == [
        ("frame 1 is empty: its objects have no volume", 2, {"line": 1, "character": 0})]
    client.change(uri, "a = $D(!cu(1,1,1), @s(2) !cu(1,1,1));\n", 2)
    assert [d["message"] for d in client.diagnostics(uri, 2)] == [
        "the scene has no '>' command, so nothing would be written; '> OBJECT;' writes an "
        "object's polygons"]
    client.change(uri, "a = !cu(1,1,1);\n> a;\n", 3)
    assert client.diagnostics(uri, 3) == []

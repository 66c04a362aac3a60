"""castor --lsp reads the unsaved text of the files a scene #includes, as a C
language server reads an unsaved header: an edit of an included file's buffer
(didChange, no save) changes the diagnostics of the scene that includes it,
in that file and in the scene's own; closing the buffer unsaved goes back to
the file on disk, which is never written."""

from __future__ import annotations

import time
from pathlib import Path

import pytest

from tests.support.lsp import Client, line_of, started_client


@pytest.fixture
def workspace(tmp_path: Path) -> Path:
    (tmp_path / "walls.cas").write_text("H = 3;\nwall = @h(4, 0.2, H) !cu(1, 0, 0);\n")
    (tmp_path / "main.cas").write_text('#include "walls.cas"\n\nhouse = $U(wall, @t(0, 4, 0) wall);\n> house;\n')
    return tmp_path


@pytest.fixture
def client(workspace: Path):
    yield from started_client(workspace)


def _settled(client: Client, uri: str, wanted, timeout: float = 30) -> list:
    """The diagnostics published for ``uri`` once ``wanted(them)`` holds."""
    return _all_settled(client, {uri: wanted}, timeout)[uri]


def _all_settled(client: Client, wanted: dict, timeout: float = 30) -> dict:
    """The last diagnostics published for each URI of ``wanted`` once each
    ``wanted[uri](them)`` holds (in whatever order they are published)."""
    last: dict = {}

    def done(message) -> bool:
        if message.get("method") == "textDocument/publishDiagnostics":
            uri = message["params"]["uri"]
            if uri in wanted:
                last[uri] = message["params"]["diagnostics"]
        return all(uri in last and test(last[uri]) for uri, test in wanted.items())

    client.wait(done, timeout)
    return last


def test_an_unsaved_included_file_changes_the_scene_s_diagnostics(client: Client,
                                                                  workspace: Path):
    walls, main = workspace / "walls.cas", workspace / "main.cas"
    on_disk = walls.read_bytes()
    stamp = walls.stat().st_mtime_ns
    main_uri = client.open(main)
    assert client.diagnostics(main_uri, 1) == []
    walls_uri = client.open(walls)
    # the object renamed in the buffer, not saved: the scene's use of it is now wrong
    renamed = walls.read_text().replace("wall =", "mur =")
    client.change(walls_uri, renamed, 2)
    found = _settled(client, main_uri, lambda d: d != [])
    assert any("object 'wall' is not defined" in d["message"] for d in found), found
    assert found[0]["range"]["start"]["line"] == 2
    # an error in the included buffer is published for the included file, where it is
    broken = walls.read_text().replace("!cu(1, 0, 0)", "!cu(1, 0)")
    client.change(walls_uri, broken, 3)
    in_walls = _settled(client, walls_uri, lambda d: d != [])
    assert in_walls[0]["range"]["start"]["line"] == line_of(broken, "wall =")
    assert "argument" in in_walls[0]["message"]
    # the buffer put right again: everything clears
    client.change(walls_uri, walls.read_text(), 4)
    _all_settled(client, {walls_uri: lambda d: d == [], main_uri: lambda d: d == []})
    assert walls.read_bytes() == on_disk and walls.stat().st_mtime_ns == stamp
    client.stop()


def test_closing_an_unsaved_included_buffer_goes_back_to_the_file(client: Client,
                                                                   workspace: Path):
    walls, main = workspace / "walls.cas", workspace / "main.cas"
    main_uri = client.open(main)
    assert client.diagnostics(main_uri, 1) == []
    walls_uri = client.open(walls)
    client.change(walls_uri, walls.read_text().replace("wall =", "mur ="), 2)
    assert _settled(client, main_uri, lambda d: d != [])
    client.notify("textDocument/didClose", {"textDocument": {"uri": walls_uri}})
    _settled(client, main_uri, lambda d: d == [])
    client.stop()


def test_hover_in_the_scene_reads_the_unsaved_parameter(client: Client, workspace: Path):
    walls, main = workspace / "walls.cas", workspace / "main.cas"
    main_uri = client.open(main)
    assert client.diagnostics(main_uri, 1) == []
    walls_uri = client.open(walls)
    changed = walls.read_text().replace("H = 3;", "H = 4.5;")
    client.change(walls_uri, changed, 2)
    end = time.monotonic() + 30
    while True:  # the scene analysed again with the buffer: H is 4.5 there
        hover = client.at("textDocument/hover", walls_uri, 0, 0)
        if hover and "4.5" in hover["contents"]["value"]:
            break
        assert time.monotonic() < end, hover
        time.sleep(0.1)
    assert hover["contents"]["value"].startswith("H = 4.5")
    client.stop()

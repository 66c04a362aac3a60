"""A file of the workspace that no file name could be read from (a NUL byte in
one of its ``#include`` names) does not stop castor --lsp: the workspace's scan
for the scenes that include an opened file skips it, the opened scene gets its
diagnostics, and the bad file, opened, gets its own diagnostic saying why. A
document whose URI names no possible file (``%00``) is not of the workspace."""

from __future__ import annotations

from pathlib import Path

import pytest

from castor.analysis.workspace import includes, scenes_including
from tests.support.lsp import Client, started_client

BAD = b'x = !cu(1, 1, 1);\n#include "a\x00b.cas"\n> x;\n'


@pytest.fixture
def workspace(tmp_path: Path) -> Path:
    (tmp_path / "parts.cas").write_text("post = @h(0.2, 0.2, 2) !cu(1, 0, 0);\n")
    (tmp_path / "main.cas").write_text('#include "parts.cas"\nshed = $U(post, shedd);\n> shed;\n')
    (tmp_path / "other.cas").write_bytes(BAD)
    return tmp_path


def test_the_scan_skips_an_include_name_with_a_nul_byte(workspace: Path):
    assert includes(str(workspace / "other.cas")) == []
    main = str((workspace / "main.cas").resolve())
    assert includes(main) == [str((workspace / "parts.cas").resolve())]
    assert scenes_including(str(workspace / "parts.cas"), [str(workspace)]) == [main]
    assert scenes_including(main, [str(workspace)]) == []


@pytest.fixture
def client(workspace: Path):
    yield from started_client(workspace)


def test_a_scene_gets_its_diagnostics_beside_a_file_with_a_nul_include(client: Client,
                                                                        workspace: Path):
    shown: list = []
    uri = client.open(workspace / "main.cas")

    def published(message) -> bool:
        if message.get("method") == "window/showMessage":
            shown.append(message["params"])
        return (message.get("method") == "textDocument/publishDiagnostics"
                and message["params"]["uri"] == uri)

    diagnostics = client.wait(published, 30)["params"]["diagnostics"]
    assert shown == []
    assert [(d["range"]["start"], d["message"]) for d in diagnostics] == [
        ({"line": 1, "character": 16}, "object 'shedd' is not defined"),
        ({"line": 2, "character": 2}, "object 'shed' is not defined (its definition had errors)")]
    other = client.open(workspace / "other.cas", BAD.decode())
    assert [(d["range"]["start"], d["message"]) for d in client.diagnostics(other, 1)] == [
        ({"line": 1, "character": 9},
         "include file name 'a\\x00b.cas' holds a NUL byte, which no file name can hold")]


def test_a_uri_with_a_nul_byte_is_no_file_of_the_workspace(client: Client, workspace: Path):
    uri = workspace.as_uri() + "/a%00b.cas"
    client.notify("textDocument/didOpen", {"textDocument": {
        "uri": uri, "languageId": "castor", "version": 1, "text": "> y;\n"}})
    said = client.wait(lambda m: m.get("method") in ("window/showMessage",
                                                     "textDocument/publishDiagnostics"), 30)
    assert said["method"] == "textDocument/publishDiagnostics"
    assert [d["message"] for d in said["params"]["diagnostics"]] == [
        "castor analyses files of the workspace only; this document is not one (open it from "
        "the folder of the scene)"]
    main = client.open(workspace / "main.cas")
    assert [d["message"] for d in client.diagnostics(main, 1)][:1] == [
        "object 'shedd' is not defined"]

"""castor --lsp, the editing loop (issue 29, items 9 and 10): a part opened alone is
analysed with the scene that includes it; hover and definition where they were
missing (a repetition's variable, an operand after a transformation, every
word of the vocabulary); a request that comes before the first analysis waits
for it; renaming objects, parameters and macros across #includes, never in
comments or strings."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest
from tests.support.lsp import EXAMPLES, Client, line_of, started_client

from castor.booleans import BOOLEANS
from castor.primitives import PRIMITIVES
from castor.transformations import TRANSFORMS


@pytest.fixture
def shelter(tmp_path: Path) -> Path:
    shutil.copy(EXAMPLES / "bus_shelter.cas", tmp_path / "bus_shelter.cas")
    shutil.copytree(EXAMPLES / "bus_shelter", tmp_path / "bus_shelter")
    return tmp_path


@pytest.fixture
def client(shelter: Path):
    yield from started_client(shelter)


def test_a_part_opened_alone_is_analysed_with_the_scene_that_includes_it(
        client: Client, shelter: Path):
    part = shelter / "bus_shelter" / "shelter.cas"
    text = part.read_text()
    uri = client.open(part)  # the scene that includes it is not open
    assert client.diagnostics(uri) == []  # alone: 40 errors (XA, LT, the colours)
    line = line_of(text, "X0 = XA + 0.5;")
    hover = client.at("textDocument/hover", uri, line, 5)["contents"]["value"]
    assert hover.startswith("XA = ")  # defined by the scene before the #include
    broken = text.replace("LA = 5;", "LA = 5 +;")
    client.change(uri, broken, 2)
    found = client.diagnostics(uri, 2)
    assert found[0]["range"]["start"]["line"] == line_of(broken, "LA = 5 +;")
    assert not [d for d in found if "'XA'" in d["message"] or "ACIER_VERT" in d["message"]]
    client.notify("textDocument/didClose", {"textDocument": {"uri": uri}})
    assert client.diagnostics(uri) == []  # cleared with the scene analysed for it


SCENE = """\
#define ROUGE 1, 0, 0
X2 = 2;
Y1 = 1;
caisse = !cu(ROUGE);  // caisse: the body, not renamed in a comment
roue = !cy(0, 0, 1);
essieu = !cu(0, 1, 0);
auto = $U(caisse, @t(X2, Y1, 0) roue, essieu);
> @h(X2, Y1, 1) auto;
>[T = 0, 1, 0.5] @rz(45 * T) auto;
"""


@pytest.fixture
def small(tmp_path: Path):
    (tmp_path / "auto.cas").write_text(SCENE)
    (tmp_path / "part.cas").write_text('#include "auto.cas"\n/* X2 caisse */ '
                                       'deux = $U(caisse, @t(X2, 0, 0) caisse);\n> deux;\n')
    return tmp_path


def _position(text: str, line_start: str, word: str, nth: int = 0) -> tuple[int, int]:
    line = line_of(text, line_start)
    source = text.split("\n")[line]
    column = -1
    for _ in range(nth + 1):
        column = source.index(word, column + 1)
    return line, column


def test_hover_and_definition_where_they_were_missing(small: Path):
    for c in started_client(small):
        uri = c.open(small / "auto.cas")
        # asked at once, before the first analysis has come: it waits for it
        line, column = _position(SCENE, "> @h", "X2")
        assert c.at("textDocument/hover", uri, line, column)["contents"]["value"] \
            .startswith("X2 = 2 ")
        line, column = _position(SCENE, "auto =", "roue")
        found = c.at("textDocument/definition", uri, line, column)
        assert [(d["range"]["start"]["line"], d["range"]["start"]["character"]) for d in found] \
            == [(line_of(SCENE, "roue ="), 0)]
        line, column = _position(SCENE, ">[T", "T", 1)
        assert c.at("textDocument/hover", uri, line, column)["contents"]["value"] \
            == "T: the variable of the repetition [T = 0, 1, 0.5]"
        found = c.at("textDocument/definition", uri, line, column)
        assert found[0]["range"]["start"] == {"line": line, "character": 2}


def test_every_word_of_the_vocabulary_has_a_hover(small: Path):
    words = [f"!{n}" for n in PRIMITIVES] + [f"@{n}" for n in TRANSFORMS] + \
        [f"${n}" for n in BOOLEANS]
    text = "".join(f"// {w}\n{w};\n" for w in words)  # hover reads the word, not the syntax
    (small / "words.cas").write_text(text)
    for c in started_client(small):
        uri = c.open(small / "words.cas")
        for k, w in enumerate(words):
            answer = c.at("textDocument/hover", uri, 2 * k + 1, 1)
            assert answer is not None, w
            assert answer["contents"]["value"].startswith(f"{w}("), (w, answer)
        assert c.process.poll() is None


def test_requests_asked_at_once_are_answered_every_time(small: Path):
    for c in started_client(small):
        for k in range(4):
            name = small / f"copy{k}.cas"
            name.write_text(SCENE)
            uri = c.open(name)
            line, column = _position(SCENE, "auto =", "caisse")
            found = c.at("textDocument/definition", uri, line, column)
            assert found and found[0]["range"]["start"]["line"] == line_of(SCENE, "caisse ="), k


def _edits(answer: dict) -> dict[str, list[tuple[int, int, int]]]:
    return {uri.rsplit("/", 1)[1]: sorted((e["range"]["start"]["line"],
                                           e["range"]["start"]["character"],
                                           e["range"]["end"]["character"]) for e in edits)
            for uri, edits in answer["changes"].items()}


def _rename(c: Client, uri: str, line: int, column: int, new: str):
    return c.request("textDocument/rename", {
        "textDocument": {"uri": uri}, "position": {"line": line, "character": column},
        "newName": new})


def test_rename_objects_parameters_and_macros_across_includes(small: Path):
    part = (small / "part.cas").read_text()
    for c in started_client(small):
        uri = c.open(small / "part.cas")
        assert c.diagnostics(uri, 1) == []
        line, column = _position(part, "/*", "caisse", 1)  # the use after '$U('
        edits = _edits(_rename(c, uri, line, column, "coffre")["result"])
        second = part.split("\n")[1]
        first, last = second.index("caisse", 10), second.rindex("caisse")
        assert edits == {"auto.cas": [(3, 0, 6), (6, 10, 16)],  # not in the comment
                         "part.cas": [(1, first, first + 6), (1, last, last + 6)]}  # nor here
        line, column = _position(part, "/*", "X2", 1)
        edits = _edits(_rename(c, uri, line, column, "LARGEUR")["result"])
        assert edits == {"auto.cas": [(1, 0, 2), (6, 21, 23), (7, 5, 7)],
                         "part.cas": [(1, second.rindex("X2"), second.rindex("X2") + 2)]}
        auto_uri = c.open(small / "auto.cas")
        edits = _edits(_rename(c, auto_uri, 3, 14, "RED")["result"])  # the macro in !cu(ROUGE)
        assert edits == {"auto.cas": [(0, 8, 13), (3, 13, 18)]}


def test_rename_refuses_what_cannot_be_renamed(small: Path):
    for c in started_client(small):
        uri = c.open(small / "auto.cas")
        c.diagnostics(uri, 1)
        refused = _rename(c, uri, *_position(SCENE, "roue =", "roue"), "Roue")
        assert "lowercase letter" in refused["error"]["message"]
        refused = _rename(c, uri, *_position(SCENE, "auto =", "roue"), "essieu")
        assert refused["error"]["message"] == "'essieu' already names a object (auto.cas:6)" \
            or "already names" in refused["error"]["message"]
        refused = _rename(c, uri, *_position(SCENE, "caisse =", "cu"), "cube")
        assert "only an object, a parameter or a macro" in refused["error"]["message"]
        refused = _rename(c, uri, *_position(SCENE, "caisse =", "body"), "corps")
        assert "error" in refused
        prepared = c.request("textDocument/prepareRename", {
            "textDocument": {"uri": uri},
            "position": dict(zip(("line", "character"), _position(SCENE, "auto =", "essieu")))})
        assert prepared["result"]["placeholder"] == "essieu"

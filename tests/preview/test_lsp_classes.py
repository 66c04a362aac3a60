"""castor --lsp and the classes of objects (LANGUAGE.md §11): completion after
``// [`` on a definition's line (classes, then a class's predefined types and
settings, then a setting's values), the class in an object's hover and in the
outline, and the warnings of a misspelt annotation as it is typed."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest
from tests.support.lsp import EXAMPLES, Client, line_of, started_client

from castor.language.classes import BY_NAME, CLASSES


@pytest.fixture
def house(tmp_path: Path) -> Path:
    shutil.copy(EXAMPLES / "house.cas", tmp_path / "house.cas")
    return tmp_path / "house.cas"


@pytest.fixture
def client(house: Path):
    yield from started_client(house.parent)


def _opened(client: Client, house: Path) -> tuple[str, str]:
    text = house.read_text()
    uri = client.open(house)
    client.diagnostics(uri, 1)
    return uri, text


def _complete_at_end_of(client: Client, uri: str, text: str, start: str, version: int,
                        **more) -> list[dict]:
    """The completions at the end of the line starting with ``start``."""
    client.change(uri, text, version)
    line = line_of(text, start)
    column = len(text.split("\n")[line])
    return client.at("textDocument/completion", uri, line, column, **more)["items"]


def test_completion_after_the_bracket_lists_the_classes(client: Client, house: Path):
    uri, text = _opened(client, house)
    edited = text.replace("// [wall] the four walls", "// [")
    items = _complete_at_end_of(client, uri, edited, "murs =", 2,
                                context={"triggerKind": 2, "triggerCharacter": "["})
    labels = {i["label"] for i in items}
    assert {info.short for info in CLASSES} <= labels  # short names
    assert {info.ifc for info in CLASSES} <= labels  # and IFC names
    assert not labels & {"murs", "plein", "H", "ENDUIT"}  # no names of the scene
    wall = next(i for i in items if i["label"] == "wall")
    assert wall["detail"] == "IfcWall"
    assert wall["kind"] == 7  # Class
    # a word begun: the same list (the editor filters it)
    edited = text.replace("// [wall] the four walls", "// [wa")
    items = _complete_at_end_of(client, uri, edited, "murs =", 3)
    assert "wall" in {i["label"] for i in items}
    # on a parameter's line, a storey
    edited = text.replace("L = 9;        /* length (x) */", "L = 9;  // [")
    items = _complete_at_end_of(client, uri, edited, "L = 9", 4)
    assert [i["label"] for i in items] == ["storey"]


def test_completion_after_a_class_lists_its_types_and_settings(client: Client, house: Path):
    uri, text = _opened(client, house)
    edited = text.replace("// [wall] the four walls", "// [slab ")
    items = _complete_at_end_of(client, uri, edited, "murs =", 2)
    assert {i["label"] for i in items} == set(BY_NAME["slab"].types)
    assert {"floor", "roof", "baseslab"} <= {i["label"] for i in items}
    edited = text.replace("[door hinge=left swing=in] the front door", "[door ")
    items = _complete_at_end_of(client, uri, edited, "porte_trou =", 3)
    labels = {i["label"] for i in items}
    assert {"hinge=", "swing=", "gate"} <= labels
    hinge = next(i for i in items if i["label"] == "hinge=")
    assert hinge["detail"] == "hinge=left|right" and hinge["insertText"] == "hinge="
    # a setting given is not offered again, and a type given leaves the settings
    edited = text.replace("[door hinge=left swing=in] the front door", "[door gate hinge=right ")
    items = _complete_at_end_of(client, uri, edited, "porte_trou =", 4)
    assert [i["label"] for i in items] == ["swing="]
    # after 'hinge=' its values
    edited = text.replace("[door hinge=left swing=in] the front door", "[door hinge=")
    items = _complete_at_end_of(client, uri, edited, "porte_trou =", 5,
                                context={"triggerKind": 2, "triggerCharacter": "="})
    assert [i["label"] for i in items] == ["left", "right"]
    # past the ']' the description: nothing offered
    edited = text.replace("// [wall] the four walls", "// [wall] the ")
    items = _complete_at_end_of(client, uri, edited, "murs =", 6,
                                context={"triggerKind": 1})
    assert not {i["label"] for i in items} & {"wall", "floor"}


def test_a_bracket_typed_elsewhere_offers_nothing(client: Client, house: Path):
    uri, text = _opened(client, house)
    edited = text + "\nx = $U["
    items = _complete_at_end_of(client, uri, edited, "x = $U[", 2,
                                context={"triggerKind": 2, "triggerCharacter": "["})
    assert items == []


def test_a_definition_over_several_lines_is_completed_on_its_last(client: Client, house: Path):
    uri, text = _opened(client, house)
    edited = text.replace("0.7, 0.7, L - E));  // [window]", "0.7, 0.7, L - E));  // [")
    items = _complete_at_end_of(client, uri, edited, "                     TROU_X(P / 2 - 0.35, "
                                "H + 0.4, 0.7, 0.7, L - E)", 2)
    assert "window" in {i["label"] for i in items}


def test_hover_shows_an_object_s_class(client: Client, house: Path):
    uri, text = _opened(client, house)
    shown = client.at("textDocument/hover", uri, line_of(text, "porte_trou ="), 2)
    value = shown["contents"]["value"]
    assert "class: door (IfcDoor)" in value
    assert "settings: hinge=left, swing=in" in value
    assert "description: the front door" in value
    value = client.at("textDocument/hover", uri, line_of(text, "socle ="), 2)["contents"]["value"]
    assert "class: slab (IfcSlab)" in value and "predefined type: baseslab" in value
    # where the object is used, too
    line = line_of(text, "maison =") + 2
    column = text.split("\n")[line].index("toit") + 1
    value = client.at("textDocument/hover", uri, line, column)["contents"]["value"]
    assert value.startswith("object toit") and "class: roof (IfcRoof)" in value
    assert "predefined type: gable_roof" in value
    # an unclassed object says nothing of a class
    value = client.at("textDocument/hover", uri, line_of(text, "battant ="), 2)["contents"]["value"]
    assert "class" not in value
    # the class's name in the annotation: what the class is
    line = line_of(text, "porte_trou =")
    column = text.split("\n")[line].index("[door") + 2
    value = client.at("textDocument/hover", uri, line, column)["contents"]["value"]
    assert value.startswith("IfcDoor (door)") and "hinge=left|right (default left)" in value
    column = text.split("\n")[line].index("hinge=") + 2
    value = client.at("textDocument/hover", uri, line, column)["contents"]["value"]
    assert value == "door's hinge: left|right (default left)"
    # a word of the description names nothing
    column = text.split("\n")[line].index("front door") + 2
    assert client.at("textDocument/hover", uri, line, column) is None


def test_the_outline_gives_each_object_its_class(client: Client, house: Path):
    uri, _ = _opened(client, house)
    found = client.request("textDocument/documentSymbol", {"textDocument": {"uri": uri}})["result"]
    detail = {s["name"]: s["detail"] for s in found}
    assert detail["murs"] == "wall"
    assert detail["toit"] == "roof gable_roof"
    assert detail["socle"] == "slab baseslab"
    assert detail["porte_trou"] == "door (hinge=left, swing=in)"
    assert detail["battant"] == "object" and detail["maison"] == "object"
    assert detail["L"] == "= 9"


def test_a_misspelt_class_is_a_warning_as_it_is_typed(client: Client, house: Path):
    uri, text = _opened(client, house)
    edited = text.replace("// [wall] the four walls", "// [wal] the four walls")
    client.change(uri, edited, 2)
    found = client.diagnostics(uri, 2)
    line = line_of(edited, "murs =")
    warnings = [d for d in found if d["range"]["start"]["line"] == line]
    assert len(warnings) == 1, found
    warning = warnings[0]
    assert warning["severity"] == 2  # a warning, never an error
    assert "unknown class 'wal'" in warning["message"]
    assert "did you mean wall" in warning["message"]
    start = edited.split("\n")[line].index("[wal]")
    assert warning["range"]["start"]["character"] == start
    assert warning["range"]["end"]["character"] == start + len("[wal]")
    # the object is then unclassed: hover and outline say so
    value = client.at("textDocument/hover", uri, line, 2)["contents"]["value"]
    assert "unclassed: annotation: unknown class 'wal'" in value
    symbols = client.request("textDocument/documentSymbol",
                             {"textDocument": {"uri": uri}})["result"]
    assert next(s for s in symbols if s["name"] == "murs")["detail"] == "object"
    # an unknown setting too; then mended, the warnings go
    edited = text.replace("[door hinge=left swing=in]", "[door hindge=left swing=in]")
    client.change(uri, edited, 3)
    found = client.diagnostics(uri, 3)
    assert [d["message"] for d in found] == [
        "annotation: unknown setting 'hindge' of door (did you mean hinge?); door has hinge, "
        "swing; the object is unclassed"]
    client.change(uri, text, 4)
    assert client.diagnostics(uri, 4) == []


def test_a_room_s_name_and_a_storey_in_hover_and_outline():
    """castor.analysis as the server reads it (no server needed): a space's long
    name, and a storey parameter's annotation explained."""
    from castor.analysis import knowledge
    from castor.analysis.scene import analyse
    from castor.settings import Source

    text = (EXAMPLES / "pavilion.cas").read_text()
    analysis = analyse(Source(text=text, name="pavilion.cas"))
    assert [d for d in analysis.diagnostics if d.kind == "error"] == []
    line = line_of(text, "sejour =") + 1
    shown, _ = knowledge.hover(analysis, "pavilion.cas", line, 2, figures=lambda *_: None)
    assert "class: space (IfcSpace)" in shown and "long name: Séjour" in shown
    detail = {s.name: s.detail for s in knowledge.symbols(analysis, "pavilion.cas")}
    assert detail["sejour"] == 'space ("Séjour")'
    line = line_of(text, "R1 =") + 1
    column = text.split("\n")[line - 1].index("storey") + 2
    shown, _ = knowledge.hover(analysis, "pavilion.cas", line, column)
    assert shown == "a storey: the parameter's value is its floor level"

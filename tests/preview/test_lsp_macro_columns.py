"""castor --lsp puts an annotation's warning where ``castor --check`` does, on
the line as written, when a macro is used earlier on that line: the column is
mapped out of the macro's expansion against the buffer's text (not the file on
disk, which the buffer may not match), after didOpen and after didChange."""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.support.lsp import Client, started_client

SHED = ("#define BOIS 0.5, 0.35, 0.2\n"
        "H = 2.5;\n"
        "W = 3;\n"
        "roof = @t(-0.2, -0.2, H) @h(W + 0.6, 0.6, 0.2) !cu(BOIS);  // [rof flat_roof] the roof\n"
        "> roof;\n")
ROOF_LINE = 3
ROOF_BRACKET = SHED.split("\n")[ROOF_LINE].index("[")  # 62, as --check's 4:63


@pytest.fixture
def workspace(tmp_path: Path) -> Path:
    (tmp_path / "shed.cas").write_text(SHED)
    (tmp_path / "draft.cas").write_text("> nothing;\n")  # the buffer is not this
    return tmp_path


@pytest.fixture
def client(workspace: Path):
    yield from started_client(workspace)


def _annotation_ranges(diagnostics: list) -> list:
    return [(d["range"], d["message"].split(";")[0]) for d in diagnostics
            if d["message"].startswith("annotation:")]


def _at(line: int, start: int, end: int) -> dict:
    return {"start": {"line": line, "character": start}, "end": {"line": line, "character": end}}


def test_the_annotation_warning_is_at_its_bracket_after_a_macro(client: Client,
                                                                 workspace: Path):
    assert ROOF_BRACKET == 62
    uri = client.open(workspace / "shed.cas")
    found = _annotation_ranges(client.diagnostics(uri, 1))
    # from the '[' to the ']' of "[rof flat_roof]"
    assert found == [(_at(ROOF_LINE, 62, 77), "annotation: unknown class 'rof' (did you mean roof?)")]
    # the annotation edited, not saved: the file on disk still says [rof
    client.change(uri, SHED.replace("[rof ", "[roff "), 2)
    found = _annotation_ranges(client.diagnostics(uri, 2))
    assert found == [(_at(ROOF_LINE, 62, 78), "annotation: unknown class 'roff' (did you mean roof?)")]


def test_an_unsaved_buffer_s_annotation_after_a_macro(client: Client, workspace: Path):
    text = "#define C 0.5, 0.35, 0.2\nx = !cu(C);  // [wal] w\n> x;\n"
    assert text.split("\n")[1].index("[") == 16  # --check says 2:17
    uri = client.open(workspace / "draft.cas", text)
    found = _annotation_ranges(client.diagnostics(uri, 1))
    assert found == [(_at(1, 16, 21), "annotation: unknown class 'wal' (did you mean wall?)")]
    client.change(uri, text.replace("[wal]", "[wale]"), 2)
    found = _annotation_ranges(client.diagnostics(uri, 2))
    assert found == [(_at(1, 16, 22), "annotation: unknown class 'wale' (did you mean wall?)")]

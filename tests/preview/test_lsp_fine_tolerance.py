"""The language server shows the warning of a curved primitive faceted so
finely that its booleans will be slow at the primitive as written, and again
after each edit that keeps it (each analysis is a run of its own;
tests/cli/test_fine_tolerance_warning.py has the words)."""

from pathlib import Path

import pytest

from tests.support.lsp import Client, started_client

WHEEL = ("TOLERANCE = 1e-8;\nroue = @h(0.35, 0.35, 0.25) !cy(0.5, 0.5, 0.5);\n"
         "> $U(!cu(1, 1, 1), @t(0.5, 0, 0.5) @rx(90) roue);\n")

SLOW = ("'!cy' gets 14,033 segments around at tolerance 1e-08: a boolean with it may take "
        "several seconds (the time grows as the square of the segments); a coarser -t (such "
        "as 1e-05) is still finer than a printer or a screen shows")


@pytest.fixture
def client(tmp_path: Path):
    yield from started_client(tmp_path)


def test_the_editor_is_told_at_the_primitive_after_each_edit(client: Client, tmp_path: Path):
    uri = client.open(tmp_path / "wheel.cas", WHEEL)
    said = [(d["message"], d["severity"], d["range"]["start"]) for d in client.diagnostics(uri, 1)]
    assert said == [(SLOW, 2, {"line": 1, "character": 28})]
    client.change(uri, WHEEL + "> roue;\n", 2)
    assert [(d["message"], d["range"]["start"]) for d in client.diagnostics(uri, 2)] == \
        [(SLOW, {"line": 1, "character": 28})]
    client.change(uri, WHEEL.replace("1e-8", "1e-6"), 3)
    assert client.diagnostics(uri, 3) == []

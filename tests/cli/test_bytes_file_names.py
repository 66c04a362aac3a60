"""A scene file whose name is not UTF-8 (Linux allows any bytes): messages show
the byte as '<0xe9>', as the command line's bad bytes are, and every output is
written, its titles and descriptions valid text (the IFC and the SVG failed with
"an internal error", messages showed 'caf\\udce9.cas')."""

from __future__ import annotations

import os

import pytest

from tests.support.cli import run

pytest.importorskip("ifcopenshell")

SCENE = b"""\
porte = @t(1, -0.1, 0) @h(0.9, 0.5, 2.1) !cu(0.2, 0.3, 0.8);  // [door]
mur = $D(@h(4, 0.3, 2.5) !cu(0.9, 0.9, 0.8), porte);  // [wall]
> mur;
"""


def _scene(folder, text: bytes = SCENE) -> str:
    path = os.path.join(os.fsencode(folder), b"caf\xe9.cas")
    with open(path, "wb") as f:
        f.write(text)
    return os.fsdecode(path)


@pytest.mark.parametrize("suffix", ["ifc", "svg", "obj"])
def test_every_output_is_written(tmp_path, suffix):
    scene = _scene(tmp_path)
    out = tmp_path / f"x.{suffix}"
    status, _, err = run("-o", str(out), scene)
    assert (status, err) == (0, "")
    text = out.read_bytes().decode("utf-8")
    if suffix != "obj":
        assert "caf<0xe9>.cas" in text.replace("&lt;", "<").replace("&gt;", ">")


def test_messages_show_the_byte(tmp_path):
    scene = _scene(tmp_path, SCENE + b"x = ;\n")
    status, _, err = run("--check", scene)
    assert status == 1
    assert err.startswith(f"{tmp_path}/caf<0xe9>.cas:4:5: error: expected an object"), err
    status, _, err = run("--check", os.fsdecode(os.fsencode(str(tmp_path)) + b"/no\xe9.cas"))
    assert (status, err) == (2, f"castor: error: cannot read '{tmp_path}/no<0xe9>.cas': "
                                "no such file\n")

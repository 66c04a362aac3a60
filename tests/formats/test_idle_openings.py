"""A door or window that cuts nothing from the wall it is subtracted from (moved
off it) is said once, in the same words, by the take-off (--summary), the IFC
and --check (told from boxes), instead of leaving the take-off silently."""

from __future__ import annotations

import json

import pytest

from tests.support.cli import run, write

NODOOR = """\
R0 = 0;
porte = @t(2, {y}, 0) @h(0.9, 0.5, 2.1) !cu(0, 0, 1);  // [door]
murs = $D(@h(6, 0.3, 2.5) !cu(1, 1, 1), porte);  // [wall]
> murs;
"""


def _said(path) -> str:
    return (f"{path}:4:1: warning: door 'porte' ({path}:2) cuts nothing from the element "
            "it is subtracted from: it is left out of the take-off and the IFC "
            "(no opening, no element)\n")


@pytest.mark.parametrize("args", [["--check"], ["--summary", "{out}.json", "-o", "{out}.stl"],
                                  ["-o", "{out}.ifc"],
                                  ["-o", "{out}.ifc", "--summary", "{out}.json"]])
def test_a_door_off_its_wall_is_said_once(tmp_path, args):
    scene = write(tmp_path, "nodoor.cas", NODOOR.format(y=2))
    out = str(tmp_path / "nd")
    status, _, err = run(*[a.format(out=out) for a in args], str(scene))
    assert status == 0
    assert err.count("warning:") == 1 and _said(scene) in err, err
    if "--summary" in args:
        frame = json.loads((tmp_path / "nd.json").read_text())["frames"][0]
        assert frame["openings"] == []
        assert [c["class"] for c in frame["classes"]] == ["IfcWall"]


def test_a_door_through_its_wall_is_not_said(tmp_path):
    scene = write(tmp_path, "door.cas", NODOOR.format(y=-0.1))
    out = tmp_path / "d"
    for args in (["--check"], ["-o", f"{out}.ifc", "--summary", f"{out}.json"]):
        status, _, err = run(*args, str(scene))
        assert (status, err) == (0, "")
    frame = json.loads((tmp_path / "d.json").read_text())["frames"][0]
    assert [o["name"] for o in frame["openings"]] == ["porte"]

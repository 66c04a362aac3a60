"""The take-off (--summary) is the same whatever the output: a picture, a
drawing, a file of triangles (OUTPUT.md, Quantities)."""

import json

import pytest

from tests.support.cli import run

SCENE = "> !cu(1, 1, 1);\n>[T = 0, 1] @t(T, 0, 0) @h(2, 1, 1) !cu(1, 0, 0);\n"


def _summary(tmp_path, output):
    (tmp_path / "s.cas").write_text(SCENE)
    status, out, err = run("--summary", "s.json", "--size", "40x30", "--samples", "1",
                           "-o", output, "s.cas", cwd=tmp_path)
    assert status == 0, err
    return json.loads((tmp_path / "s.json").read_text())


@pytest.mark.parametrize("output", ["x-%d.png", "x.gif", "x-%d.svg", "x-%d.glb", "x-%d.stl",
                                    "x-%d.3mf"])
def test_the_take_off_is_the_streams_whatever_the_output(tmp_path, output):
    expected = _summary(tmp_path, "x.cps")
    assert [f["number"] for f in expected["frames"]] == [1, 2, 3]
    assert expected["frames"][0]["objects"][0]["polygons"] == 6  # a cube: six squares
    assert _summary(tmp_path, output) == expected

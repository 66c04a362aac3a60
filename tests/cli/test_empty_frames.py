"""An empty frame is warned about whatever the output: the stream, a mesh file,
a drawing, a picture (a blank picture says why)."""

import pytest

from tests.support.cli import run

EMPTY = "> $I(!cu(1, 0, 0), @t(5, 0, 0) !cu(1, 0, 0));\n> $D(!cu(1, 0, 0), !cu(1, 0, 0));\n"
FULL = "> !cu(1, 0, 0);\n> @h(0.01, 0.01, 0.01) !sp(1, 0, 0);\n"


@pytest.mark.parametrize("output", ["x.cps", "x-%d.glb", "x-%d.svg", "x-%d.png", "x.gif"])
def test_an_empty_frame_is_warned_about(tmp_path, output):
    (tmp_path / "e.cas").write_text(EMPTY)
    status, out, err = run("--size", "40x30", "--samples", "1", "-o", output, "e.cas",
                           cwd=tmp_path)
    assert status == 0, err
    assert "e.cas:1:1: warning: frame 1 is empty" in err
    assert "e.cas:2:1: warning: frame 2 is empty" in err


def test_a_small_object_is_no_empty_frame(tmp_path):
    (tmp_path / "f.cas").write_text(FULL)
    status, out, err = run("--size", "40x30", "--samples", "1", "-o", "x-%d.png", "f.cas",
                           cwd=tmp_path)
    assert status == 0 and err == "", err

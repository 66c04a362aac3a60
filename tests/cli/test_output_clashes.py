"""An output that is another file of the same run (issue 29's trial): '--summary
x.glb -o x.glb' wrote the JSON figures over the mesh, exit 0, without a word. As
for a scene file castor reads, it is a usage error (exit 2), whatever path or
link names the same file, and for any file of an -o pattern; nothing is written."""

import os

import pytest

from tests.support.cli import run

SCENE = "a = !cu(1, 1, 1);\n> a;\n> @t(2, 0, 0) a;\n"


def _scene(tmp_path):
    (tmp_path / "two.cas").write_text(SCENE)
    return sorted(os.listdir(tmp_path))


@pytest.mark.parametrize("summary, output, shown", [
    ("x.glb", "x.glb", "--summary x.glb: is where -o x.glb writes the frames; give the figures "
                       "a file of their own (--summary x.json)"),
    ("./sub/../x.glb", "x.glb", "--summary ./sub/../x.glb: is where -o x.glb writes"),
    ("x-002.glb", "x-%03d.glb", "--summary x-002.glb: is where -o x-%03d.glb writes"),
    ("50%-7.glb", "50%%-%d.glb", "--summary 50%-7.glb: is where -o 50%%-%d.glb writes"),
])
def test_the_summary_and_the_frames_in_one_file_is_a_usage_error(tmp_path, summary, output,
                                                                  shown):
    (tmp_path / "sub").mkdir()
    before = _scene(tmp_path)
    status, out, err = run("--summary", summary, "-o", output, "two.cas", cwd=tmp_path)
    assert status == 2
    assert err.startswith(f"castor: error: {shown}")
    assert sorted(os.listdir(tmp_path)) == before


def test_a_link_to_the_output_is_the_output(tmp_path):
    before = _scene(tmp_path)
    (tmp_path / "x.glb").write_bytes(b"old mesh")
    (tmp_path / "y.json").symlink_to("x.glb")
    status, out, err = run("--summary", "y.json", "-o", "x.glb", "two.cas", cwd=tmp_path)
    assert status == 2 and "--summary y.json: is where -o x.glb writes the frames" in err
    assert (tmp_path / "x.glb").read_bytes() == b"old mesh"
    assert sorted(os.listdir(tmp_path)) == sorted(before + ["x.glb", "y.json"])


def test_the_parameter_file_is_no_output(tmp_path):
    _scene(tmp_path)
    (tmp_path / "p.json").write_text('{"parameterSets": {"a": {}}, "fileFormatVersion": "1"}')
    status, out, err = run("--summary", "p.json", "-p", "p.json", "-P", "a", "-o", "/dev/null",
                           "two.cas", cwd=tmp_path)
    assert status == 2
    assert err.startswith("castor: error: --summary p.json: is the parameter file castor reads "
                          "(-p); give the output another name")
    assert '"a"' in (tmp_path / "p.json").read_text()


def test_a_scene_among_the_pattern_s_files_is_a_usage_error(tmp_path):
    (tmp_path / "x-1.cas").write_text(SCENE)
    status, out, err = run("-f", "stl", "-o", "x-%d.cas", "x-1.cas", cwd=tmp_path)
    assert status == 2 and "-o x-%d.cas: is a scene castor reads" in err
    assert (tmp_path / "x-1.cas").read_text() == SCENE


def test_different_files_and_devices_are_still_written(tmp_path):
    _scene(tmp_path)
    status, out, err = run("--summary", "x.json", "-o", "x-%d.glb", "two.cas", cwd=tmp_path)
    assert status == 0, err
    assert sorted(os.listdir(tmp_path)) == ["two.cas", "x-1.glb", "x-2.glb", "x.json"]
    status, out, err = run("--summary", "/dev/null", "-o", "/dev/null", "two.cas", cwd=tmp_path)
    assert status == 0, err


def test_the_register_is_no_output_and_a_set_is_still_written(tmp_path):
    # the register is read before the outputs are checked: its path, not the
    # register read from it, is what an output may not be (an internal error once)
    (tmp_path / "two.cas").write_text("a = !cu(1, 1, 1);\n> a;\n")  # one frame
    (tmp_path / "set.toml").write_text('[project]\ntitle = "T"\nscale = "1:50"\n\n'
                                       '[[sheet]]\nnumber = "A-1"\ndrawing = "plan z=0.5"\n')
    status, _, err = run("--sheets", "set.toml", "-f", "pdf", "-o", "set.toml", "two.cas",
                         cwd=tmp_path)
    assert status == 2 and err.startswith(
        "castor: error: -o set.toml: is the drawing register castor reads (--sheets)"), err
    status, _, err = run("--sheets", "set.toml", "-o", "set.pdf", "two.cas", cwd=tmp_path)
    assert status == 0, err
    assert (tmp_path / "set.pdf").read_bytes().startswith(b"%PDF")

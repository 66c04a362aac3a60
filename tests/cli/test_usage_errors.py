"""A usage error is one line first, `castor: error: WHAT, and what to write
instead`, then at most a one-line hint, never the usage text (CLI.md)."""

import pytest

from tests.support.cli import run

CUBE = "> !cu(1, 1, 1);\n"


@pytest.mark.parametrize("args, what", [
    (["-o", "nodir/x.glb"], "cannot write 'nodir/x.glb': the directory 'nodir' does not exist"),
    (["--set", "H=abc"], "--set H=abc: 'abc' is neither a number nor a parameter"),
    (["-o", "x.xyz"], "cannot tell the format of 'x.xyz' from its extension"),
    (["--frob"], "unrecognized arguments: --frob"),
    (["--sumary", "q.json"], "unrecognized arguments: --sumary (did you mean --summary?)"),
    (["-f", "dwg"], "invalid choice: 'dwg'"),
    (["--jobs", "x"], "--jobs"),
], ids=["missing-directory", "set-value", "extension", "unknown-option", "misspelt-option",
        "format", "jobs"])
def test_the_error_comes_first_and_alone(tmp_path, args, what):
    status, out, err = run(*args, "-", stdin=CUBE, cwd=tmp_path)
    assert status == 2 and out == ""
    lines = err.splitlines()
    assert lines[0].startswith("castor: error: ") and what in lines[0], err
    assert lines[1:] == ["try 'castor --help'"], err
    assert "usage:" not in err
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("args", [["--summary", "house.cas"], ["-f", "off", "-o", "./house.cas"]],
                         ids=["summary", "output"])
def test_an_output_never_writes_over_the_scene_it_reads(tmp_path, args):
    """`castor --summary house.cas house.cas` wrote the take-off over the scene
    and exited 0; an output named as a scene file is a usage error, and the
    scene is left as it was."""
    scene = tmp_path / "house.cas"
    scene.write_text(CUBE)
    status, out, err = run(*args, "house.cas", cwd=tmp_path)
    assert status == 2 and out == ""
    assert err.splitlines()[0] == (f"castor: error: {args[-2]} {args[-1]}: is a scene castor reads; "
                                   f"give the output another name"), err
    assert scene.read_text() == CUBE
    assert sorted(p.name for p in tmp_path.iterdir()) == ["house.cas"]

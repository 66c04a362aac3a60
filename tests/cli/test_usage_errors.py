"""A usage error is one line first, `castor: error: WHAT, and what to write
instead`, then at most a one-line hint, never the usage text (CLI.md)."""

import pytest

from meshcheck import run

CUBE = "> !cu(1, 1, 1);\n"


@pytest.mark.parametrize("args, what", [
    (["-o", "nodir/x.glb"], "cannot write 'nodir/x.glb': the directory 'nodir' does not exist"),
    (["--set", "H=abc"], "--set H=abc: 'abc' is not a parameter"),
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

"""An input that cannot be read, or that holds no '>' command, writes nothing on
standard output; an unreadable file is a usage error (exit 2) for castor and
castor-view alike, in their own words."""

import subprocess
import sys

import pytest

from tests.support.cli import run


@pytest.mark.parametrize("path, reason", [("/etc", "it is a directory"),
                                          ("nofile.cas", "no such file")])
def test_castor_writes_nothing_for_an_unreadable_input(tmp_path, path, reason):
    status, out, err = run(path, cwd=tmp_path)
    assert (status, out) == (2, "")
    assert err == f"castor: error: cannot read '{path}': {reason}\n"


def test_castor_writes_nothing_for_an_input_with_no_frame(tmp_path):
    status, out, err = run("/dev/null", cwd=tmp_path)
    assert (status, out) == (0, "")
    assert "the scene has no '>' command, so nothing was written" in err


def test_frames_that_all_fail_still_make_a_stream(tmp_path):
    status, out, err = run("--no-cpp", stdin="> @h(0, 1, 1) !cu(1, 0, 0);\n", cwd=tmp_path)
    assert (status, out) == (1, "castor-polygons 1\n")


@pytest.mark.parametrize("path, reason", [("nofile.off", "no such file"),
                                          ("/etc", "it is a directory")])
def test_castor_view_says_so_as_castor_does(tmp_path, path, reason):
    result = subprocess.run([sys.executable, "-m", "castor.view.cli", "-o", "x.png", path],
                            capture_output=True, text=True, cwd=tmp_path, timeout=60)
    assert result.returncode == 2
    assert result.stderr == f"castor-view: error: cannot read '{path}': {reason}\n"
    assert list(tmp_path.iterdir()) == []

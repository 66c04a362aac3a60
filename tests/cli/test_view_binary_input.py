r"""castor-view on a file that is not text (issue 29's trial): its message showed
the first line as it came, replacement characters and control characters on the
terminal. The text shown is escaped (a byte that is not UTF-8 as \xcd, as
castor says it), printable ASCII, short."""

import subprocess
import sys

import pytest

from tests.support.cli import OUTSIDE

GARBAGE = bytes([0xcd, 0x55, 0x8f, 0x01, 0x1b, 0x5b, 0x32, 0x4a, 0x5c, 0xff]) * 30


def _view(*args, stdin=None, cwd=None):
    return subprocess.run([sys.executable, "-m", "castor.view.cli", "-o", "v.png", *args],
                          input=stdin, capture_output=True, cwd=cwd or OUTSIDE, timeout=120)


@pytest.mark.parametrize("from_file", [True, False])
def test_binary_input_is_shown_escaped(tmp_path, from_file):
    (tmp_path / "garbage.cas").write_bytes(GARBAGE)
    result = (_view("garbage.cas", cwd=tmp_path) if from_file
              else _view(stdin=GARBAGE, cwd=tmp_path))
    name = "garbage.cas" if from_file else "<stdin>"
    err = result.stderr.decode("ascii")  # nothing but ASCII
    assert result.returncode == 1
    assert err == (f"castor-view: error: {name}:1: not a castor polygon stream (first line is "
                   "'\\xcdU\\x8f\\x01\\x1b[2J\\\\\\xff\\xcdU\\x8f\\x01\\x1b...'); give a mesh file, or "
                   "pipe castor's output\n")
    assert all(" " <= c <= "~" for c in err.rstrip("\n"))


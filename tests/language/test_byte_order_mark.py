"""A UTF-8 byte-order mark at the start of a scene file is skipped.

Editors on Windows save UTF-8 with EF BB BF in front: castor said
``bom.cas:1:1: error: unexpected character U+FEFF`` and then that every
parameter of the first statement was undefined, while ``cpp bom.cas | castor``
worked (GNU cpp skips the mark). It is skipped now, in files and on standard
input, with and without the preprocessor, in included files too, and the
columns of line 1 are those the user sees (vi shows no column for the mark).
"""

import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
BOM = b"\xef\xbb\xbf"
SCENE = b"L = 8;\nmurs = @h(L, 5, 3) !cu(1, 1, 1);\n> murs;\n"


def castor(cwd, *args, stdin: bytes | None = None):
    done = subprocess.run([sys.executable, "-m", "castor", *args], cwd=cwd, input=stdin,
                          capture_output=True, timeout=120,
                          env={"PYTHONPATH": str(REPO), "PATH": "/usr/bin:/bin"})
    return done.returncode, done.stdout, done.stderr.decode()


@pytest.mark.parametrize("how", [(), ("--no-cpp",)])
def test_a_file_that_starts_with_a_byte_order_mark_reads_as_without(tmp_path, how):
    (tmp_path / "bom.cas").write_bytes(BOM + SCENE)
    assert castor(tmp_path, *how, "--check", "bom.cas") == (0, b"", "")
    with_mark = castor(tmp_path, *how, "bom.cas")
    assert with_mark[0] == 0 and with_mark[2] == ""
    (tmp_path / "bom.cas").write_bytes(SCENE)
    assert with_mark == castor(tmp_path, *how, "bom.cas")


@pytest.mark.parametrize("how", [(), ("--no-cpp",)])
def test_standard_input_that_starts_with_a_byte_order_mark(tmp_path, how):
    status, out, err = castor(tmp_path, *how, "--check", stdin=BOM + SCENE)
    assert (status, out, err) == (0, b"", "")


@pytest.mark.parametrize("how", [(), ("--no-cpp",)])
def test_columns_of_line_one_do_not_count_the_mark(tmp_path, how):
    (tmp_path / "bom.cas").write_bytes(BOM + b"L = 8 + Q;\n> !cu(1, 1, 1);\n")
    status, _, err = castor(tmp_path, *how, "--check", "bom.cas")
    assert status == 1
    assert err.splitlines()[0].startswith("bom.cas:1:9: error: parameter 'Q' is not defined")
    assert err.splitlines()[1:3] == [" L = 8 + Q;", "         ^"]
    assert "U+FEFF" not in err


def test_an_included_file_with_a_byte_order_mark(tmp_path):
    (tmp_path / "part.cas").write_bytes(BOM + b"L = 8 + Q;\n")
    (tmp_path / "main.cas").write_bytes(BOM + b'#include "part.cas"\n> !cu(1, 1, 1);\n')
    status, _, err = castor(tmp_path, "--check", "main.cas")
    assert status == 1
    assert err.splitlines()[0].startswith("part.cas:1:9: error: parameter 'Q'")
    assert err.splitlines()[1:3] == [" L = 8 + Q;", "         ^"]

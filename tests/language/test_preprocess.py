"""#include names that cannot be opened are errors at their place, and the run goes on.

Issue 18, items 3 and 15: a NUL byte in a name was an internal error, a file that
is not UTF-8 text too, and a missing #include stopped the run so that the
errors after it were never seen (an external cpp reports them all).
"""

import subprocess
import sys

import pytest


def castor(tmp_path, text: bytes, *args: str, name: str = "scene.cas"):
    (tmp_path / name).write_bytes(text)
    done = subprocess.run([sys.executable, "-m", "castor", *args, name], cwd=tmp_path,
                          capture_output=True, timeout=60)
    return done.returncode, done.stdout.decode(), done.stderr.decode()


def test_nul_byte_in_include_name_is_an_error_at_its_place(tmp_path):
    status, out, err = castor(tmp_path, b'#include "a\0b.cas"\n> !cu(1, 0, 0);\n')
    assert "internal error" not in err and "Traceback" not in err, err
    assert err.startswith("scene.cas:1:10: error: "), err
    assert "NUL" in err
    assert status == 1
    assert "endframe 1 6" in out  # and the frame after it is made


def test_include_of_a_file_that_is_not_text(tmp_path):
    (tmp_path / "bin.cas").write_bytes(b"\xff\xfe\x00binary")
    status, out, err = castor(tmp_path, b'#include "bin.cas"\n> !cu(1, 0, 0);\n')
    assert "internal error" not in err, err
    assert err.startswith("scene.cas:1:10: error: cannot read include file 'bin.cas'"), err
    assert "UTF-8" in err
    assert status == 1 and "endframe 1 6" in out


def test_include_of_a_directory(tmp_path):
    (tmp_path / "walls.cas").mkdir()
    status, out, err = castor(tmp_path, b'#include "walls.cas"\n> !cu(1, 0, 0);\n')
    assert err.startswith("scene.cas:1:10: error: cannot read include file 'walls.cas'"), err
    assert "directory" in err
    assert status == 1 and "endframe 1 6" in out


@pytest.mark.parametrize("line", [b'#include <>', b'#include ""', b'#include "\x01"',
                                  b'#include "a\\"b"', b'#include <a\0b>', b'#include "/"',
                                  b'#include "' + b"x" * 5000 + b'"'])
def test_odd_include_names(tmp_path, line):
    status, out, err = castor(tmp_path, line + b"\n> !cu(1, 0, 0);\n")
    assert "internal error" not in err and "Traceback" not in err, err
    assert err.startswith("scene.cas:1:"), err
    assert " error: " in err.splitlines()[0]
    assert status == 1 and "endframe 1 6" in out


def test_missing_include_is_reported_and_the_run_goes_on(tmp_path):
    text = b'#include "missing.cas"\n> !cu(1, 0, 0);\n> @h(2) nothing;\n'
    status, out, err = castor(tmp_path, text)
    lines = [line for line in err.splitlines() if ": error: " in line]
    assert lines[0].startswith("scene.cas:1:10: error: cannot find include file 'missing.cas'")
    assert lines[1].startswith("scene.cas:3:"), err  # the error after it is reported too
    assert "nothing" in lines[1]
    assert status == 1 and "endframe 1 6" in out


def test_missing_include_inside_an_included_file(tmp_path):
    (tmp_path / "part.cas").write_text('#include "gone.cas"\nP = 1;\n')
    status, out, err = castor(tmp_path, b'#include "part.cas"\n> @h(P) !cu(1, 0, 0);\n')
    assert err.startswith("part.cas:1:10: error: cannot find include file 'gone.cas'"), err
    assert status == 1 and "endframe 1 6" in out

"""Only standard output failing is said as "cannot write to standard output";
another OSError (a file of castor's own missing) is an internal error, in one
line, never said to be standard output's."""

from __future__ import annotations

import errno
import os

from castor import cli


def test_a_full_disk_behind_standard_output(capsys, monkeypatch):
    monkeypatch.delenv("CASTOR_DEBUG", raising=False)
    assert cli._status(OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))) == 2
    assert capsys.readouterr().err == (
        "castor: error: cannot write to standard output: no space left on device\n")


def test_a_missing_file_is_not_standard_output(capsys, monkeypatch):
    monkeypatch.delenv("CASTOR_DEBUG", raising=False)
    missing = OSError(errno.ENOENT, os.strerror(errno.ENOENT), "/nowhere/castor.lark")
    assert cli._status(missing) == 1
    assert capsys.readouterr().err == (
        "castor: internal error: FileNotFoundError: [Errno 2] No such file or directory: "
        "'/nowhere/castor.lark' (please report it with the scene; CASTOR_DEBUG=1 shows where)\n")


def test_a_full_disk_writing_a_named_file_is_not_standard_output(capsys, monkeypatch):
    monkeypatch.delenv("CASTOR_DEBUG", raising=False)
    full = OSError(errno.ENOSPC, os.strerror(errno.ENOSPC), "/tmp/spool")
    assert cli._status(full) == 1
    assert "standard output" not in capsys.readouterr().err


def test_standard_output_closed(tmp_path):
    """Started with standard output closed ('>&-'): the stream is not written,
    and said so (it was a traceback); -o FILE is written as ever."""
    import subprocess
    import sys

    from tests.support.cli import OUTSIDE

    def run(*args):
        return subprocess.run([sys.executable, "-m", "castor", "--no-cpp", *args],
                              input="> !cu(1, 1, 1);\n", stderr=subprocess.PIPE, text=True,
                              timeout=120, cwd=OUTSIDE, preexec_fn=lambda: os.close(1))

    closed = run()
    assert (closed.returncode, closed.stderr) == (
        2, "castor: error: cannot write to standard output: standard output is closed\n")
    written = run("-o", str(tmp_path / "c.stl"))
    assert (written.returncode, written.stderr) == (0, "")
    assert (tmp_path / "c.stl").stat().st_size > 0

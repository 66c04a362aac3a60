"""vi's :make reads castor's messages through vim/compiler/castor.vim: errors,
warnings and the notes after them ("in expansion of macro M") are entries of
the quickfix list at their file, line and column; the source line and the
caret under it are not."""

import json
import shutil
import subprocess
from pathlib import Path

import pytest

VIM = Path(__file__).resolve().parents[2] / "vim"

MESSAGES = [
    "m.cas:2:14: error: macro M takes 1 argument, but 2 were given",
    "a = $U(M(1), M(1, 2));",
    "             ^",
    "m.cas:1:9: note: in expansion of macro M, defined at m.cas:1",
    "m.cas:3:1: warning: the value 9 is outside the slider's range 1 to 5",
    "castor: 1 error",
]


@pytest.mark.skipif(shutil.which("vim") is None, reason="needs Debian's vim")
def test_errors_warnings_and_notes_are_quickfix_entries(tmp_path):
    (tmp_path / "messages.txt").write_text("\n".join(MESSAGES) + "\n")
    out = tmp_path / "qf.json"
    script = (f"set rtp^={VIM}\ncompiler castor\n"
              f"cgetfile {tmp_path / 'messages.txt'}\n"
              "call writefile([json_encode(map(getqflist(), "
              "{_, e -> [e.lnum, e.col, e.type, e.valid, e.text]}))], "
              f"'{out}')\nqa!\n")
    (tmp_path / "run.vim").write_text(script)
    subprocess.run(["vim", "-Nu", "NONE", "-i", "NONE", "-es", "-S", str(tmp_path / "run.vim")],
                   cwd=tmp_path, timeout=60, stdin=subprocess.DEVNULL, check=False)
    entries = [e for e in json.loads(out.read_text()) if e[3]]
    assert entries == [[2, 14, "e", 1, "macro M takes 1 argument, but 2 were given"],
                       [1, 9, "n", 1, "in expansion of macro M, defined at m.cas:1"],
                       [3, 1, "w", 1, "the value 9 is outside the slider's range 1 to 5"]]

"""A gesture on the live preview reaches Vim 9 (CLI.md, "Editing on screen";
docs/editors.md): Debian's Vim, in a pseudo-terminal as a user runs it, with
castor's own small client (vim/autoload/castor/client.vim) and
``castor --lsp --serve``: the preview's address comes with window/showMessage,
a Place made on the preview's server lands in Vim's buffer with
workspace/applyEdit, unsaved, and ``u`` undoes it. Skipped where vim is missing."""

from __future__ import annotations

import json
import os
import pty
import select
import shutil
import sys
import time
import urllib.request
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
VIM = shutil.which("vim")

SCENE = "/* a slab */\ndalle = @h(4, 2, 0.2) !cu(0.7, 0.7, 0.7);\n> dalle;\n"
LINE = "bloc1 = @t(5, 0.5, 0) @h(1, 1, 1) !cu(0.8, 0.8, 0.8); > dalle, bloc1;"

SCRIPT = r"""
function! s:Wait(condition) abort
  let l:i = 0
  while l:i < 1800 && !eval(a:condition)
    sleep 50m
    let l:i += 1
  endwhile
  return eval(a:condition)
endfunction
let g:out = {}
let g:out.told = s:Wait('!empty(castor#client#messages())')
call writefile([get(castor#client#messages(), -1, 'none')], $CASTOR_URL . '.part')
call rename($CASTOR_URL . '.part', $CASTOR_URL)
let g:out.edited = s:Wait('join(getline(1, "$"), "\n") =~# "bloc1"')
" the page's request answered before Vim ends (and its server with it)
call s:Wait('filereadable($CASTOR_ANSWERED)')
let g:out.after = getline(1, '$')
let g:out.modified = &modified
normal! u
let g:out.undone = getline(1, '$')
call writefile([json_encode(g:out)], $CASTOR_RESULT . '.part')
call rename($CASTOR_RESULT . '.part', $CASTOR_RESULT)
qall!
"""


def post(url: str, body: dict) -> dict:
    request = urllib.request.Request(url + "gesture", data=json.dumps(body).encode(),
                                     headers={"Content-Type": "application/json"})
    with urllib.request.urlopen(request, timeout=60) as answer:
        return json.loads(answer.read())


class Terminal:
    """Vim in a pseudo-terminal, its screen read (and not looked at)."""

    def __init__(self, argv: list[str], cwd: Path, env: dict):
        self.pid, self.fd = pty.fork()
        if self.pid == 0:  # the child
            os.chdir(cwd)
            os.execve(argv[0], argv, env)

    def until(self, path: Path, seconds: float) -> str:
        end = time.monotonic() + seconds
        while not path.exists():
            assert time.monotonic() < end, f"{path.name} never came"
            assert not os.waitpid(self.pid, os.WNOHANG)[0], "vim ended"
            if select.select([self.fd], [], [], 0.1)[0]:
                try:
                    os.read(self.fd, 65536)
                except OSError:
                    pass
        return path.read_text().strip()

    def close(self) -> None:
        try:
            os.kill(self.pid, 9)
            os.waitpid(self.pid, 0)
        except (ProcessLookupError, ChildProcessError):
            pass
        os.close(self.fd)


@pytest.mark.skipif(VIM is None, reason="vim is not installed (Debian: apt install vim)")
def test_a_gesture_on_the_preview_lands_in_vims_buffer(tmp_path: Path):
    scene = tmp_path / "slab.cas"
    scene.write_text(SCENE)
    script = tmp_path / "test.vim"
    script.write_text(SCRIPT)
    command = [sys.executable, "-m", "castor", "--lsp", "--serve", "--port", "0"]
    init = tmp_path / "vimrc"
    init.write_text(f"set nocompatible\nlet &runtimepath = '{ROOT / 'vim'},' . &runtimepath\n"
                    f"filetype plugin on\nlet g:castor_lsp_command = {json.dumps(command)}\n")
    url_file, result = tmp_path / "url.txt", tmp_path / "result.json"
    env = {"HOME": str(tmp_path), "PATH": "/usr/bin:/bin", "TERM": "xterm", "LANG": "C.UTF-8",
           "PYTHONPATH": str(ROOT), "CASTOR_URL": str(url_file), "CASTOR_RESULT": str(result),
           "CASTOR_ANSWERED": str(tmp_path / "answered")}
    # opened by its name in the current folder, as one does: the edit names it by its path
    vim = Terminal([VIM, "-n", "-i", "NONE", "-u", str(init), "-S", str(script), scene.name],
                   tmp_path, env)
    try:
        message = vim.until(url_file, 60)
        assert message.startswith("castor: the live preview of the buffers is at http://127.0.0.1:")
        url = message.rpartition(" ")[2]
        snapped = post(url, {"command": "castor.snap", "arguments": {
            "frame": 1, "origin": [5, 0.5, 10], "direction": [0, 0, -1], "pixelSize": 0.01}})
        placed = post(url, {"command": "castor.place", "arguments": {
            "frame": 1, "primitive": "!cu", "at": snapped["result"]["point"],
            "size": [1, 1, 1], "version": snapped["version"]}})
        assert placed["written"][0]["text"] == LINE
        (tmp_path / "answered").write_text("")
        found = json.loads(vim.until(result, 120))
    finally:
        vim.close()
    assert found["told"] and found["edited"]
    assert found["after"] == SCENE.replace("> dalle;", LINE).rstrip("\n").split("\n")
    assert found["modified"] == 1  # in the buffer, unsaved
    assert found["undone"] == SCENE.rstrip("\n").split("\n")  # u undoes it
    assert scene.read_text() == SCENE

"""The steps of docs/editors.md ("Setting up Vim and Neovim"), and nothing else,
set up Debian's Vim 9 and Neovim (issue 29, item 8): run in an empty home
folder, with castor on the PATH as the README installs it, each editor gives a
*.cas file its filetype and shows the language server's diagnostics, for a
scene and for a part that a scene includes (analysed with that scene). Vim runs
in a pseudo-terminal, as a user's does (its start-up reads defaults.vim there,
not in Ex mode); Neovim headless. The steps are read from docs/editors.md: the
first ```sh block after that heading."""

from __future__ import annotations

import json
import os
import pty
import re
import select
import shutil
import subprocess
import sys
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
VIM, NVIM = shutil.which("vim"), shutil.which("nvim")

WALLS = "mur = @h(4, 0.2, 3) !cu(1, 1, 1);\nw = $U(mur, @t(1, 0, 0) murr);\n> w;\n"
WALLS_SAID = ["object 'murr' is not defined; did you mean 'mur'?",
              "object 'w' is not defined (its definition had errors)"]
SCENE = 'L = 2;\n#define ROUGE 1, 0, 0\n#include "parts/p.cas"\n> q;\n'
PART = "p = @h(L, 1, 1) !cu(ROUGE);\nq = $U(p, pp);\n"
PART_SAID = ["object 'pp' is not defined; did you mean 'p'?"]  # never L nor ROUGE


def steps() -> str:
    text = (ROOT / "docs" / "editors.md").read_text()
    section = text.split("## Setting up Vim and Neovim", 1)[1]
    return re.search(r"```sh\n(.*?)```", section, re.S).group(1)


@pytest.fixture
def home(tmp_path: Path):
    """An empty home folder after the steps, castor on the PATH, and a workspace."""
    home, bin_ = tmp_path / "home", tmp_path / "bin"
    home.mkdir()
    bin_.mkdir()
    (bin_ / "castor").write_text(f"#!/bin/sh\nPYTHONPATH={ROOT} exec {sys.executable} "
                                 f"-m castor \"$@\"\n")
    (bin_ / "castor").chmod(0o755)
    env = {"HOME": str(home), "PATH": f"{bin_}:/usr/bin:/bin", "TERM": "xterm", "LANG": "C.UTF-8"}
    run = subprocess.run(["bash", "-e", "-c", steps()], cwd=ROOT, env=env, capture_output=True,
                         text=True, timeout=60)
    assert run.returncode == 0, run.stderr
    work = tmp_path / "work"
    (work / "parts").mkdir(parents=True)
    (work / "walls.cas").write_text(WALLS)
    (work / "scene.cas").write_text(SCENE)
    (work / "parts" / "p.cas").write_text(PART)
    return env, work, tmp_path


NVIM_SCRIPT = """
local out = { filetype = vim.bo.filetype }
vim.wait(30000, function() return #vim.diagnostic.get(0) > 0 end, 50)
out.diagnostics = {}
for _, d in ipairs(vim.diagnostic.get(0)) do table.insert(out.diagnostics, d.message) end
out.clients = #vim.lsp.get_active_clients()
local f = io.open(vim.env.CASTOR_RESULT, 'w'); f:write(vim.fn.json_encode(out)); f:close()
vim.cmd('qall!')
"""

VIM_SCRIPT = """
let g:out = {'filetype': &filetype}
let s:i = 0
while s:i < 600 && empty(castor#client#diagnostics(bufnr()))
  sleep 50m
  let s:i += 1
endwhile
let g:out.diagnostics = map(castor#client#diagnostics(bufnr()), {_, d -> d.text})
let g:out.loclist = map(getloclist(0), {_, d -> d.text})
let g:out.signs = len(sign_getplaced(bufnr(), #{group: 'castor'})[0].signs)
call writefile([json_encode(g:out)], $CASTOR_RESULT)
qall!
"""


def _nvim(env, work: Path, tmp: Path, file: str) -> dict:
    script, result = tmp / "test.lua", tmp / "nvim.json"
    script.write_text(NVIM_SCRIPT)
    run = subprocess.run([NVIM, "--headless", "-n", "-i", "NONE", "-c", f"luafile {script}",
                          file], cwd=work, env=dict(env, CASTOR_RESULT=str(result)),
                         capture_output=True, timeout=90)
    assert result.exists(), run.stderr.decode()[-2000:]
    return json.loads(result.read_text())


def _vim(env, work: Path, tmp: Path, file: str) -> dict:
    script, result = tmp / "test.vim", tmp / "vim.json"
    script.write_text(VIM_SCRIPT)
    pid, terminal = pty.fork()
    if pid == 0:  # the child: Vim in a terminal, as a user starts it
        os.chdir(work)
        os.execve(VIM, [VIM, "-n", "-i", "NONE", "-S", str(script), file],
                  dict(env, CASTOR_RESULT=str(result)))
    end = time.monotonic() + 90
    try:
        while time.monotonic() < end and not os.waitpid(pid, os.WNOHANG)[0]:
            if select.select([terminal], [], [], 0.2)[0]:
                try:
                    os.read(terminal, 65536)  # the screen, not looked at
                except OSError:
                    break
    finally:
        try:
            os.kill(pid, 9)
            os.waitpid(pid, 0)
        except (ProcessLookupError, ChildProcessError):
            pass
        os.close(terminal)
    assert result.exists(), "vim wrote no result"
    return json.loads(result.read_text())


@pytest.mark.skipif(NVIM is None, reason="nvim is not installed (Debian: apt install neovim)")
def test_neovim_after_the_steps(home):
    env, work, tmp = home
    found = _nvim(env, work, tmp, "walls.cas")
    assert (found["filetype"], found["clients"], found["diagnostics"]) == \
        ("castor", 1, WALLS_SAID)
    found = _nvim(env, work, tmp, "parts/p.cas")
    assert (found["filetype"], found["diagnostics"]) == ("castor", PART_SAID)


@pytest.mark.skipif(VIM is None, reason="vim is not installed (Debian: apt install vim)")
def test_vim_after_the_steps(home):
    env, work, tmp = home
    found = _vim(env, work, tmp, "walls.cas")
    assert (found["filetype"], found["diagnostics"]) == ("castor", WALLS_SAID)
    assert found["loclist"] == WALLS_SAID and found["signs"] == 2
    found = _vim(env, work, tmp, "parts/p.cas")
    assert (found["filetype"], found["diagnostics"]) == ("castor", PART_SAID)

"""A gesture on the live preview reaches a real editor (CLI.md, "Editing on
screen"): Debian's Neovim (0.7), headless, runs ``castor --lsp --serve``
through the project's vim/ files as a user's Neovim does; the preview's
address comes to it with window/showMessage; a Place made on the preview's
server lands in Neovim's buffer with workspace/applyEdit, unsaved, and ``u``
undoes it. Skipped, with the reason, where nvim is missing."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
NVIM = shutil.which("nvim")

SCENE = "/* a slab */\ndalle = @h(4, 2, 0.2) !cu(0.7, 0.7, 0.7);\n> dalle;\n"

SCRIPT = r"""
local out = {}
local function save(name, value)  -- whole or not at all: written beside, then renamed
  local handle = io.open(name .. '.part', 'w')
  handle:write(value)
  handle:close()
  os.rename(name .. '.part', name)
end
local shown = vim.lsp.handlers['window/showMessage']
vim.lsp.handlers['window/showMessage'] = function(err, result, ctx, config)
  out.message = result.message
  return shown(err, result, ctx, config)
end
vim.cmd('edit ' .. vim.fn.fnameescape(vim.env.CASTOR_SCENE))
local ok = vim.wait(30000, function()
  return out.message ~= nil and #vim.lsp.buf_get_clients(0) > 0
end, 20)
out.attached = ok
-- the preview's address, for the test to make its gesture on
save(vim.env.CASTOR_URL, out.message or 'none')
out.edited = vim.wait(90000, function()
  return table.concat(vim.api.nvim_buf_get_lines(0, 0, -1, false), '\n'):find('bloc1') ~= nil
end, 20)
out.after = vim.api.nvim_buf_get_lines(0, 0, -1, false)
out.modified = vim.bo.modified
vim.cmd('normal! u')
out.undone = vim.api.nvim_buf_get_lines(0, 0, -1, false)
save(vim.env.CASTOR_RESULT, vim.fn.json_encode(out))
vim.lsp.stop_client(vim.lsp.get_active_clients())
vim.cmd('qall!')
"""


def post(url: str, body: dict) -> dict:
    request = urllib.request.Request(url + "gesture", data=json.dumps(body).encode(),
                                     headers={"Content-Type": "application/json"})
    with urllib.request.urlopen(request, timeout=60) as answer:
        return json.loads(answer.read())


def appears(path: Path, process: subprocess.Popen, seconds: float = 60) -> str:
    """The file's text once Neovim has written it (or a failure if Neovim ends
    first, or after ``seconds``)."""
    end = time.monotonic() + seconds
    while not path.exists():
        assert process.poll() is None, process.stderr.read().decode()[-2000:]
        assert time.monotonic() < end, f"{path.name} never came"
        time.sleep(0.05)
    return path.read_text()


@pytest.mark.skipif(NVIM is None, reason="nvim is not installed (Debian: apt install neovim)")
def test_a_gesture_on_the_preview_lands_in_neovims_buffer(tmp_path: Path):
    scene = tmp_path / "slab.cas"
    scene.write_text(SCENE)
    script = tmp_path / "test.lua"
    script.write_text(SCRIPT)
    init = tmp_path / "init.vim"
    command = [sys.executable, "-m", "castor", "--lsp", "--serve", "--port", "0"]
    init.write_text(f"set nocompatible\nlet &runtimepath = '{ROOT / 'vim'},' . &runtimepath\n"
                    f"filetype plugin on\nlet g:castor_lsp_command = {json.dumps(command)}\n")
    url_file, result = tmp_path / "url.txt", tmp_path / "result.json"
    env = dict(os.environ, PYTHONPATH=str(ROOT), CASTOR_SCENE=str(scene),
               CASTOR_URL=str(url_file), CASTOR_RESULT=str(result),
               XDG_STATE_HOME=str(tmp_path), XDG_DATA_HOME=str(tmp_path),
               XDG_CONFIG_HOME=str(tmp_path))
    nvim = subprocess.Popen([NVIM, "--headless", "-n", "-i", "NONE", "-u", str(init),
                             "-c", f"luafile {script}"], cwd=tmp_path, env=env,
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    try:
        message = appears(url_file, nvim)
        assert message.startswith("castor: the live preview of the buffers is at http://127.0.0.1:")
        url = message.rpartition(" ")[2]
        snapped = post(url, {"command": "castor.snap", "arguments": {
            "frame": 1, "origin": [5, 0.5, 10], "direction": [0, 0, -1], "pixelSize": 0.01}})
        placed = post(url, {"command": "castor.place", "arguments": {
            "frame": 1, "primitive": "!cu", "at": snapped["result"]["point"],
            "size": [1, 1, 1], "version": snapped["version"]}})
        line = "bloc1 = @t(5, 0.5, 0) @h(1, 1, 1) !cu(0.8, 0.8, 0.8); > dalle, bloc1;"
        assert placed["written"][0]["text"] == line
        found = json.loads(appears(result, nvim, 120))
        nvim.wait(30)
    finally:
        if nvim.poll() is None:
            nvim.kill()
            nvim.wait()
    assert found["attached"] and found["edited"]
    assert found["after"] == SCENE.replace("> dalle;", line).rstrip("\n").split("\n")
    assert found["modified"] is True  # in the buffer, unsaved
    assert found["undone"] == SCENE.rstrip("\n").split("\n")  # u undoes it
    assert scene.read_text() == SCENE

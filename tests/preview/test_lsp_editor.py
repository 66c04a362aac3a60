"""castor --lsp end to end in a real editor: Debian's Neovim (0.7) with its
built-in client, started by the project's vim/ files exactly as a user's
Neovim would start it, headless. Skipped, with the reason, where nvim is
missing."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
NVIM = shutil.which("nvim")

SCRIPT = r"""
local out = {}
local function save()
  local handle = io.open(vim.env.CASTOR_RESULT, 'w')
  handle:write(vim.fn.json_encode(out))
  handle:close()
end
vim.cmd('edit ' .. vim.fn.fnameescape(vim.env.CASTOR_SCENE))
out.filetype = vim.bo.filetype
local ok = vim.wait(20000, function() return #vim.diagnostic.get(0) > 0 end, 50)
out.diagnostics = {}
for _, d in ipairs(vim.diagnostic.get(0)) do
  table.insert(out.diagnostics, { line = d.lnum, col = d.col, message = d.message,
                                  severity = d.severity })
end
local function request(method, line, character)
  local params = { textDocument = vim.lsp.util.make_text_document_params(),
                   position = { line = line, character = character } }
  local answers = vim.lsp.buf_request_sync(0, method, params, 10000) or {}
  for _, answer in pairs(answers) do
    if answer.result then return answer.result end
  end
  return vim.NIL
end
out.hover = request('textDocument/hover', 0, 0)
out.definition = request('textDocument/definition', 2, 8)
-- an edit, unsaved: the error goes away
vim.api.nvim_buf_set_lines(0, 2, 3, false, { 'w = $U(mur, @t(1, 0, 0) mur);' })
vim.wait(20000, function() return #vim.diagnostic.get(0) == 0 end, 50)
out.after_edit = #vim.diagnostic.get(0)
out.clients = #vim.lsp.get_active_clients()
save()
vim.lsp.stop_client(vim.lsp.get_active_clients())
vim.cmd('qall!')
"""


@pytest.mark.skipif(NVIM is None, reason="nvim is not installed (Debian: apt install neovim)")
def test_neovim_client_shows_diagnostics_hover_and_definition(tmp_path: Path):
    scene = tmp_path / "walls.cas"
    scene.write_text("H = 2.9;  // [2.5:0.1:4] height of the walls\n"
                     "mur = @h(4, 0.2, H) !cu(1, 1, 1);\n"
                     "w = $U(mur, @t(1, 0, 0) murr);\n"
                     "> w;\n")
    script = tmp_path / "test.lua"
    script.write_text(SCRIPT)
    result = tmp_path / "result.json"
    init = tmp_path / "init.vim"
    # the user's setup: the project's vim/ folder on the runtime path
    init.write_text(f"set nocompatible\nlet &runtimepath = '{ROOT / 'vim'},' . &runtimepath\n"
                    f"filetype plugin on\nlet g:castor_lsp_command = "
                    f"{json.dumps([sys.executable, '-m', 'castor', '--lsp'])}\n")
    env = dict(os.environ, PYTHONPATH=str(ROOT), CASTOR_SCENE=str(scene),
               CASTOR_RESULT=str(result), XDG_STATE_HOME=str(tmp_path),
               XDG_DATA_HOME=str(tmp_path), XDG_CONFIG_HOME=str(tmp_path))
    run = subprocess.run([NVIM, "--headless", "-n", "-i", "NONE", "-u", str(init),
                          "-c", f"luafile {script}"], cwd=tmp_path, env=env,
                         capture_output=True, timeout=120)
    assert result.exists(), run.stderr.decode()[-2000:]
    found = json.loads(result.read_text())
    assert found["filetype"] == "castor"
    assert found["clients"] == 1
    messages = [d["message"] for d in found["diagnostics"]]
    assert messages == ["object 'murr' is not defined; did you mean 'mur'?",
                        "object 'w' is not defined (its definition had errors)"]
    assert (found["diagnostics"][0]["line"], found["diagnostics"][0]["col"]) == (2, 24)
    hover = found["hover"]["contents"]["value"]
    assert hover.startswith("H = 2.9") and "height of the walls" in hover
    definition = found["definition"][0]
    assert definition["range"]["start"]["line"] == 1  # 'mur =' on the second line
    assert found["after_edit"] == 0
    assert scene.read_text().count("murr") == 1  # the buffer was never written


VIM = shutil.which("vim")

VIM_SCRIPT = r"""
let g:added = []
function! LspAddServer(servers)
  call extend(g:added, a:servers)
endfunction
let g:defined = {}
let &runtimepath = '@VIM@,@FAKE@,' . &runtimepath
runtime plugin/castor_lsp.vim
doautocmd VimEnter
doautocmd User lsp_setup
runtime ale_linters/castor/castor_lsp.vim
let g:result = #{added: g:added, cmd: g:registered.cmd({}), allowlist: g:registered.allowlist,
      \ ale_name: g:defined.name, ale_lsp: g:defined.lsp,
      \ ale_command: g:defined.command(1), ale_executable: g:defined.executable(1)}
call writefile([json_encode(g:result)], '@RESULT@')
qall!
"""

FAKE_VIM_LSP = """
function! lsp#register_server(info) abort
  let g:registered = a:info
endfunction
"""

FAKE_ALE = """
function! ale#linter#Define(filetype, linter) abort
  let g:defined = a:linter
  let g:defined.filetype = a:filetype
endfunction
function! ale#Escape(text) abort
  return shellescape(a:text)
endfunction
"""


@pytest.mark.skipif(VIM is None, reason="vim is not installed (Debian: apt install vim)")
def test_vim9_files_register_the_server_with_each_client(tmp_path: Path):
    """Debian's Vim 9 sources vim/ as a user's Vim would; the three clients'
    registration functions (yegappan/lsp's LspAddServer, vim-lsp's
    lsp#register_server, ALE's ale#linter#Define) are stood in for, and what
    castor's files hand them is checked."""
    fake = tmp_path / "fake"
    (fake / "autoload" / "ale" / "linter").mkdir(parents=True)
    (fake / "autoload" / "lsp.vim").write_text(FAKE_VIM_LSP)
    (fake / "autoload" / "ale").mkdir(exist_ok=True)
    (fake / "autoload" / "ale" / "linter.vim").write_text(FAKE_ALE.split("function! ale#Escape")[0])
    (fake / "autoload" / "ale.vim").write_text("function! ale#Escape" +
                                               FAKE_ALE.split("function! ale#Escape")[1])
    result = tmp_path / "result.json"
    script = tmp_path / "test.vim"
    script.write_text(VIM_SCRIPT.replace("@VIM@", str(ROOT / "vim")).replace("@FAKE@", str(fake))
                      .replace("@RESULT@", str(result)))
    run = subprocess.run([VIM, "-N", "-u", "NONE", "-i", "NONE", "-es", "-S", str(script)],
                         cwd=tmp_path, capture_output=True, timeout=60,
                         env=dict(os.environ, HOME=str(tmp_path)))
    assert result.exists(), (run.stdout + run.stderr).decode()[-2000:]
    found = json.loads(result.read_text())
    assert found["added"] == [{"name": "castor", "filetype": ["castor"], "path": "castor",
                               "args": ["--lsp"]}]
    assert found["cmd"] == ["castor", "--lsp"] and found["allowlist"] == ["castor"]
    assert found["ale_name"] == "castor_lsp" and found["ale_lsp"] == "stdio"
    assert found["ale_command"] == "'castor' '--lsp'" and found["ale_executable"] == "castor"

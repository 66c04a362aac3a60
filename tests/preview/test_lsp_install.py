"""castor --lsp works with castor as the README installs it (issue 29, item 7):
pygls and lsprotocol are ordinary dependencies, and castor's start-up never
imports them (nor the analysis): only --lsp does."""

from __future__ import annotations

import os
import subprocess
import sys
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def _names(requirements: list[str]) -> set[str]:
    return {r.split(">")[0].split("=")[0].split("<")[0].split("[")[0].strip().lower()
            for r in requirements}


def test_pygls_and_lsprotocol_are_ordinary_dependencies():
    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    assert {"pygls", "lsprotocol"} <= _names(project["dependencies"])
    # the old extra still installs (nothing more)
    assert "lsp" in project["optional-dependencies"]


IMPORTED = """
import sys
from castor import cli
status = cli.main(sys.argv[1:])
names = sorted(n for n in sys.modules if n.split(".")[0] in ("pygls", "lsprotocol")
               or n.startswith(("castor.lsp", "castor.analysis")))
print("IMPORTED", names)
"""


def _imported(args: list[str], stdin: str = "") -> list[str]:
    run = subprocess.run([sys.executable, "-c", IMPORTED, *args], input=stdin, text=True,
                         capture_output=True, timeout=60, cwd=ROOT,
                         env=dict(os.environ, PYTHONPATH=str(ROOT)))
    line = [line for line in run.stdout.splitlines() if line.startswith("IMPORTED")]
    assert line, run.stderr[-2000:]
    return eval(line[-1].removeprefix("IMPORTED "))  # a list of names, printed by repr


def test_start_up_imports_neither_pygls_nor_the_analysis():
    assert _imported(["--check", "-"], "> !cu(1, 0, 0);\n") == []
    assert _imported(["-"], "> !cu(1, 0, 0);\n") == []


def test_params_imports_the_analysis_but_not_the_protocol():
    found = _imported(["--params", "-"], "H = 3; // [1:5]\n> @h(H, 1, 1) !cu(1, 0, 0);\n")
    assert "castor.analysis.scene" in found
    assert not [n for n in found if n.startswith(("pygls", "lsprotocol", "castor.lsp"))]


def test_lsp_starts_and_answers_initialize(tmp_path: Path):
    message = b'{"jsonrpc": "2.0", "id": 1, "method": "initialize", "params": {"capabilities": {}}}'
    exit_ = b'{"jsonrpc": "2.0", "method": "exit", "params": null}'
    data = b"".join(b"Content-Length: %d\r\n\r\n%s" % (len(m), m) for m in (message, exit_))
    run = subprocess.run([sys.executable, "-m", "castor", "--lsp"], input=data, cwd=tmp_path,
                         capture_output=True, timeout=60, env=dict(os.environ, PYTHONPATH=str(ROOT)))
    assert b'"renameProvider"' in run.stdout and b'"hoverProvider": true' in run.stdout, run.stderr


def test_the_analysis_lives_apart_from_the_protocol():
    """castor/lsp/ holds the protocol only: the preview and the command line
    reach the analysis through castor.analysis, and castor.analysis never
    imports the protocol (issue 28, item 3)."""
    import ast

    wrong = []
    for path in sorted((ROOT / "castor").rglob("*.py")):
        module = ".".join(path.relative_to(ROOT).with_suffix("").parts)
        for node in ast.walk(ast.parse(path.read_text())):
            names = [node.module or ""] if isinstance(node, ast.ImportFrom) else \
                [a.name for a in node.names] if isinstance(node, ast.Import) else []
            for name in names:
                if name.startswith("castor.lsp") and not module.startswith("castor.lsp") \
                        and (module, name) != ("castor.cli", "castor.lsp.server"):
                    wrong.append(f"{module} imports {name}")
                if module.startswith("castor.analysis") and name.split(".")[0] in (
                        "pygls", "lsprotocol"):
                    wrong.append(f"{module} imports {name}")
    assert wrong == []

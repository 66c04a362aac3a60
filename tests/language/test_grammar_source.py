"""The grammar at the top of the repository, shipped into the package (issue 28, item 6).

grammar/castor.lark is the one source: a checkout reads it there; setup.py's
build step (what `pip install .` runs) copies it beside castor/language/parse.py
with the tables made from it, and castor run from the built package reads only
its package.
"""

import re
import subprocess
import sys
from pathlib import Path

from castor.language import tables
from castor.language.parse import grammar_text

ROOT = Path(__file__).resolve().parents[2]
SOURCE = ROOT / "grammar" / "castor.lark"


def test_a_checkout_reads_the_grammar_at_the_top():
    assert SOURCE.is_file()
    assert not (ROOT / "castor" / "language" / "castor.lark").exists()  # one source only
    assert Path(tables.grammar_path()) == SOURCE
    assert grammar_text() == SOURCE.read_text(encoding="utf-8")


def test_every_grammar_file_named_exists():
    """Docstrings and comments named grammar/castor.lark before it was there."""
    named = set()
    for path in [*(ROOT / "castor").rglob("*.py"), ROOT / "setup.py", ROOT / "pyproject.toml",
                 ROOT / "MANIFEST.in", SOURCE]:
        named |= set(re.findall(r"\b[\w./-]*/[\w.-]+\.lark\b", path.read_text(encoding="utf-8")))
    assert "grammar/castor.lark" in named
    assert all((ROOT / name).exists() for name in named), named


def test_the_built_package_carries_the_grammar_and_reads_only_itself(tmp_path):
    build = tmp_path / "site"
    done = subprocess.run([sys.executable, "setup.py", "-q", "build_py", "--build-lib", str(build)],
                          cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    shipped = build / "castor" / "language" / "castor.lark"
    assert shipped.read_bytes() == SOURCE.read_bytes()
    # run from elsewhere, with no repository beside it: its own grammar and tables,
    # and a syntax error still worded from lark's parser built on that grammar
    code = ("import sys; from castor.language import tables, parse\n"
            "print(tables.grammar_path()); from castor import cli\n"
            "sys.exit(cli.main(sys.argv[1:]))\n")
    (tmp_path / "tmp").mkdir()
    env = {"PYTHONPATH": str(build), "TMPDIR": str(tmp_path / "tmp"), "PATH": "/usr/bin:/bin"}
    run = subprocess.run([sys.executable, "-B", "-c", code, "--no-cpp", "-"],
                         input="> !cu(1, 0, 0);\nx = @t(1, 2 !cu(1, 0, 0);\n", cwd=tmp_path,
                         capture_output=True, text=True, env=env, timeout=120)
    assert run.stdout.splitlines()[0] == str(shipped)
    assert "endframe 1 6" in run.stdout
    assert "<stdin>:2:13: error: expected ',' or ')' after an argument, found '!cu'" in run.stderr
    assert list((tmp_path / "tmp").iterdir()) == []  # no tables built at run time

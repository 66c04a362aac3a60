"""The test suite's own layout (tests/README.md): shared helpers live in the
``tests.support`` and ``tests.oracle`` packages, imported by those names; no
test module imports another, and no helper imports a test module."""

import ast
from pathlib import Path

TESTS = Path(__file__).resolve().parents[1]
HELPERS = ("support", "oracle")


def _imported(path: Path) -> list[str]:
    """The modules a file imports, by the names written (relative ones as '.x')."""
    names = []
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            names += [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            names.append("." * node.level + (node.module or ""))
    return names


def wrong_imports(root: Path) -> list[str]:
    """Imports that break the rule, in the test suite under ``root``: a test
    module or a helper importing a test module, or any module under ``root``
    by a bare name (which works only with its folder on sys.path)."""
    bare = {p.stem for p in root.rglob("*.py")} | {p.name for p in root.iterdir() if p.is_dir()}
    wrong = []
    for path in sorted(root.rglob("*.py")):
        helper = path.relative_to(root).parts[0] in HELPERS
        for name in _imported(path):
            parts = name.split(".")
            if (parts[-1].startswith("test_") or (parts[0] in bare and not helper)
                    or (parts[0] == "tests" and parts[1:2] not in ([], ["support"], ["oracle"]))):
                wrong.append(f"{path.relative_to(root)} imports {name}")
    return wrong


def test_no_test_module_imports_another_and_helpers_come_from_their_packages():
    assert wrong_imports(TESTS) == []


def test_the_rule_is_seen(tmp_path):
    """An import of one test module by another, and of a helper by a bare name."""
    for folder in ("geometry", "drawings", "support"):
        (tmp_path / folder).mkdir()
    (tmp_path / "drawings" / "test_drawings.py").write_text("from tests.support.cli import run\n")
    (tmp_path / "support" / "cli.py").write_text("from .stream import Frame\n")
    (tmp_path / "geometry" / "test_a.py").write_text(
        "import numpy\nfrom test_drawings import Drawn\nimport cli\nfrom tests.drawings import x\n")
    assert wrong_imports(tmp_path) == ["geometry/test_a.py imports test_drawings",
                                       "geometry/test_a.py imports cli",
                                       "geometry/test_a.py imports tests.drawings"]

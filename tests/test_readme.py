"""The README's two commands for a fresh machine, and CI running the second."""

from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def _blocks():
    text = (ROOT / "README.md").read_text()
    parts = text.split("```")
    return [parts[i].strip() for i in range(1, len(parts), 2)]


def test_ci_runs_the_readme_test_command_exactly():
    first, second = _blocks()[:2]
    assert "pip install ." in first and "castor examples/" in first
    assert "pytest" in second
    ci = (ROOT / ".ci" / "run").read_text().splitlines()
    assert ci[-1] == second

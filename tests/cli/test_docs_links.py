"""The README and the pages of docs/ lead where they say (issue 28, item 5).

Every relative link of README.md and docs/*.md names a file that exists, and a
link to a heading (`page.md#heading`) a heading that page has, as GitHub
makes its anchors. Every path the pages name in the repository's own folders
(`castor/mesh/creases.py`, `tests/oracle.py`, `docs/pictures/car.png`), and
every path written in backquotes with a folder and an ending (`mesh/merge.py`,
under `castor/`), exists: a moved module or test must take its pages along.
"""

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)\)")
FOLDERS = ("castor", "tests", "benchmarks", "scripts", "vim", "docs", "examples", ".ci")
NAMED = re.compile(r"(?<![\w./~-])((?:%s)/[\w./-]*\w)" % "|".join(re.escape(f) for f in FOLDERS))
QUOTED = re.compile(r"`([\w.-]+(?:/[\w.-]+)+\.(?:py|lark|md|sh|js|vim|lua|png|gif|html|css))`")


def anchor(heading: str) -> str:
    """GitHub's anchor of a heading: lower case, punctuation dropped, spaces as hyphens."""
    text = re.sub(r"[^\w\- ]", "", heading.strip().lower())
    return text.replace(" ", "-")


def anchors(page: Path) -> set[str]:
    text = re.sub(r"```.*?```", "", page.read_text(), flags=re.S)
    return {anchor(m.group(1)) for m in re.finditer(r"^#{1,6} (.+)$", text, re.M)}


def test_the_anchors_are_made_as_github_makes_them():
    assert anchor("Smooth solids (`@s`)") == "smooth-solids-s"
    assert anchor("Meshes: the engine's results, memory, writing") == \
        "meshes-the-engines-results-memory-writing"


def test_the_readme_leads_to_every_page_of_docs():
    readme = (ROOT / "README.md").read_text()
    linked = {m.group(1) for m in LINK.finditer(readme)}
    pages = {f"docs/{p.name}" for p in PAGES[1:]}
    assert len(pages) >= 8
    assert pages <= linked, pages - linked


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.name)
def test_every_link_leads_to_a_file_and_heading_that_exist(page):
    broken = []
    for m in LINK.finditer(page.read_text()):
        target = m.group(1)
        if re.match(r"[a-z]+:", target):  # https:, mailto:
            continue
        path, _, heading = target.partition("#")
        goal = (page.parent / path).resolve() if path else page
        if not goal.exists():
            broken.append(target)
        elif heading and goal.suffix == ".md" and heading not in anchors(goal):
            broken.append(target)
    assert not broken, broken


def _placeholder(path: str) -> bool:
    """A path written with a word in capitals for the reader's own: castor/formats/NAME.py."""
    return re.search(r"\b[A-Z]{2,}\b", path) is not None


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.name)
def test_every_path_a_page_names_exists(page):
    text = page.read_text()
    missing = []
    for m in NAMED.finditer(text):
        path = m.group(1).rstrip(".")
        if not _placeholder(path) and not (ROOT / path).exists():
            missing.append(path)
    for m in QUOTED.finditer(text):
        path = m.group(1)
        bases = (ROOT, ROOT / "castor", page.parent)
        if not _placeholder(path) and not any((base / path).exists() for base in bases):
            missing.append(path)
    assert not missing, missing

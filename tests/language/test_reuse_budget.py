"""The parsed statements the editing loop remembers (castor.analysis.reuse) are
bounded by their text, not only by their number (issue 29, item 11): each
version of a long statement typed in kept its scene graph alive (up to 50,000
statements, whatever their size: a statement of 40,000 cubes is 1.2 MB of text
and 77 MB of nodes). Memory is counted (statements and characters kept), not
timed."""

from __future__ import annotations

import pytest

from castor.analysis import reuse
from castor.analysis.scene import analyse
from castor.settings import Source


def _long(cubes: int, version: int) -> str:
    operands = ", ".join(f"@t({k}, 0, 0) !cu(0.{version}, 0, 0)" for k in range(cubes))
    return f"big = $U({operands});\n> big;\n"


@pytest.fixture
def budget(monkeypatch):
    reuse.forget()
    monkeypatch.setattr(reuse, "MAX_TEXT", 20_000, raising=False)
    yield 20_000
    reuse.forget()


def _kept_text() -> int:
    """The characters of the statements remembered, counted from the memory itself."""
    return sum(len(key[0]) for key in list(reuse._remembered))


def test_the_versions_of_a_long_statement_kept_stay_within_the_budget(budget):
    statement = len(_long(300, 0).split("\n")[0])  # about 7,700 characters
    assert budget // 3 < statement < budget // 2
    for version in range(8):  # eight edits of the long statement
        analysis = analyse(Source(text=_long(300, version), name="long.cas"))
        assert analysis.diagnostics == []
        assert _kept_text() <= budget
    # the newest versions are those kept: two long statements and the short '> big;'
    texts = [key[0] for key in reuse._remembered]
    assert len([t for t in texts if t.startswith("big")]) == 2
    assert any("!cu(0.7, 0, 0)" in t for t in texts)
    assert reuse.remembered() == (len(texts), _kept_text())


def test_a_statement_used_again_is_kept_before_older_ones(budget):
    first, second, third = _long(300, 1), _long(300, 2), _long(300, 3)
    analyse(Source(text=first, name="long.cas"))
    analyse(Source(text=second, name="long.cas"))
    again = analyse(Source(text=first, name="long.cas"))  # undo: the first text again
    assert again.diagnostics == []
    analyse(Source(text=third, name="long.cas"))  # forgets the second, used least recently
    texts = [key[0] for key in reuse._remembered]
    assert any("!cu(0.1, 0, 0)" in t for t in texts)
    assert any("!cu(0.3, 0, 0)" in t for t in texts)
    assert not any("!cu(0.2, 0, 0)" in t for t in texts)


def test_a_statement_longer_than_the_budget_is_not_kept(budget):
    analysis = analyse(Source(text=_long(1_000, 0), name="long.cas"))  # 26,000 characters
    assert analysis.diagnostics == []
    assert [key[0] for key in reuse._remembered] == ["\n> big;"]
    assert _kept_text() <= budget


def test_many_short_statements_are_all_kept():
    reuse.forget()
    text = "".join(f"P{k} = {k};\n" for k in range(200)) + "> !cu(1, 0, 0);\n"
    analyse(Source(text=text, name="short.cas"))
    again = analyse(Source(text=text, name="short.cas"))
    assert again.diagnostics == []
    count, characters = reuse.remembered()
    assert count == 201 and characters == _kept_text()
    reuse.forget()

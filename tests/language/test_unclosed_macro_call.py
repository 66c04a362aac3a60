"""A macro call whose '(' never closes is said at the call, once.

``#define X(a) a`` then ``m = X(!cu(1,1,1);`` said "'m' starts with a lowercase
letter ... the parameter name 'X' is not an object" (the preprocessor had left
the call unexpanded without a word) and then that 'm' was not defined; GNU cpp
says "unterminated argument list invoking macro". castor now says so at the
call, in the user's words, and nothing more for that statement or the names it
defined. A macro given the wrong number of arguments no longer cascades either.
"""

import pytest

from castor.analysis.scene import analyse
from castor.settings import Source
from tests.support.cli import run_here

SCENES = {
    "unclosed": ("#define X(a) a\nm = X(!cu(1,1,1);\n> m;\n",
                 "2:5: error: the call of macro X has no closing ')'"),
    "unclosed-before-a-directive": (
        "#define X(a) a\nm = X(!cu(1,1,1);\n#define Y 2\nK = Y;\n> m;\n",
        "2:5: error: the call of macro X has no closing ')'"),
    "argument-count": ("#define X(a, b) a\nm = X(!cu(1,1,1));\n> m;\n",
                       "2:5: error: macro X takes 2 arguments, but 1 was given"),
}


@pytest.mark.parametrize("name", sorted(SCENES))
def test_one_message_at_the_call(tmp_path, monkeypatch, name):
    monkeypatch.chdir(tmp_path)
    text, message = SCENES[name]
    (tmp_path / "mac.cas").write_text(text)
    status, out, err = run_here("--check", "mac.cas")
    assert (status, out) == (1, "")
    assert err == f"mac.cas:{message}\n {text.splitlines()[1]}\n     ^\n"
    # the language server's analysis says the same, and nothing more
    found = [f"{d.location.line}:{d.location.column}: {d.kind}: {d.message}"
             for d in analyse(Source(text=text, name=str(tmp_path / "mac.cas"))).diagnostics]
    assert found == [message]


def test_a_call_over_several_lines_is_no_error(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "ml.cas").write_text("#define X(a) a\nm = X(\n  !cu(1,1,1)\n);\n> m;\n")
    assert run_here("--check", "ml.cas") == (0, "", "")


def test_the_statements_after_it_are_still_checked(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "mac.cas").write_text("#define X(a) a\nm = X(!cu(1,1,1);\n> m;\n")
    (tmp_path / "more.cas").write_text("n = @h(1, Q, 1) !cu(1, 1, 1);\n> n;\n")
    status, _, err = run_here("--check", "mac.cas", "more.cas")
    assert status == 1
    assert [line.split(": error: ")[0] for line in err.splitlines()
            if ": error: " in line] == ["mac.cas:2:5", "more.cas:1:11"]

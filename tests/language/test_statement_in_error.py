"""LANGUAGE.md §9: "the statement in error is skipped".

``P = 5`` without its ';', followed by statements: castor says ``expected ';'
at the end of the statement`` and exits 1, yet took the statement as if the
';' were there, and wrote a frame made with P = 5. The parser
(castor/language/parse.py, Parser.parse) re-parses the statement given its
';' and delivers it; the fix, there, delivers its errors and a
SkippedDefinition instead. Marked as expected to fail until that file, which
another change owns, takes it (and tests/language/test_diagnostics.py's
test_missing_semicolon_is_recovered and tests/cli/test_user_errors.py's
test_missing_semicolon_before_a_comment_at_the_end, which assert the
recovery, are turned round).
"""

import pytest

from tests.support.cli import run_here

SKIPPED = pytest.mark.xfail(strict=True, reason="parse.py delivers a statement given its "
                            "missing ';' (LANGUAGE.md §9 skips it)")


@SKIPPED
def test_a_parameter_missing_its_semicolon_is_not_used(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "err2.cas").write_text(
        "L = 8;\nP = 5\nmurs = @h(L, P, 3) !cu(1, 1, 1);\n> murs;\n")
    status, out, err = run_here("-o", "keep.stl", "err2.cas")
    assert status == 1
    assert err.splitlines()[:3] == [
        "err2.cas:2:6: error: expected ';' at the end of the statement, found the name 'murs'",
        " P = 5", "      ^"]
    assert not (tmp_path / "keep.stl").exists()  # its only frame needed P


@SKIPPED
def test_an_earlier_value_stays(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "s.cas").write_text("P = 4;\nP = 5\nm = @h(P, 1, 1) !cu(1, 1, 1);\n> m;\n")
    status, out, err = run_here("s.cas")
    assert status == 1 and err.count("error:") == 1
    assert "frame 1" in out and " 4 " in out and " 5 " not in out

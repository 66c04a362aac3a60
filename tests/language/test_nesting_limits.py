"""The README's nesting limits, as the code has them (castor.language.parse's
MAX_DEPTH): 100,000 levels of objects and expressions; parentheses alone are no
level. A frame nested just below the parser's limit went past the evaluator's
stack and ended in 'internal error: IndexError' (the frame's RecursionError was
taken for the parser's); it is an error at the '>' that says so."""

from tests.support.cli import run


def _nested(depth: int) -> str:
    return "> " + "$U(" * depth + "!cu(1, 1, 1)" + ")" * depth + ";\n"


def test_a_frame_too_deep_to_evaluate_is_an_error_not_a_crash(tmp_path):
    (tmp_path / "deep.cas").write_text(_nested(99_990))
    status, out, err = run("--check", "deep.cas", cwd=tmp_path)
    assert status == 1
    assert err == "deep.cas:1:1: error: the frame's objects are nested too deeply to evaluate\n"


def test_parentheses_alone_have_no_limit_and_operands_100000(tmp_path):
    deep = 200_000
    (tmp_path / "p.cas").write_text("H = 1;\nX = " + "(" * deep + "H" + ")" * deep
                                    + ";\n> @t(X, 0, 0) !cu(1, 1, 1);\n")
    status, out, err = run("--check", "p.cas", cwd=tmp_path)
    assert status == 0 and err == ""
    (tmp_path / "f.cas").write_text("H = 1;\nX = " + "abs(" * 100_001 + "H" + ")" * 100_001
                                    + ";\n> @t(X, 0, 0) !cu(1, 1, 1);\n")
    status, out, err = run("--check", "f.cas", cwd=tmp_path)
    assert status == 1
    assert err.startswith("f.cas:2:9: error: nesting deeper than 100000 levels")

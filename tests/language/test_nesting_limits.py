"""The README's nesting limits, as the code has them (castor.language.parse's
MAX_DEPTH): 100,000 levels of objects and expressions; parentheses alone are no
level. A frame nested just below the parser's limit went past the evaluator's
stack and ended in 'internal error: IndexError' (the frame's RecursionError was
taken for the parser's); now every thread and process that walks a tree has the
stack and the recursion limit for it (castor.settings), so what the parser
accepts is evaluated and written."""

from tests.support.cli import run


def _nested(depth: int) -> str:
    return "> " + "$U(" * depth + "!cu(1, 1, 1)" + ")" * depth + ";\n"


def test_a_frame_just_below_the_parsers_limit_is_evaluated_and_written(tmp_path):
    (tmp_path / "deep.cas").write_text(_nested(99_990))
    status, out, err = run("--check", "deep.cas", cwd=tmp_path)
    assert (status, err) == (0, "")
    status, out, err = run("-o", "deep.stl", "deep.cas", cwd=tmp_path)
    assert (status, err) == (0, "")
    assert (tmp_path / "deep.stl").stat().st_size == 84 + 12 * 50  # the cube's 12 triangles


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

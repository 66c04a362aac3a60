"""The preprocessor's messages in castor's words (issue 29's trial): pcpp's own
texts ('Unterminated #if 1' followed by an empty line, 'Misplaced #endif') were
capitalised, said nothing of what to write, and the first left a blank line; an
#elif or a second #else after a block's #else passed without a word, and an #if
without a condition made its #endif 'misplaced'."""

import pytest

from tests.support.cli import run

CUBE = "x = !cu(1, 0, 0);\n> x;\n"


@pytest.mark.parametrize("text, message", [
    ("#if 1\n" + CUBE,
     "<stdin>:1:1: error: '#if 1' has no matching '#endif'; add #endif where its block ends"),
    ("#ifdef A  // walls\n" + CUBE,
     "<stdin>:1:1: error: '#ifdef A' has no matching '#endif'; add #endif where its block ends"),
    ("#ifndef A\n" + CUBE,
     "<stdin>:1:1: error: '#ifndef A' has no matching '#endif'; add #endif where its block ends"),
    ("#else\n" + CUBE,
     "<stdin>:1:1: error: '#else' without an '#if' before it; remove it, or add the #if it "
     "belongs to"),
    (CUBE + "#elif 1\n",
     "<stdin>:3:1: error: '#elif' without an '#if' before it; remove it, or add the #if it "
     "belongs to"),
    ("#endif\n" + CUBE,
     "<stdin>:1:1: error: '#endif' without an '#if' before it; remove it, or add the #if it "
     "closes"),
    ("#if 1\n#else\n#elif 1\n#endif\n" + CUBE,
     "<stdin>:3:1: error: an '#elif' after this block's '#else' (line 2); a block has one "
     "#else, after its #elif"),
    ("#if 0\n#else\n#else\n#endif\n" + CUBE,
     "<stdin>:3:1: error: a second '#else' after this block's '#else' (line 2); a block has "
     "one #else, after its #elif"),
    ("#define F(X X\n" + CUBE,
     "<stdin>:1:1: error: #define: its parameters have no ')'; write #define NAME(X, Y) VALUE"),
    ("#include <walls.cas\n" + CUBE,
     "<stdin>:1:1: error: malformed #include <...> (no '>'); write #include \"file.cas\""),
    ("#define F(..., X) X\n" + CUBE,
     "<stdin>:1:1: error: #define: no parameter may follow '...'; write ... last"),
    ("#error stop here\n" + CUBE, "<stdin>:1:1: error: #error stop here"),
])
def test_each_message_is_one_line_in_castor_s_words(text, message):
    status, out, err = run("--check", stdin=text)
    assert status == 1
    assert err.splitlines() == [message]
    assert err == message + "\n"  # no blank line after it


def test_an_if_without_a_condition_still_opens_its_block():
    status, out, err = run("--check", stdin="#if\ny = !cu(1, 1, 1);\n#else\n" + CUBE + "#endif\n")
    assert status == 1
    assert err.splitlines() == ["<stdin>:1:1: error: #if needs a condition"]


def test_nested_blocks_each_have_their_else():
    text = "#if 0\n#if 1\n#else\n#endif\n#else\n#ifdef A\n#elif 1\n#else\n#endif\n#endif\n"
    status, out, err = run("--check", stdin=text + CUBE)
    assert status == 0 and err == ""

"""The root lexer's faster order (castor.language.lexing): proven for the grammar
(grammar/castor.lark), refused where it would change a token, and reading the
same tokens as lark's order (issue 29, item 11)."""

from __future__ import annotations

import re
from pathlib import Path

from castor.language import lexing

ROOT = Path(__file__).resolve().parents[2]
PUNCTUATION = ("COMMA", "LPAR", "RPAR", "LSQB", "RSQB", "SEMICOLON", "EQUAL", "FACETIZE",
               "POW", "ADDOP", "MULOP")


def _root():
    """The root lexer's expression as made from the grammar file (a checkout reads
    grammar/castor.lark; its tables are made from it when it changes)."""
    from castor.language.parse import _parser_and_builder, grammar_text
    from castor.language.scene import Tables

    assert grammar_text() == (ROOT / "grammar" / "castor.lark").read_text()
    parser, _ = _parser_and_builder(Tables())
    patterns, ignored, _, _ = parser._root
    pattern = "|".join(p for p, _ in patterns)
    return pattern, patterns[0][1], frozenset(ignored)


def test_the_grammar_s_punctuation_and_blanks_are_proven_first():
    pattern, flags, ignored = _root()
    moved = lexing.faster_order(lexing.alternatives(pattern, flags), flags)
    # the single characters are tried before names and numbers
    assert max(moved.index(n) for n in PUNCTUATION if n not in ("ADDOP", "MULOP")) < \
        min(moved.index("LNAME"), moved.index("NUMBER"))
    # and '/' (MULOP) still after '//' and '/*' (COMMENT)
    assert moved.index("COMMENT") < moved.index("MULOP")
    _, blanks = lexing.order(pattern, flags, ignored)
    assert blanks and re.fullmatch(blanks, " \t\n ") is not None


def test_terminals_that_may_start_alike_keep_their_order():
    pieces = [("NAME", r"(?P<NAME>[a-z]+)"), ("KEYWORD", r"(?P<KEYWORD>if)"),
              ("ANY", r"(?P<ANY>.)"), ("SLASH", r"(?P<SLASH>/)"), ("DIGIT", r"(?P<DIGIT>\d)")]
    moved = lexing.faster_order(pieces, re.UNICODE)
    assert moved.index("NAME") < moved.index("KEYWORD")  # 'if' is also a NAME
    assert moved.index("ANY") < moved.index("SLASH") and moved.index("ANY") < moved.index("DIGIT")
    # one that may match nothing (it may win anywhere) lets nothing pass it
    empty = [("A", r"(?P<A>a)"), ("EMPTY", r"(?P<EMPTY>x*)"), ("B", r"(?P<B>b)")]
    assert lexing.faster_order(empty, re.UNICODE) == ["A", "EMPTY", "B"]


def test_blanks_that_another_terminal_may_start_are_not_folded():
    pattern = r"(?P<A>[ ]+x)|(?P<WS>[ ]+)|(?P<B>b)"
    alternatives, blanks = lexing.order(pattern, re.UNICODE, frozenset({"WS"}))
    assert blanks == ""
    assert alternatives.index("(?P<A>") < alternatives.index("(?P<WS>")


def _tokens(regex, text):
    out, pos = [], 0
    scan = re.compile(regex + r"|(?P<stray>(?s:.))|(?P<end>\Z)", re.UNICODE)
    while True:
        found = scan.match(text, pos)
        kind = found.lastgroup
        if kind == "end":
            return out
        out.append((kind, found.start(kind), found.group(kind)))
        pos = found.end()


def test_the_new_order_reads_the_same_tokens():
    pattern, flags, ignored = _root()
    alternatives, blanks = lexing.order(pattern, flags, ignored)
    text = ("P = 2.5e3 ^ -(1 % 3) / 4 * .5; // note\n/* a\n b */ a = @t(1, P, 0)"
            " $U[I = 0, 3]( !cu(0, 1, 2), b) ;\n> a, #x £ é\t\f 1.2.3e 9E+2;  ")
    old = [t for t in _tokens(pattern, text) if t[0] not in ignored]
    new = [t for t in _tokens(f"{blanks}(?:{alternatives})", text) if t[0] not in ignored]
    assert new == old
    assert ("MULOP", text.index("/ 4"), "/") in new


def test_a_call_s_plain_arguments_are_proven_readable_at_once():
    pattern, flags, ignored = _root()
    found = lexing.arguments(pattern, flags, ignored, "LPAR", ("COMMA", "RPAR"), "ADDOP",
                             ("NUMBER", "PARAM"))
    assert found is not None  # else a long statement is read token by token again
    assert (found.opening, found.separator, set(found.blanks), found.signs) == \
        ("(", ",", set(" \t\n\r\f"), {"+", "-"})
    assert set("AHZ") <= found.names and not found.names & set("0.ahz_")
    whole = re.compile(found.whole, flags)
    assert whole.match(" \n( - \t1.5e3 ,H,.5 )x").end() == 20
    for refused in ("(/* c */ 1)", "(1 /* c */)", "(2 * H)", "(1.5.3)", "(x)", "(--1)", "(f(1))",
                    "()", "(1,)", "(1 2)", "1)", "(1e)", "(H(1))"):
        assert whole.match(refused) is None, refused


def _proven(pattern: str) -> bool:
    """Whether a call's plain arguments are proven readable at once with these terminals."""
    return lexing.arguments(pattern, re.UNICODE, frozenset({"WS"}), "LPAR", ("COMMA", "RPAR"),
                            "ADDOP", ("NUMBER", "NAME")) is not None


def test_plain_arguments_are_not_read_at_once_where_another_terminal_may_start_alike():
    # a terminal '-1' (that a number with its sign might be) and the sign's '-'
    pattern = (r"(?P<NEG>\-1)|(?P<NUMBER>\d+)|(?P<NAME>[A-Z]+)|(?P<ADDOP>\-)|(?P<LPAR>\()"
               r"|(?P<RPAR>\))|(?P<COMMA>,)|(?P<WS>[ ]+)")

    assert not _proven(pattern)
    assert _proven(pattern.replace(r"(?P<NEG>\-1)|", ""))
    # signs of two characters, blanks that are not a run of known characters
    assert not _proven(pattern.replace(r"(?P<NEG>\-1)|", "").replace(r"(?P<ADDOP>\-)",
                                                                    r"(?P<ADDOP>\-\-)"))
    assert not _proven(pattern.replace(r"(?P<NEG>\-1)|", "").replace(r"(?P<WS>[ ]+)",
                                                                    r"(?P<WS>[ ]+x)"))


def test_groups_are_made_non_capturing_only_where_the_expression_reads_the_same():
    assert lexing._uncaptured(r"(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?") == \
        r"(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?"
    # parentheses escaped or in a class are characters, '[]' and '[^]' open a class
    assert lexing._uncaptured(r"\((a)\)[(][^]()]+[]](c)") == r"\((?:a)\)[(][^]()]+[]](?:c)"
    assert lexing._uncaptured(r"(?=(b))(?i:x)") == r"(?=(?:b))(?i:x)"
    for kept in (r"(a)\1", r"(?P<n>a)(?P=n)", r"(a)?(?(1)b|c)"):  # references to groups
        assert lexing._uncaptured(kept) == kept


def test_plain_arguments_are_not_read_at_once_where_a_value_may_hold_a_cut():
    # a number that may hold the comma, the ')' or a blank: the list is cut there
    pattern = (r"(?P<NUMBER>\d+)|(?P<NAME>[A-Z]+)|(?P<ADDOP>\-)|(?P<LPAR>\()"
               r"|(?P<RPAR>\))|(?P<COMMA>,)|(?P<WS>[ ]+)")

    assert _proven(pattern)
    for number in (r"\d+(?:,\d+)?", r"\d+(?:\)\d+)?", r"\d+(?: \d+)?", r"\d+.?"):
        assert not _proven(pattern.replace(r"\d+)", number + ")", 1)), number

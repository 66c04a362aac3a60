"""Syntax errors in the user's words: lark's exceptions translated into
castor's messages (what was found, what was expected, and the habits of other
languages that lead there), with the place to report them."""

from __future__ import annotations

import re

from lark import Token
from lark.exceptions import UnexpectedCharacters, UnexpectedEOF, UnexpectedInput, UnexpectedToken

from castor.diagnostics import CastorError, CastorSyntaxError
from castor.language.expressions import FUNCTIONS
from castor.language.reader import Chunk
from castor.language.scene import Tables

_WORDS = {
    "PARAM": "a parameter name",
    "LNAME": "a name",
    "NUMBER": "a number",
    "PRIMITIVE": "a primitive",
    "TRANSFORM": "a transformation",
    "BOOLEAN": "'$U', '$I' or '$D'",
    "FACETIZE": "'>'",
    "ADDOP": "'+' or '-'",
    "MULOP": "'*', '/' or '%'",
    "POW": "'^'",
    "SEMICOLON": "';'",
    "COMMA": "','",
    "LPAR": "'('",
    "RPAR": "')'",
    "LSQB": "'['",
    "RSQB": "']'",
    "EQUAL": "'='",
    "$END": "the end of the input",
}
_OPERATORS = {"ADDOP", "MULOP", "POW"}
_OBJECT_START = {"PRIMITIVE", "TRANSFORM", "BOOLEAN", "LNAME"}
_EXPR_START = {"NUMBER", "PARAM", "LPAR"}


def _describe_expected(expected: set[str]) -> str:
    expected = set(expected) - {"COMMENT", "WS"}
    words: list[str] = []
    if expected & {"COMMA", "RPAR", "RSQB", "SEMICOLON"}:
        expected -= _OPERATORS  # operators are always possible after a value: noise
    if _OBJECT_START <= expected:
        words.append("an object (a primitive such as !cu(...), a transformation, "
                     "$U/$I/$D or an object name)")
        expected -= _OBJECT_START
    if _EXPR_START <= expected:
        words.append("an expression")
        expected -= _EXPR_START | {"ADDOP", "LNAME"}
    if _OPERATORS <= expected:
        words.append("an operator")
        expected -= _OPERATORS
    order = ["SEMICOLON", "COMMA", "RPAR", "RSQB", "LPAR", "LSQB", "EQUAL"]
    for name in sorted(expected, key=lambda n: (order.index(n) if n in order else 99, n)):
        words.append(_WORDS.get(name, name.lower()))
    if not words:
        return "something else"
    if len(words) == 1:
        return words[0]
    return ", ".join(words[:-1]) + " or " + words[-1]


def _describe_found(token: Token) -> str:
    kind = token.type
    if kind == "$END":
        return "the end of the input"
    if kind == "NUMBER":
        return f"the number {token}"
    if kind == "PARAM":
        return f"the parameter name '{token}'"
    if kind == "LNAME":
        return f"the name '{token}'"
    if kind in ("PRIMITIVE", "TRANSFORM", "BOOLEAN"):
        return f"'{token}'"
    return f"'{token}'"


_COMMENT = re.compile(r"/\*(?:.|\n)*?\*/|//[^\n]*")
# an object definition (its name is lower case), after any comments
DEFINED = re.compile(r"(?:\s|/\*(?:.|\n)*?\*/|//[^\n]*)*([A-Za-z][A-Za-z0-9_]*)\s*=(?!=)")


def _code_before(text: str, pos: int) -> str:
    """``text[:pos]`` without its trailing blanks and comments: where a missing
    ';' goes (after '> a // the house', not inside the comment)."""
    blanked = _COMMENT.sub(lambda m: re.sub(r"[^\n]", " ", m.group()), text[:pos])
    return text[:len(blanked.rstrip())]


def _end_before(chunk: Chunk, pos: int):
    """The location just after the last character of code before ``pos``."""
    before = _code_before(chunk.text, pos)
    line = before.count("\n") + 1
    column = len(before) - (before.rfind("\n") + 1) + 1
    return chunk.location(line, column)


def _rest_from(chunk: Chunk, line: int, column: int) -> Chunk:
    lines = chunk.text.split("\n")
    first = lines[line - 1][column - 1:]
    offset = (column - 1) + (chunk.first_column if line == 1 else 0)
    return Chunk("\n".join([first] + lines[line:]), chunk.origins[line - 1:], offset)


def _acceptable(exc: UnexpectedToken) -> set[str]:
    """The tokens the parser would really take here.

    LALR merges states, so the table's list for the failing state can name
    tokens that this context does not allow; asking the interactive parser
    to try each one gives the true list.
    """
    parser = getattr(exc, "interactive_parser", None)
    if parser is not None:
        try:
            accepted = set(parser.accepts())
            if accepted:
                return accepted
        except (UnexpectedInput, CastorError, RecursionError):
            pass
    return set(exc.expected)


_NAME_BEFORE = re.compile(r"([a-z][A-Za-z0-9_]*)\s*$")
_DEFINES_NAME = re.compile(r"\s*([a-z][A-Za-z0-9_]*)\s*=\s*$")


def _habit(chunk: Chunk, pos: int, token: Token, expected: set[str], tables):
    """A message for the slips of people who write French (or other languages):
    a lowercase parameter name, a decimal comma. (message, location) or None."""
    before = _code_before(chunk.text, pos)
    if token.type == "COMMA" and re.search(r"\d$", before) \
            and re.match(r"\d", chunk.text[pos + 1:pos + 2]) and "COMMA" not in expected:
        number = re.search(r"[\d.]+$", before).group()
        digits = re.match(r"\d+", chunk.text[pos + 1:]).group()
        return (f"a decimal comma? write {number}.{digits} with a point; a comma separates "
                f"arguments", None)
    defined = _DEFINES_NAME.fullmatch(before)
    if defined and token.type in ("NUMBER", "PARAM", "LPAR", "ADDOP"):
        name = defined.group(1)
        return (f"'{name}' starts with a lowercase letter, so it names an object, and "
                f"{_describe_found(token)} is not an object; a parameter name starts with "
                f"an uppercase letter: {name[0].upper() + name[1:]} = ...", None)
    used = _NAME_BEFORE.search(before)
    if used and token.type == "LPAR" and "LPAR" not in expected:
        return _call_where_an_object_is_expected(chunk, before, used, tables)
    if used and "LPAR" in expected and token.type != "LPAR":
        name = used.group(1)
        start = chunk.location(before.count("\n") + 1,
                               used.start() - (before.rfind("\n") + 1) + 1)
        if name in FUNCTIONS:
            return f"the function '{name}' takes its argument in parentheses: {name}(...)", start
        if tables is not None and name in tables.objects:
            return (f"'{name}' is an object, not a number; parameters start with an "
                    f"uppercase letter", start)
        return (f"'{name}' is not a parameter: parameter names start with an uppercase "
                f"letter ({name[0].upper() + name[1:]})", start)
    return None


def _call_where_an_object_is_expected(chunk: Chunk, before: str, used, tables):
    """A lowercase name followed by '(' where an object is expected: a function
    call (``h = sqrt(-1);``) or an object given arguments; say that lowercase
    names are objects and parameters start with an uppercase letter."""
    name = used.group(1)
    start = chunk.location(before.count("\n") + 1, used.start() - (before.rfind("\n") + 1) + 1)
    defined = re.fullmatch(r"\s*([a-z][A-Za-z0-9_]*)\s*=\s*" + re.escape(name) + r"\s*", before)
    if tables is not None and name in tables.objects and name not in FUNCTIONS:
        return (f"'{name}' is an object and takes no arguments; for a value that varies, "
                f"use a parameter (its name starts with an uppercase letter) inside the "
                f"object's definition", start)
    what = (f"'{name}' is a function, called" if name in FUNCTIONS
            else f"'{name}(' is a call")
    if defined:
        target = defined.group(1)
        return (f"{what} where an object is expected: '{target}' starts with a "
                f"lowercase letter, so it names an object; a parameter name starts with an "
                f"uppercase letter: {target[0].upper() + target[1:]} = {name}(...)", start)
    return (f"{what} where an object is expected: lowercase names are objects; "
            f"a number goes into an argument, or into a parameter (its name starts with an "
            f"uppercase letter)", start)


def syntax_error(exc: UnexpectedInput, chunk: Chunk,
                  tables: Tables | None = None) -> tuple[CastorError, Chunk | None, list[Chunk]]:
    """Translate lark's exception; also return the statement given its missing ';'
    (or None) and the rest of the chunk to resume on."""
    if isinstance(exc, UnexpectedCharacters):
        char = chunk.text[exc.pos_in_stream]
        location = chunk.location(exc.line, exc.column)
        if char in "!@":
            kind = "primitive" if char == "!" else "transformation"
            message = (f"'{char}' must be followed directly by a {kind} name, "
                       f"such as {'!cu' if char == '!' else '@t'}")
        elif char == "$":
            message = "'$' must be followed directly by U, I or D"
        elif char == "#":
            message = "a preprocessor directive must start its own line"
        elif "\udc80" <= char <= "\udcff" or char == "\ufffd":
            message = "unexpected byte: the input is not UTF-8 text"
        elif not char.isprintable():
            message = f"unexpected character U+{ord(char):04X}"
        else:
            message = f"unexpected character '{char}'"
            if char == '"' or char == "'":
                message += "; the language has no strings"
        return CastorSyntaxError(message, location), None, []

    if isinstance(exc, UnexpectedEOF):
        expected = set(exc.expected)
        token = Token("$END", "")
        pos = len(chunk.text)
    else:
        assert isinstance(exc, UnexpectedToken)
        expected = _acceptable(exc)
        token = exc.token
        pos = token.start_pos if token.type != "$END" else len(chunk.text)

    at_line_start = token.type != "$END" and chunk.text[:pos].rsplit("\n", 1)[-1].strip() == "" \
        and "\n" in chunk.text[:pos]
    rest = [_rest_from(chunk, token.line, token.column)] if at_line_start else []
    if "SEMICOLON" in expected and (token.type == "$END" or at_line_start):
        # The statement ended without its ';': point at where it should be, and
        # take the statement as if it were there.
        location = _end_before(chunk, pos)
        message = f"expected ';' at the end of the statement, found {_describe_found(token)}"
        code = _code_before(chunk.text, pos)
        head = Chunk(code + ";", chunk.origins[:code.count("\n") + 1], chunk.first_column)
        return CastorSyntaxError(message, location), head, rest

    if token.type == "$END":
        location = _end_before(chunk, pos)
    else:
        location = chunk.location(token.line, token.column)
    habit = _habit(chunk, pos, token, expected, tables)
    if habit is not None:
        message, at = habit
        return CastorSyntaxError(message, at or location), None, rest
    context = ""
    if {"COMMA", "RPAR"} <= expected:
        context = " after an argument"
    elif "RSQB" in expected and "COMMA" in expected:
        context = " in the repetition"
    message = f"expected {_describe_expected(expected)}{context}, found {_describe_found(token)}"
    return CastorSyntaxError(message, location), None, rest

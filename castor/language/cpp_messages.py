"""The preprocessor's messages in castor's words: pcpp's own texts
('Unterminated #if 1', 'Misplaced #endif') reworded as castor's other messages
are, lower-case and saying what to write; and what pcpp lets pass that cpp
refuses (an #elif or a second #else after a block's #else), from each file's
open #if blocks."""

from __future__ import annotations

import re

from castor.diagnostics import PreprocessError

_CONDITION = re.compile(r"Could not evaluate expression due to .* \(passed to evaluator: '(.*)'\)",
                        re.S)
_UNTERMINATED = re.compile(r"Unterminated\s*#\s*(\w+)(.*)", re.S)
_AT_LEAST = re.compile(r"Macro (\w+) must have at least (\d+) arguments?")
_COMMENT = re.compile(r"/\*.*?\*/|//.*", re.S)

# pcpp's other messages, as castor says them
_MESSAGES = {
    "Misplaced #else": "'#else' without an '#if' before it; remove it, or add the #if it belongs to",
    "Misplaced #elif": "'#elif' without an '#if' before it; remove it, or add the #if it belongs to",
    "Misplaced #endif": "'#endif' without an '#if' before it; remove it, or add the #if it closes",
    "Missing '(' in macro arguments": "the macro's arguments have no '('; write NAME(ARGUMENTS)",
    "Missing ')' in macro arguments": "a ')' is missing at the end of the macro's arguments",
    "Empty expression": "#if or #elif needs a condition",
    "Malformed defined()": "malformed defined(); write defined(NAME)",
    "Malformed #include <...>": "malformed #include <...> (no '>'); write #include \"file.cas\"",
    "No more arguments may follow a variadic argument":
        "#define: no parameter may follow '...'; write ... last",
    "Invalid macro argument": "#define: a parameter is not a name; write #define NAME(X, Y)",
    "Bad macro definition": "malformed #define; write #define NAME VALUE or #define NAME(X, Y) VALUE",
}


def printable(name: str) -> str:
    """A name as a message shows it: control characters (a NUL byte) escaped."""
    return "".join(c if c.isprintable() else repr(c)[1:-1] for c in name)


def castor_words(msg: str, defining: bool = False) -> str:
    """One of pcpp's messages as castor says it (castor's own pass unchanged), on
    one line (pcpp's 'Unterminated' ends with the directive's newline);
    ``defining``: while pcpp reads a #define."""
    condition = _CONDITION.fullmatch(msg)
    if condition:  # not Python's exception
        return (f"#if or #elif cannot evaluate '{condition[1]}'; write a condition of "
                f"numbers, macros, defined(NAME) and C's operators")
    if defining and msg.startswith("Missing ')'"):
        return "#define: its parameters have no ')'; write #define NAME(X, Y) VALUE"
    msg = msg.strip()
    open_block = _UNTERMINATED.fullmatch(msg)
    if open_block:
        condition = " ".join(_COMMENT.sub(" ", open_block[2]).split())
        directive = f"#{open_block[1]} {condition}".strip()
        return f"'{directive}' has no matching '#endif'; add #endif where its block ends"
    at_least = _AT_LEAST.fullmatch(msg)
    if at_least:
        count = int(at_least[2])
        return (f"macro {at_least[1]} takes at least {count} argument{'s' if count != 1 else ''} "
                f"before its '...'")
    return _MESSAGES.get(msg, msg)


class Blocks:
    """Each file's open #if blocks, as the directives come (those of blocks left
    out too): for each, the line of its #else (0: none yet)."""

    def __init__(self):
        self.files: dict[str, list[int]] = {}

    def follow(self, directive, location, reporter) -> None:
        """Follow one directive (a pcpp token, at ``location``); report the error
        cpp gives for it that pcpp does not."""
        problem = self._problem(directive)
        if problem is not None:
            reporter.error(PreprocessError(problem, location))

    def _problem(self, directive) -> str | None:
        blocks = self.files.setdefault(getattr(directive, "source", None) or "", [])
        name = directive.value
        if name in ("if", "ifdef", "ifndef"):
            blocks.append(0)
        elif name == "endif" and blocks:
            blocks.pop()
        elif name in ("elif", "else") and blocks:
            if blocks[-1]:
                what = "an '#elif'" if name == "elif" else "a second '#else'"
                return (f"{what} after this block's '#else' (line {blocks[-1]}); a block has one "
                        f"#else, after its #elif")
            if name == "else":
                blocks[-1] = int(getattr(directive, "lineno", 0) or 0) or 1
        return None

    def ended(self, file: str, msg: str) -> None:
        """Where pcpp's message ``msg`` says that a block of ``file`` was left open
        at its end (one message each), that block is over."""
        if _UNTERMINATED.fullmatch(msg.strip()) and self.files.get(file):
            self.files[file].pop()

"""The faults of a macro's call, in castor's words, at the call as written: a
wrong number of arguments (pcpp says "Macro X requires 2 arguments but was
passed 1" at the line's start) and a '(' that never closes (pcpp says
nothing). Each is the one message of its statement: its place is marked as
explained (castor.diagnostics.Reporter.explained), so the parser's error
there, and the uses of the name the statement failed to define, say nothing
more. ``hooks`` is castor.language.cpp's preprocessor.
"""

from __future__ import annotations

import re

from castor.diagnostics import Location, PreprocessError


def arguments_in(text: str, start: int) -> int:
    """How many arguments the parentheses opened just before ``start`` hold (as
    many as pcpp counts: an empty pair holds one), or -1 when they do not close."""
    depth, count = 1, 1
    for char in text[start:]:
        if char == "(":
            depth += 1
        elif char == ")":
            depth -= 1
            if depth == 0:
                return count
        elif char == "," and depth == 1:
            count += 1
    return -1


def argument_count(hooks, location: Location, name: str, wanted: str, given: str):
    """The place and castor's words for a macro use with the wrong number of
    arguments: at the first use on the line with that many."""
    text = hooks.originals.line(location.file, location.line)
    column = 1
    if text is not None:
        hooks.reporter.source_lines[(location.file, location.line)] = text
        uses = [(use.start() + 1, arguments_in(text, use.end()))
                for use in re.finditer(rf"(?<![\w]){re.escape(name)}\s*\(", text)]
        column = next((c for c, n in uses if n == int(given)), uses[0][0] if uses else 1)
    return (Location(location.file, location.line, column),
            f"macro {name} takes {wanted} argument{'' if wanted == '1' else 's'}, but "
            f"{given} {'was' if given == '1' else 'were'} given")


def unclosed(hooks, paren) -> None:
    """A macro call whose '(' (the token ``paren``) has no ')' (pcpp leaves it
    unexpanded without a word): an error at the call, the one message of its
    statement (GNU cpp: "unterminated argument list invoking macro")."""
    file, line = getattr(paren, "source", None), int(getattr(paren, "lineno", 0) or 0)
    text = hooks.originals.line(file, line) if file else None
    if text is None:
        return
    with_arguments = {name for name, macro in hooks.macros.items() if macro.arglist is not None}
    for use in re.finditer(r"(?<![\w])([A-Za-z_]\w*)\s*\(", text):
        if use[1] in with_arguments and arguments_in(text, use.end()) < 0:
            location = Location(file, line, use.start() + 1)
            if location in hooks.reporter.explained:
                return  # said already (pcpp scans what follows again)
            hooks.reporter.source_lines[(file, line)] = text
            hooks.reporter.explained.add(location)
            hooks.reporter.error(PreprocessError(
                f"the call of macro {use[1]} has no closing ')'", location))
            return
